#!/usr/bin/env bash
# The picture side of issue 4's variants (thesis §6.1): each cache variant rendered with a
# static camera and compared with LDR-FLIP (`memograph diff`) against the same render
# without a cache and the same seed. A second uncached render with another seed gives the
# scale: what another noise pattern alone changes at this sample count.
#   bash tools/issue4/quality.sh         here on lavapipe (after tools/build.sh; 8 min measured),
#                                        small images; writes
#                                        docs/results/issue4_quality_lavapipe.md
#   bash bundle/quality.sh --gpu         on the GPU machine (tools/bundle_issue4.sh; about 4 min
#                                        estimated, not yet run there):
#                                        1920x1080, P = 6, L = 4 on the pipeline backend
#                                        with callables (what the tables time), the tile
#                                        cache with 4x4 tiles, subgroup and deferred fill;
#                                        writes $OUT/issue4_quality_gpu.md (the images stay
#                                        on the machine: a 1080p PFM is 25 MB)
set -euo pipefail
gpu=0
case ${1:-} in
--gpu) gpu=1 ;;
"") ;;
-h | --help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
*) echo "quality.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
esac
if [ $gpu = 1 ]; then
  m=bundle/memograph
  OUT=${OUT:-/tmp/out}
  mkdir -p "$OUT"
  out=$OUT/issue4_quality_gpu.md
  source bundle/device_env.sh
else
  cd "$(dirname "$0")/../.."
  m=${MEMOGRAPH:-build/tools/memograph}
  out=${OUT_MD:-docs/results/issue4_quality_lavapipe.md}
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$work}

rows=()
# render SCENE NAME FLAGS...: renders into $work/SCENE_NAME.pfm.
render() {
  local scene=$1 name=$2
  shift 2
  "$m" render "builtin:$scene" "$@" --out "$work/${scene}_$name.pfm" >"$work/${scene}_$name.log" 2>&1 ||
    { cat "$work/${scene}_$name.log" >&2; exit 1; }
}
# compare SCENE NAME: mean FLIP of NAME against none, and the last frame's hit rate.
compare() {
  local scene=$1 name=$2 flip hit
  flip=$("$m" diff "$work/${scene}_none.pfm" "$work/${scene}_$name.pfm" | awk '/^mean/ {print $2}')
  hit=$(grep -o '([0-9.]* %)' "$work/${scene}_$name.log" | tr -d '()' || true)
  rows+=("| $scene | $name | $flip | ${hit:-—} |")
}
# variants SCENE "NAME:FLAGS" ...: renders none, none with seed 7 and each variant with the
# scene's settings (${settings[@]}), and compares each with none.
variants() {
  local scene=$1 variant name
  shift
  render "$scene" none "${settings[@]}"
  render "$scene" none-seed7 "${settings[@]}" --seed 7
  compare "$scene" none-seed7
  for variant in "$@"; do
    name=${variant%%:*}
    # shellcheck disable=SC2086 # the flags are a list of words
    render "$scene" "$name" "${settings[@]}" ${variant#*:}
    compare "$scene" "$name"
  done
}

if [ $gpu = 1 ]; then
  # Table 6.1's size: 2^24 texels (2^20 4x4 tiles, the default entry count).
  gpuVariants=("texel:--cache texel --cache-entries 16777216"
    "texel-secondary:--cache texel --cache-entries 16777216 --cache-secondary-only"
    "tile4x4:--cache tile --tile 4x4" "tile4x4-bilinear:--cache tile --tile 4x4 --filter bilinear"
    "tile4x4-deferred:--cache tile --tile 4x4 --tile-fill deferred")
  for scene in classroom landscape; do
    settings=(--size 1920x1080 --paths 6 --bounces 4 --frames 8 --backend pipeline)
    variants "$scene" "${gpuVariants[@]}"
  done
  where="Static camera, 1920×1080, P = 6, L = 4, 8 frames, pipeline backend with callables;
texel cache 2^24 entries, tile cache 2^20 4×4 tiles"
else
  settings=(--size 160x90 --paths 4 --frames 32 --backend query)
  variants landscape "texel:--cache texel" "texel-snap:--cache texel --snap-uv" \
    "texel-bias-1:--cache texel --mip-bias -1" "texel-bias+1:--cache texel --mip-bias 1" \
    "texel-fp16:--cache texel --value-format fp16" \
    "texel-secondary:--cache texel --cache-secondary-only" \
    "tile2x2:--cache tile --tile 2x2" "tile4x2:--cache tile --tile 4x2" \
    "tile4x2-bilinear:--cache tile --tile 4x2 --filter bilinear" \
    "tile4x2-secondary:--cache tile --tile 4x2 --cache-secondary-only" \
    "tile4x4-deferred:--cache tile --tile 4x4 --tile-fill deferred"
  # The classroom's 88 materials need the pipeline backend here, where lavapipe has no
  # subgroup operations: texel variants and the deferred tile fill only.
  settings=(--size 128x72 --paths 2 --frames 16 --backend pipeline)
  variants classroom "texel:--cache texel" "texel-bias-1:--cache texel --mip-bias -1" \
    "texel-secondary:--cache texel --cache-secondary-only" \
    "tile4x4-deferred:--cache tile --tile 4x4 --tile-fill deferred"
  where="Static camera; landscape 160×90, P = 4, 32 frames, query backend; classroom 128×72,
P = 2, 16 frames, pipeline backend (callables)"
fi

device=$("$m" render --list-devices 2>/dev/null | head -1 | sed 's/^\[0\] //')
{
  echo "# Issue 4: picture quality of the cache variants ($([ $gpu = 1 ] && echo GPU || echo lavapipe))"
  echo
  echo "Generated by \`tools/issue4/quality.sh$([ $gpu = 1 ] && echo ' --gpu')\` on $device."
  echo "$where. Cache defaults otherwise ($([ $gpu = 1 ] || echo '2^20 entries,')"
  echo "D = 8, LRU, frame clock, counter read check). Mean LDR-FLIP against the same render"
  echo "without a cache, same seed (linear radiance clamped to [0, 1]): the two share most of"
  echo "their noise, so the figure is mostly what the cache changes. \`none-seed7\` is the"
  echo "uncached render with another seed, for scale: what a different noise pattern alone"
  echo "changes at this sample count. Hit rate: the last frame's."
  echo
  echo "| scene | variant | mean FLIP vs none | hit rate |"
  echo "| --- | --- | --- | --- |"
  printf '%s\n' "${rows[@]}"
} >"$out"
echo "quality.sh: wrote $out"
