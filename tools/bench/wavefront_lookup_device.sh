#!/usr/bin/env bash
# On the GPU machine, after tools/bundle_device.sh (carry bundle and .gl): where the
# wavefront's texel-cache lookup pass spends its time, and whether both architectures give
# the same picture at one seed. In one call, each step under its own time limit:
# 1. pictures: the classroom at 960x540, P = 6, L = 4, 4 frames at its static camera, seed 1,
#    without a cache and with the default texel and tile caches, megakernel and wavefront
#    (six .pfm files; compare them here with `memograph diff`);
# 2. the wavefront's floor and its frame without a cache (its binning passes), over the
#    first 40 cameras of the path, the cached runs' frames;
# 3. the wavefront with the texel cache over the first 40 cameras of the path, once with the
#    defaults and once each with one setting of the lookup changed: the frame clock (no
#    atomic clock tick per hit), the key read check (two fences a read instead of four), both,
#    and no eviction (no clock stamp written on a hit); then the default tile cache, and the
#    texel cache at twice the default entries (the hit rate a larger cache reaches).
#   bash tools/bench/wavefront_lookup_device.sh [--local] [--size WxH]
# --local runs here on lavapipe (no carried loader), e.g. --local --size 64x36, to check it.
# Results in $OUT: the .pfm files, lookup_rows.csv (one bench line a run) and lookup_log.txt.
set -uo pipefail
local=0 size=1920x1080 picture=960x540
while [ $# -gt 0 ]; do
  case $1 in
  --local) local=1; shift ;;
  --size) size=$2; picture=$2; shift 2 ;;
  *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
done
log_name=lookup_log.txt rows_name=lookup_rows.csv
source tools/bench/wavefront_device_setup.sh
step() { # limit, then the command
  local limit=$1 t0
  shift
  t0=$(date +%s)
  echo "== $*" >>"$log"
  timeout "$limit" "$@" >>"$log" 2>&1
  echo "rc=$? seconds=$(($(date +%s) - t0))" >>"$log"
}
for cache in none texel tile; do
  for shading in megakernel wavefront; do
    step 40 "$m" render builtin:classroom --backend pipeline --size "$picture" --paths 6 \
      --bounces 4 --frames 4 --seed 1 --cache "$cache" --shading "$shading" \
      --shader-cache /tmp/lookup_shaders --out "$OUT/${cache}_${shading}.pfm"
  done
done
bench() { # limit, label, then the flags
  local limit=$1 label=$2 csv=/tmp/lookup_$2.csv
  shift 2
  rm -f "$csv"
  step "$limit" "$m" bench builtin:classroom --backend pipeline --sizes "$size" --paths 6 \
    --bounces 4 --warmup 2 --shading wavefront --time-limit $((limit - 5)) --label "$label" \
    --shader-cache /tmp/lookup_shaders --csv "$csv" "$@"
  appendRow "$csv"
}
# The floor and the uncached frame over the same 40 cameras as the cached runs, so that
# "memoized ÷ floor" and the speed-up over no cache compare the same frames.
bench 30 floor --frames 40 --camera-frames 300 --floor-materials
bench 30 no_cache --frames 40 --camera-frames 300
for variant in default "--clock frame" "--cache-read-check key" \
  "--clock frame --cache-read-check key" "--eviction none"; do
  label=$(echo "texel $variant" | tr -c 'a-z0-9\n' '_' | tr -s _)
  # shellcheck disable=SC2086 # the variant is its flags
  bench 30 "$label" --frames 40 --camera-frames 300 --cache texel \
    $([ "$variant" = default ] || echo $variant)
done
bench 30 tile_default --frames 40 --camera-frames 300 --cache tile
bench 30 texel_entries_2_25 --frames 40 --camera-frames 300 --cache texel --cache-entries 33554432
grep -E "^==|median|passes|cache texel|rc=" "$log" | cut -c1-300
