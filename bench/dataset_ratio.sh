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
measure() {  # render a dataset; print "wall cpu" seconds (cpu = user + system of the process)
  local TIMEFORMAT='%R %U %S' t
  t=$( { time "$bin" dataset "$work/$1.json" -o "$work/$1" >/dev/null 2>&1; } 2>&1 )
  awk '{ printf "%s %.3f\n", $1, $2 + $3 }' <<<"$t"
}
spec rgb false
spec all true
read -r rgb rgbCpu <<<"$(measure rgb)"
read -r all allCpu <<<"$(measure all)"
awk -v r="$rgb" -v a="$all" -v rc="$rgbCpu" -v ac="$allCpu" -v n="$frames" 'BEGIN {
  printf "dataset of robocup2006, %d frames, 360x360, 1 spp, fast engine (wall / CPU seconds)\n", n
  printf "RGB only:                 %6.2f s wall  %6.2f s CPU  %6.1f frames/s\n", r, rc, n / r
  printf "RGB + every output:       %6.2f s wall  %6.2f s CPU  %6.1f frames/s\n", a, ac, n / a
  printf "ratio: every output costs %.2fx RGB only in wall time, %.2fx in CPU time\n", a / r, ac / rc
}'
