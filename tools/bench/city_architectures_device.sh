#!/usr/bin/env bash
# The city on the GPU machine for both architectures (docs/results.md, "The city in both
# architectures"): builtin:city at SIZE (default 1920x1080), P = 6, L = 4, every STRIDE-th
# camera of its 360-camera street path (default 18: 20 cameras), for {wavefront, megakernel}
# x {none, frustum, lipac}, then the wavefront with LiPaC on the free-material floor and with
# mesh LODs. One bench line each (city_bench.csv: median frame, peak and median AS bytes).
# Then the mirror: camera 153 of the path (84 m from the mirror, facing it) accumulated over
# FRAMES_MIRROR frames (default 32) at 960x540, seed 1, unculled and LiPaC in the wavefront,
# and their mean LDR-FLIP (mirror.txt). SCENE=builtin:city:path=aerial runs the aerial path, its
# mirror camera 135.
# After tools/bundle_device.sh, on the GPU machine (carry bundle and .gl):
#   OUT=$OUT bash tools/bench/city_architectures_device.sh
set -uo pipefail
[ -n "${MEMOGRAPH:-}" ] || source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=${MEMOGRAPH:-bundle/memograph}
size=${SIZE:-1920x1080}
stride=${STRIDE:-18}
limit=${LIMIT:-90}
scene=${SCENE:-builtin:city}
work=$(mktemp -d)
sc="$work/shader_cache"
append_csv() {
  [ -f "$1" ] || return 0
  if [ -s "$2" ]; then tail -n +2 "$1" >>"$2"; else cat "$1" >"$2"; fi
}
run() {
  local label=$1
  shift
  echo "== $label: $*" | tee -a "$OUT/city_log.txt"
  timeout "$limit" "$m" bench "$scene" --sizes "$size" --paths 6 --bounces 4 --warmup 0 \
    --frames $((360 / stride)) --camera-frames 360 --frame-stride "$stride" \
    --time-limit $((limit - 15)) --label "$label" --shader-cache "$sc" \
    --csv "$work/$label.csv" "$@" 2>&1 | tail -6 >>"$OUT/city_log.txt"
  echo "rc=${PIPESTATUS[0]}" >>"$OUT/city_log.txt"
  append_csv "$work/$label.csv" "$OUT/city_bench.csv"
}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/city_env.txt" 2>&1
for arch in wavefront megakernel; do
  for mode in none frustum lipac; do
    run "${arch}_$mode" --shading "$arch" --culling "$mode"
  done
done
run wavefront_lipac_floor --shading wavefront --culling lipac --floor-materials
run wavefront_lipac_lods --shading wavefront --culling lipac --mesh-lods on
run megakernel_lipac_lods --shading megakernel --culling lipac --mesh-lods on

campath=examples/camera_paths/city.campath
mirror_camera=153
case $scene in
*path=aerial*) campath=examples/camera_paths/city_aerial.campath mirror_camera=135 ;;
esac
camera=$(grep -v '^#' "$campath" | grep . | sed -n "$((mirror_camera + 1))p")
for _ in $(seq 1 "${FRAMES_MIRROR:-32}"); do echo "$camera"; done >"$work/mirror.campath"
for mode in none lipac; do
  timeout 60 "$m" render "$scene" --shading wavefront --culling "$mode" --size 960x540 \
    --paths 6 --bounces 4 --frames "${FRAMES_MIRROR:-32}" --camera-path "$work/mirror.campath" \
    --seed 1 --shader-cache "$sc" --out "$work/mirror_$mode.pfm" >>"$OUT/city_log.txt" 2>&1
done
"$m" diff "$work/mirror_none.pfm" "$work/mirror_lipac.pfm" >"$OUT/mirror.txt" 2>&1
cat "$OUT/mirror.txt"
