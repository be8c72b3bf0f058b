#!/usr/bin/env bash
# On the GPU machine, after tools/bundle_device.sh (carry bundle and .gl): the wavefront's
# figures against the megakernel's (docs/results.md, "Wavefront against megakernel"). In one call, each step
# under its own time limit:
# 1. pictures of the classroom at its static camera, 960x540, P = 6, L = 4, seed 1, compared
#    on the device with `memograph diff` (pictures.txt):
#    - 4 frames without a cache, and with the texel cache with --snap-uv (a texel's value
#      then depends only on its key, not on which hit stored it first): megakernel against
#      wavefront at one seed;
#    - 64 frames (384 paths a pixel) with the default texel and tile caches, megakernel
#      against wavefront (a cached value that some hit stored first differs by thread order,
#      and a path that meets it turns elsewhere, so at one seed the two trace other noise),
#      beside the uncached wavefront at seeds 1 and 2: the noise left at that count;
# 2. benches at 1920x1080 over the first 40 cameras of each path, one after another (a cached
#    frame depends on the frames before it), the floor and the uncached frame over the same
#    cameras: the classroom in the wavefront (floor, no cache, texel cache, texel cache with
#    the frame clock, tile cache) and in the megakernel (floor, texel, tile), the landscape in
#    the wavefront (floor, no cache, texel, tile).
#   bash tools/bench/wavefront_lookup_device.sh [--local] [--size WxH] [--frames N]
#     [--against BINARY | --whole-path]
# --local runs here on lavapipe (no carried loader), e.g. --local --size 64x36 --frames 2, to
# check it. --against BINARY measures a change of the lookup instead, in one call: the
# 4-frame pictures of step 1, then the wavefront's cached benches of step 2 with BINARY (rows
# labelled _before) and this binary, interleaved (before, after, before, after on the
# classroom) so that a drift of the machine shows, with the floor and the uncached frame.
# --whole-path: only the wavefront's benches, over the whole 300-camera path of each scene
# (floor, no cache, the default texel and tile caches; no pictures). Results in $OUT: pictures.txt, lookup_rows.csv (one bench line a run) and
# lookup_log.txt.
set -uo pipefail
local=0 size=1920x1080 picture=960x540 converged=64 against= whole=0
while [ $# -gt 0 ]; do
  case $1 in
  --local) local=1; shift ;;
  --against) against=$2; shift 2 ;;
  --whole-path) whole=1; shift ;;
  --size) size=$2; picture=$2; shift 2 ;;
  --frames) converged=$2; shift 2 ;;
  *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
done
log_name=lookup_log.txt rows_name=lookup_rows.csv
source tools/bench/wavefront_device_setup.sh
work=$(mktemp -d)
step() { # limit, then the command
  local limit=$1 t0
  shift
  t0=$(date +%s)
  echo "== $*" >>"$log"
  timeout "$limit" "$@" >>"$log" 2>&1
  echo "rc=$? seconds=$(($(date +%s) - t0))" >>"$log"
}
picture() { # name, frames, then the flags
  local name=$1 frames=$2
  shift 2
  step 40 "$m" render builtin:classroom --backend pipeline --size "$picture" --paths 6 \
    --bounces 4 --frames "$frames" --shader-cache /tmp/lookup_shaders --out "$work/$name.pfm" "$@"
}
compare() { # title, two picture names
  echo "== $1: $3 against $2" >>"$OUT/pictures.txt"
  "$m" diff "$work/$2.pfm" "$work/$3.pfm" >>"$OUT/pictures.txt" 2>&1
}
bench() { # limit, scene, label, then the flags
  local limit=$1 scene=$2 label=$3 csv=/tmp/lookup_$2_$3.csv
  shift 3
  rm -f "$csv"
  step "$limit" "$m" bench "builtin:$scene" --backend pipeline --sizes "$size" --paths 6 \
    --bounces 4 --warmup 2 --time-limit $((limit - 5)) --label "$label" \
    --shader-cache "/tmp/lookup_shaders$shaders" --csv "$csv" --frames "$frames" \
    --camera-frames 300 "$@"
  appendRow "$csv"
}
# The end of every mode: the summary of what it measured.
finish() {
  rm -rf "$work"
  grep -E "^==|median|passes|cache t|stopped|rc=" "$log" | cut -c1-300
  [ ! -f "$OUT/pictures.txt" ] || grep -E "^==|mean" "$OUT/pictures.txt"
  exit 0
}
shaders= frames=40
if [ "$whole" = 1 ]; then
  frames=300
  for scene in classroom landscape; do
    bench 60 "$scene" floor --shading wavefront --floor-materials
    bench 70 "$scene" no_cache --shading wavefront
    bench 60 "$scene" texel --shading wavefront --cache texel
    bench 60 "$scene" tile --shading wavefront --cache tile
  done
  finish
fi
for shading in megakernel wavefront; do
  picture "none_$shading" 4 --seed 1 --shading "$shading"
  picture "snap_$shading" 4 --seed 1 --shading "$shading" --cache texel --snap-uv
done
compare "4 frames, seed 1, no cache" none_megakernel none_wavefront
compare "4 frames, seed 1, texel cache --snap-uv" snap_megakernel snap_wavefront
if [ -n "$against" ]; then
  after=$m
  # before/after: the binary `m` is, and its own shader cache.
  side() { if [ "$1" = before ]; then m=$against shaders=_before; else m=$after shaders=; fi; }
  before_after() { # limit, scene, rounds: each cache's benches, before then after, per round
    local limit=$1 scene=$2 rounds=$3 cache round which suffix
    for cache in texel tile; do
      for round in $(seq "$rounds"); do
        suffix=$([ "$rounds" = 1 ] || echo "_$round")
        for which in before after; do
          side "$which"
          bench "$limit" "$scene" "${cache}_$which$suffix" --shading wavefront --cache "$cache"
        done
      done
    done
    side after
  }
  bench 30 classroom floor --shading wavefront --floor-materials
  bench 30 classroom no_cache --shading wavefront
  before_after 35 classroom 2
  bench 25 landscape floor --shading wavefront --floor-materials
  before_after 25 landscape 1
  finish
fi
for cache in texel tile; do
  for shading in megakernel wavefront; do
    picture "${cache}_${shading}_converged" "$converged" --seed 1 --shading "$shading" \
      --cache "$cache"
  done
  compare "$converged frames, seed 1, $cache cache" "${cache}_megakernel_converged" \
    "${cache}_wavefront_converged"
done
for seed in 1 2; do
  picture "none_wavefront_seed$seed" "$converged" --seed "$seed" --shading wavefront
done
compare "$converged frames, no cache, wavefront: the noise" none_wavefront_seed1 \
  none_wavefront_seed2
compare "$converged frames, wavefront: texel cache against none" none_wavefront_seed1 \
  texel_wavefront_converged
bench 30 classroom floor --shading wavefront --floor-materials
bench 30 classroom no_cache --shading wavefront
bench 30 classroom texel --shading wavefront --cache texel
bench 30 classroom texel_clock_frame --shading wavefront --cache texel --clock frame
bench 35 classroom tile --shading wavefront --cache tile
bench 30 classroom megakernel_floor --shading megakernel --floor-materials
bench 35 classroom megakernel_texel --shading megakernel --cache texel
bench 40 classroom megakernel_tile --shading megakernel --cache tile
bench 25 landscape floor --shading wavefront --floor-materials
bench 25 landscape no_cache --shading wavefront
bench 25 landscape texel --shading wavefront --cache texel
bench 25 landscape tile --shading wavefront --cache tile
finish
