#!/usr/bin/env bash
# Runs one libFuzzer target for N seconds from its seed corpus (never writing into the repository).
#   fuzz/run_fuzzer.sh BUILD/bin/fuzz_TARGET SECONDS TARGET
# A crash leaves its input in out/fuzz-crashes/TARGET/ (add it to fuzz/regressions/TARGET/ once
# fixed) and fails. The last line is "fuzz TARGET: N runs in S s, 0 crashes" or says what failed.
# FUZZ_EXTRA_ARGS: more libFuzzer flags, e.g. "-fork=1 -ignore_crashes=1" to keep fuzzing past
# a known crash (every crash still lands in out/fuzz-crashes/TARGET/ and fails the run);
# FUZZ_LOG: a file for libFuzzer's own log, kept (default: a temporary one, removed).
set -uo pipefail
binary=$1 seconds=$2 target=$3
repo=$(cd "$(dirname "$0")/.." && pwd)
if [ ! -x "$binary" ]; then
  echo "fuzz $target: missing $binary — build it with 'make fuzz-build' (make test and make fuzz do)" >&2
  exit 1
fi
seeds=("$repo/fuzz/seeds/$target" "$repo/fuzz/regressions/$target")
case $target in
  scene_loader) seeds+=("$repo/scenes" "$repo/tests/bad_inputs") ;;
  gltf_import) seeds+=("$repo/fuzz/assets" "$repo/tests/bad_inputs/scenes") ;;
  dataset_spec) seeds+=("$repo/tests/bad_inputs/datasets") ;;
  manifest | shard_manifest) seeds+=("$repo/tests/bad_inputs/manifests") ;;
esac
# A dictionary (JSON tokens and field names) where the target has one.
dict=()
[ -f "$repo/fuzz/dictionaries/$target.dict" ] && dict=(-dict="$repo/fuzz/dictionaries/$target.dict")
work=$(mktemp -d "${TMPDIR:-/tmp}/omnicam-fuzz-$target-XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus" "$work/crashes"
existing=()
for s in "${seeds[@]}"; do [ -d "$s" ] && existing+=("$s"); done
log=${FUZZ_LOG:-$work/fuzz.log}  # FUZZ_LOG: keep libFuzzer's own log there (long runs)
# Leak reports from third-party static caches are not findings: leaks off, every other check on.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  "$binary" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 \
  "${dict[@]}" ${FUZZ_EXTRA_ARGS:-} -artifact_prefix="$work/crashes/" "$work/corpus" "${existing[@]}" >"$log" 2>&1
status=$?
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
# -fork: no final stats; the last status line "#N: cov: ..." counts every job's executions.
[ -n "$runs" ] || runs=$(grep -o '^#[0-9]*: cov:' "$log" | tail -n 1 | grep -o '[0-9]*')
if [ $status -ne 0 ] || [ -n "$(ls -A "$work/crashes")" ]; then
  mkdir -p "$repo/out/fuzz-crashes/$target"
  cp "$work"/crashes/* "$repo/out/fuzz-crashes/$target/" 2>/dev/null
  tail -n 40 "$log" >&2
  echo "fuzz $target: FAILED (exit $status); inputs in out/fuzz-crashes/$target/" >&2
  exit 1
fi
echo "fuzz $target: ${runs:-0} runs in $seconds s, 0 crashes"
