#!/usr/bin/env bash
# What the dataset outputs cost: a FRAMES-frame fast dataset of robocup2006 (360x360, 1 spp,
# random poses) with RGB + depth + instance + semantic + normals + landmarks, against the same
# frames with RGB only; whole-process wall time of `omnicam dataset`, both runs in one go.
# Usage: bench/dataset_ratio.sh [FRAMES]   (default 1000)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-1000}
bin=build/bin/omnicam
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
spec() {  # spec with the given outputs switch (true: everything, false: RGB only)
  cat > "$work/$1.json" <<JSON
{"format": "omnicam-dataset/1", "scene": "$PWD/scenes/robocup2006.json", "spp": 1, "size": 360,
 "poses": {"random": {"count": $frames, "seed": 1, "region": [-2.7, -1.8, 2.7, 1.8], "clearance": 0.1}},
 "outputs": {"rgb": "png", "depth": $2, "instance": $2, "semantic": $2, "normal": $2, "landmarks": $2}}
JSON
}
seconds() {  # render a dataset, print its wall time in seconds
  local start end
  start=$(date +%s.%N)
  "$bin" dataset "$work/$1.json" -o "$work/$1" >/dev/null 2>&1
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l
}
spec rgb false
spec all true
rgb=$(seconds rgb)
all=$(seconds all)
awk -v r="$rgb" -v a="$all" -v n="$frames" 'BEGIN {
  printf "dataset of robocup2006, %d frames, 360x360, 1 spp, fast engine\n", n
  printf "RGB only:          %6.2f s  %6.1f frames/s\n", r, n / r
  printf "RGB + depth, instance, semantic, normal, landmarks: %6.2f s  %6.1f frames/s\n", a, n / a
  printf "ratio: all outputs cost %.2fx RGB only\n", a / r
}'
