#!/usr/bin/env bash
# What the dataset outputs cost, in both layouts: a FRAMES-frame fast dataset of robocup2006
# (360x360, 1 spp, random poses) with every output (RGB, depth, instance, semantic, normals,
# landmarks, COCO) against the same frames with RGB only, one file per output ("files") and one
# OpenEXR per frame ("multilayer", RLE; "multilayer-zip"); whole-process wall and CPU time of
# `omnicam dataset`, all six runs in one go.
# Usage: bench/dataset_ratio.sh [FRAMES]   (default 1000)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-1000}
bin=build/bin/omnicam
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
spec() {  # spec NAME LAYOUT EVERYTHING(true/false); LAYOUT multilayer-zip: multilayer, zip-compressed
  local layout=$2 extra=""
  if [ "$layout" = multilayer-zip ]; then layout=multilayer extra='"multilayer_compression": "zip",'; fi
  cat > "$work/$1.json" <<JSON
{"format": "omnicam-dataset/1", "scene": "$PWD/scenes/robocup2006.json", "spp": 1, "size": 360, "layout": "$layout", $extra
 "poses": {"random": {"count": $frames, "seed": 1, "region": [-2.7, -1.8, 2.7, 1.8], "clearance": 0.1}},
 "outputs": {"depth": $3, "instance": $3, "semantic": $3, "normal": $3, "landmarks": $3, "coco": $3}}
JSON
}
measure() {  # render a dataset; print "wall cpu MB" (cpu = user + system of the process)
  local TIMEFORMAT='%R %U %S' t
  t=$( { time "$bin" dataset "$work/$1.json" -o "$work/$1" >/dev/null 2>&1; } 2>&1 )
  awk -v mb="$(du -sm "$work/$1" | cut -f1)" '{ printf "%s %.3f %s\n", $1, $2 + $3, mb }' <<<"$t"
  rm -rf "${work:?}/$1"
}
echo "dataset of robocup2006, $frames frames, 360x360, 1 spp, fast engine"
printf '%-15s %-14s %9s %9s %9s %8s\n' layout outputs "wall s" "CPU s" frames/s MB
for layout in files multilayer multilayer-zip; do
  spec "$layout-rgb" "$layout" false
  spec "$layout-all" "$layout" true
  read -r rgb rgbCpu rgbMb <<<"$(measure "$layout-rgb")"
  read -r all allCpu allMb <<<"$(measure "$layout-all")"
  awk -v l="$layout" -v r="$rgb" -v a="$all" -v rc="$rgbCpu" -v ac="$allCpu" -v n="$frames" -v rm="$rgbMb" -v am="$allMb" 'BEGIN {
    printf "%-15s %-14s %9.2f %9.2f %9.1f %8d\n", l, "RGB only", r, rc, n / r, rm
    printf "%-15s %-14s %9.2f %9.2f %9.1f %8d\n", l, "every output", a, ac, n / a, am
    printf "%-15s every output costs %.2fx RGB only in wall time, %.2fx in CPU time\n", l, a / r, ac / rc
  }'
done
