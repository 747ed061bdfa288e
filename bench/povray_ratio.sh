#!/usr/bin/env bash
# Fast renderer vs POV-Ray, per frame, over the 100-frame thesis-loop of robocup2006 at equal
# spp, measured in one run (whole-process wall time, both writing PNG frames + sidecars).
# Usage: bench/povray_ratio.sh [SPP] [FRAMES]   (defaults: 1 100)
set -euo pipefail
cd "$(dirname "$0")/.."
spp=${1:-1}
frames=${2:-100}
bin=build/bin/omnicam
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
seconds() {  # run a render, print its wall time in seconds
  local start end
  start=$(date +%s.%N)
  "$bin" render scenes/robocup2006.json --path thesis-loop --frames "$frames" --spp "$spp" --engine "$1" \
    -o "$work/$1" >/dev/null 2>&1
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
fast=$(seconds fast)
povray=$(seconds povray)
awk -v f="$fast" -v p="$povray" -v n="$frames" -v s="$spp" 'BEGIN {
  printf "thesis-loop, %d frames, 360x360, %d spp, unlit\n", n, s
  printf "fast:   %8.2f ms/frame (%.1f frames/s)\n", 1000 * f / n, n / f
  printf "povray: %8.2f ms/frame (%.2f frames/s)\n", 1000 * p / n, n / p
  printf "ratio:  fast is %.0fx faster than POV-Ray per frame\n", p / f
}'
