#!/usr/bin/env bash
# On the GPU machine, after tools/bundle_ab.sh: the same bench row for bundle/memograph and for
# every bundle/ab/<rev>/memograph, alternated (A B A B ...) for each scene in one call, so that
# their frame times compare on one GPU with its drift spread over both. Each row is a scene at
# 1920x1080, P = 6, L = 4 over the first --frames cameras of its built-in path, at the
# defaults unless bench flags follow. The scene `pack` is the Blender material scene's pack
# (bundle/material_scene.mgpack, tools/bundle_ab.sh --material-scene) over its own camera
# path. --local runs here (no carried Vulkan loader), e.g.
#   bash tools/bench/ab_device.sh --local --scenes landscape --size 32x18 --frames 2
# on lavapipe to check the script.
#   bash tools/bench/ab_device.sh [--local] [--scenes "S ..."] [--size WxH] [--frames N]
#                                 [--rounds R] [--limit S] [bench flags...]
# Results in $OUT: ab_log.txt (each run's summary) and ab_rows.csv (one bench line a run,
# labelled <rev>-<scene>-<round>).
set -uo pipefail
frames=150 limit=90 scenes=classroom size=1920x1080 local=0 rounds=1
while [ $# -gt 0 ]; do
  case $1 in
  --local) local=1; shift ;;
  --scene | --scenes) scenes=$2; shift 2 ;;
  --size) size=$2; shift 2 ;;
  --frames) frames=$2; shift 2 ;;
  --rounds) rounds=$2; shift 2 ;;
  --limit) limit=$2; shift 2 ;;
  *) break ;;
  esac
done
[ $local = 1 ] || source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
flags=("$@")
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/ab_env.txt" 2>&1 || true
# A second run in the same call appends to ab_rows.csv under the header already there.
first=1
[ -s "$OUT/ab_rows.csv" ] && first=0
pack=bundle/material_scene.mgpack
for scene in $scenes; do
  # A built-in scene's path is 300 cameras long; the pack brings its own.
  spec=("builtin:$scene" --camera-frames 300)
  if [ "$scene" = pack ]; then
    [ -f $pack ] ||
      { echo "ab_device: no $pack (tools/bundle_ab.sh --material-scene)" >&2; exit 2; }
    spec=($pack)
  fi
  for round in $(seq 1 "$rounds"); do
    for m in bundle/memograph bundle/ab/*/memograph; do
      [ -x "$m" ] || continue
      dir=$(dirname "$m")
      rev=$(cut -d' ' -f1 "$dir/VERSION" 2>/dev/null || basename "$dir")
      label="$rev-$scene-$round"
      echo "== $label ($(cat "$dir/VERSION" 2>/dev/null)): ${flags[*]}" | tee -a "$OUT/ab_log.txt"
      timeout "$limit" "$m" bench "${spec[@]}" --sizes "$size" --paths 6 --bounces 4 \
        --warmup 2 --frames "$frames" --time-limit $((limit - 10)) \
        --shader-cache "/tmp/ab_shaders_$rev" --label "$label" --csv "/tmp/ab_$label.csv" \
        "${flags[@]}" 2>&1 | tail -6 | tee -a "$OUT/ab_log.txt"
      if [ $first = 1 ]; then cat "/tmp/ab_$label.csv"; first=0; else tail -n +2 "/tmp/ab_$label.csv"; fi \
        >>"$OUT/ab_rows.csv" 2>/dev/null
    done
  done
done
