#!/usr/bin/env bash
# The city on the GPU machine for both architectures (docs/results.md, "The city in both
# architectures"): builtin:city at SIZE (default 1920x1080), P = 6, L = 4, every STRIDE-th
# camera of its 360-camera street path (default 18: 20 cameras), for {wavefront, megakernel}
# x {none, frustum, lipac}, then the wavefront with LiPaC on the free-material floor and with
# mesh LODs. One bench line each (city_bench.csv: median frame, peak and median AS bytes).
# Then the mirror: camera 153 of the path (84 m from the mirror, facing it), after the 8
# cameras before it, accumulated over FRAMES_MIRROR frames (default 32) at 960x540, seed 1,
# in the wavefront unculled, with LiPaC and with LiPaC and mesh LODs; the LDR-FLIP of each
# culled picture against the unculled one (mirror.txt). SCENE=builtin:city:path=aerial runs the aerial path, its
# mirror camera 135.
# After tools/bundle_device.sh, on the GPU machine (carry bundle and .gl):
#   OUT=$OUT bash tools/bench/city_architectures_device.sh
# LOD_FLAGS (for example "--lod-pixel-error 0.25") go to every run with mesh LODs.
# STEPS="bench" or STEPS="mirror" runs one step; MIRROR_SIZE sets the mirror's size. To check
# the script here on lavapipe (figures meaningless), with the small city and its own path:
#   build/tests/runtime/scene/builtin/scenes_write_camera_paths /tmp/paths 360 0.02
#   MEMOGRAPH=build/tools/memograph SCENE=builtin:city:scale=0.02 CAMPATH=/tmp/paths/city.campath
#   STEPS=mirror MIRROR_SIZE=32x18 FRAMES_MIRROR=2 OUT=/tmp/city bash tools/bench/city_architectures_device.sh
set -uo pipefail
[ -n "${MEMOGRAPH:-}" ] || source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=${MEMOGRAPH:-bundle/memograph}
size=${SIZE:-1920x1080}
# The megakernel takes about 1.2 s a frame of the city on an H100, the wavefront 70 ms: the
# megakernel's rows may take every STRIDE_MEGAKERNEL-th camera instead (default STRIDE).
stride=${STRIDE:-18}
stride_megakernel=${STRIDE_MEGAKERNEL:-$stride}
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
  local stride=$stride
  [[ $label != megakernel* ]] || stride=$stride_megakernel
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
steps=" ${STEPS:-bench mirror} "
if [[ $steps == *" bench "* ]]; then
for arch in wavefront megakernel; do
  for mode in none frustum lipac; do
    run "${arch}_$mode" --shading "$arch" --culling "$mode"
  done
done
run wavefront_lipac_floor --shading wavefront --culling lipac --floor-materials
# shellcheck disable=SC2086 # LOD_FLAGS is a list of flags
run wavefront_lipac_lods --shading wavefront --culling lipac --mesh-lods on ${LOD_FLAGS:-}
# shellcheck disable=SC2086
run megakernel_lipac_lods --shading megakernel --culling lipac --mesh-lods on ${LOD_FLAGS:-}
fi
[[ $steps == *" mirror "* ]] || exit 0

campath=examples/camera_paths/city.campath
mirror_camera=153
case $scene in
*path=aerial*) campath=examples/camera_paths/city_aerial.campath mirror_camera=135 ;;
esac
campath=${CAMPATH:-$campath}
mapfile -t cameras < <(grep -v '^#' "$campath" | grep .)
# LiPaC learns what a camera sees from the frames before it, as on the path: the 8 cameras
# before the mirror camera, then FRAMES_MIRROR frames at it (the image accumulates those).
frames_mirror=${FRAMES_MIRROR:-32}
printf '%s\n' "${cameras[@]:mirror_camera-8:8}" >"$work/mirror.campath"
for _ in $(seq 1 "$frames_mirror"); do echo "${cameras[mirror_camera]}"; done >>"$work/mirror.campath"
mirror_run() {
  local label=$1
  shift
  timeout 90 "$m" render "$scene" --shading wavefront --size "${MIRROR_SIZE:-960x540}" --paths 6 --bounces 4 \
    --frames $((frames_mirror + 8)) --camera-path "$work/mirror.campath" --seed 1 \
    --shader-cache "$sc" --out "$work/mirror_$label.pfm" "$@" >>"$OUT/city_log.txt" 2>&1
}
mirror_run none --culling none
mirror_run lipac --culling lipac
# shellcheck disable=SC2086 # LOD_FLAGS is a list of flags
mirror_run lipac_lods --culling lipac --mesh-lods on ${LOD_FLAGS:-}
for label in lipac lipac_lods; do
  echo "== mirror camera $mirror_camera: $label against none" >>"$OUT/mirror.txt"
  "$m" diff "$work/mirror_none.pfm" "$work/mirror_$label.pfm" >>"$OUT/mirror.txt" 2>&1
done
cat "$OUT/mirror.txt"
