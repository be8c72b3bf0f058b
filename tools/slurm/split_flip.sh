#!/usr/bin/env bash
# How close a cached render split over jobs comes to one run (docs/guide/slurm.md): renders
# frames 0..2S-1 of a camera path in one run, then frames S..2S-1 alone after each number of
# --warmup-frames, and prints the mean LDR-FLIP (memograph diff) of the split frames
# against the unsplit ones; a second unsplit run gives the noise floor of the device.
#   bash tools/slurm/split_flip.sh [MEMOGRAPH] [render options...]
# Environment: SPLIT (S, default 8), WARMUPS (default "0 2 4 8"), SCENE, CAMERA_PATH, SIZE
# (default 64x36), STATE (the options that carry state from frame to frame; default
# "--cache texel --cache-entries 65536").
set -euo pipefail
memograph=${1:-build/tools/memograph}
shift || true
root=$(cd "$(dirname "$0")/../.." && pwd)
split=${SPLIT:-8}
warmups=${WARMUPS:-0 2 4 8}
scene=${SCENE:-builtin:landscape:terrain=2}
path=${CAMERA_PATH:-$root/examples/camera_paths/landscape.campath}
read -r -a state <<<"${STATE:---cache texel --cache-entries 65536}"
options=(--camera-path "$path" --size "${SIZE:-64x36}" --paths 2 --bounces 2 "${state[@]}" "$@")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
last=$((2 * split - 1))

render() {  # FOLDER RANGE [options]
  local folder=$1 range=$2
  shift 2
  mkdir -p "$work/$folder"
  "$memograph" render "$scene" "${options[@]}" --frame-range "$range" \
    --out "$work/$folder/frame_####.pfm" "$@" 2>/dev/null
}

mean_flip() {  # FOLDER: the mean over frames S..2S-1 of their mean FLIP against "whole"
  local folder=$1 sum=0 f value
  for f in $(seq "$split" "$last"); do
    value=$("$memograph" diff "$work/whole/$(printf 'frame_%04d.pfm' "$f")" \
      "$work/$folder/$(printf 'frame_%04d.pfm' "$f")" | sed -n 's/^mean[^0-9]*\([0-9.e+-]*\).*/\1/p')
    sum=$(python3 -c "print($sum + $value)")
  done
  python3 -c "print('%.5f' % (($sum) / $split))"
}

render whole "0:$last"
render again "0:$last"
echo "unsplit against another unsplit run: mean FLIP $(mean_flip again)"
for warmup in $warmups; do
  render "warm$warmup" "$split:$last" --warmup-frames "$warmup"
  echo "frames $split..$last alone after $warmup warm-up frames: mean FLIP $(mean_flip "warm$warmup")"
done
