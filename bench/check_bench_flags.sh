#!/bin/sh
# ctest BenchFlags.HelpAndBadFlagsStartNoRun: the benchmarks that are programs of their own read
# their flags before any work. --help prints the usage (exit 0); a flag they do not know, one
# given twice, or a value that is not its integer exits 2 with the usage; none of these writes a
# file in the working folder (path_dataset_rate once took `--help` for its cache folder). Google
# Benchmark's programs exit 2 on a flag they do not know.
# Usage: check_bench_flags.sh PATH_DATASET_RATE SCENE_SCALING SLURM_SPEEDUP PATH_VS_CYCLES ROS_LATENCY DATASET_BENCH OMNICAM_BENCH
set -u
work=$(mktemp -d)
cd "$work" || exit 1
fail() { echo "FAIL: $*"; cat out 2>/dev/null; exit 1; }
# expect CODE PATTERN PROGRAM ARGS...: PROGRAM ARGS exits CODE and its output holds PATTERN.
expect() {
  want=$1 pattern=$2
  shift 2
  "$@" >out 2>&1
  got=$?
  [ "$got" = "$want" ] || fail "$* exited $got, not $want"
  grep -q -- "$pattern" out || fail "$*: no \"$pattern\" in its output"
}
for program in "$1" "$2" "$3" "$4" "$5"; do
  expect 0 '^usage: ' "$program" --help
  expect 2 '^usage: ' "$program" --no-such-flag
done
expect 2 'must be an integer in' "$3" --frames ten
expect 2 'given twice' "$3" --frames=2 --frames 3
expect 2 'needs a value' "$3" --frames
for program in "$6" "$7"; do
  expect 2 'unrecognized command-line flag' "$program" --no-such-flag
done
rm -f out
cd / && rmdir "$work" || fail "files written in the working folder: $(ls -A "$work")"
echo "benchmark flags: ok"
