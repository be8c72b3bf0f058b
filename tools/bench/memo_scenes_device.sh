#!/usr/bin/env bash
# On the GPU machine, after tools/bundle_memo_scenes.sh (carry bundle and .gl): the
# memoization table of the material scenes for the packed Blender material scene
# (bundle/material_scene.mgpack), builtin:landscape and builtin:classroom. Per scene,
# along its camera path at 1920x1080, P = 6, L = 4: no cache on both architectures
# (megakernel, wavefront), the free-material floor (--floor-materials), the texel cache
# (its cuts keyed by the key domain the compiler chose per material: uv, object or world; on
# the Blender scene also with one domain at a time) on the wavefront and, for scenes of at most 16 graphs, on the megakernel's switch dispatch;
# and the tile cache (whole uv-only graphs). Each bench line gives the frame time, the hit
# rate and the cached share of the estimated material cost by domain; served = cached share
# x hit rate. Then the converged picture at a reduced, stated sample count (static camera,
# --quality-size, P = 6, --quality-frames frames): the texel-cached render against the
# uncached one at the same seed (mean LDR-FLIP; bias: the 8x8-block mean absolute error and
# the image means), and the uncached render with another seed against it for scale
# (seed-to-seed noise). Every step has its own time limit, cut to what is left of --budget
# seconds (default 540, under the device call's 600; a step with less than 15 s left is
# skipped and its row says so); the default run takes about 300-400 s on an H100 (cold
# pipeline creation about 7 s a process, reused via --shader-cache).
#   bash tools/bench/memo_scenes_device.sh [--local] [--size WxH] [--frames N] [--warmup N]
#        [--quality-size WxH] [--quality-frames N] [--scenes "pack classroom landscape"]
#        [--pack FILE] [--camera FILE] [--limit-scale K] [--budget S] [--runs "NAME..."]
#        [--quality-shading megakernel|wavefront] [--variants "NAME..."] [--keep-pictures]
# --local runs here (no carried Vulkan loader; MEMOGRAPH, default build/tools/memograph; every
# time limit x 10 unless --limit-scale says), e.g. on lavapipe: --local --size 64x36
# --frames 2 --quality-size 32x18 --quality-frames 2 --scenes "pack landscape"
# --pack scene.mgpack --camera examples/blender/material_scene.camera. --runs: only these
# bench runs (floor none-megakernel none-wavefront texel-wavefront texel-wavefront-uv
# texel-wavefront-object texel-wavefront-world (the pack only: one key domain each,
# --cache-keys) texel-megakernel-switch tile-megakernel; default all; --local's tile cache uses 4x2 tiles, lavapipe's subgroups
# having 8 lanes); --quality-shading: the architecture of the picture renders
# (default wavefront; lavapipe compiles the wavefront's per-material passes slowly);
# --variants: texel-cache settings measured beside the default, each a bench run
# texel-wavefront-NAME and a picture texel-NAME: trilinear and stochastic (--cache-filter),
# finer (--mip-bias 1: keys of half the size), secondary (--cache-secondary-only: camera hits
# uncached), refreshN (--cache-refresh N), and NAME_NAME... for several at once (default none);
# --keep-pictures: the uncached
# and texel pictures (PFM) come back in $OUT too, as SCENE_none.pfm and SCENE_texel.pfm (and
# SCENE_texel-NAME.pfm for each variant).
# e.g. run(carry=["bundle", ".gl"], command="bash tools/bench/memo_scenes_device.sh").
# Results in $OUT (default /tmp/out), written row by row so that a run cut short keeps what
# it finished: memo_scenes_table.md (the timing table), memo_scenes_quality.md (the picture
# table), memo_scenes_rows.csv (one bench CSV line a run) and memo_scenes_log.txt (every
# command's output).
set -uo pipefail
local=0 scale= budget= size=1920x1080 runs= variants= keep=0 qshading=wavefront frames=10 warmup=2 qsize=960x540 qframes=16
scenes="pack landscape classroom"
pack=bundle/material_scene.mgpack camera=bundle/material_scene.camera
while [ $# -gt 0 ]; do
  case $1 in
  --local) local=1; shift ;;
  --size) size=$2; shift 2 ;;
  --frames) frames=$2; shift 2 ;;
  --warmup) warmup=$2; shift 2 ;;
  --quality-size) qsize=$2; shift 2 ;;
  --quality-frames) qframes=$2; shift 2 ;;
  --scenes) scenes=$2; shift 2 ;;
  --pack) pack=$2; shift 2 ;;
  --camera) camera=$2; shift 2 ;;
  --limit-scale) scale=$2; shift 2 ;;
  --budget) budget=$2; shift 2 ;;
  --runs) runs=$2; shift 2 ;;
  --quality-shading) qshading=$2; shift 2 ;;
  --variants) variants=$2; shift 2 ;;
  --keep-pictures) keep=1; shift ;;
  -h | --help) sed -n '2,38p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "memo_scenes_device.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ $local = 1 ] && MEMOGRAPH=${MEMOGRAPH:-build/tools/memograph}
scale=${scale:-$([ $local = 1 ] && echo 10 || echo 1)}
# lavapipe's subgroups have 8 lanes, too few for the default 4x4 tile (one lane a texel).
tile=()
[ $local = 1 ] && tile=(--tile 4x2)
budget=${budget:-$([ $local = 1 ] && echo 100000 || echo 540)}
log_name=memo_scenes_log.txt rows_name=memo_scenes_rows.csv
source tools/bench/wavefront_device_setup.sh  # OUT, m, $log, $rows, appendRow
table="$OUT/memo_scenes_table.md"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$work}
shaders=/tmp/memo_scenes_shaders
start=$(date +%s)
spp=$((6 * qframes))

# stepLimit LIMIT: LIMIT x the scale, cut to the budget's remainder; empty when under 15 s.
stepLimit() {
  local limit=$(($1 * scale)) left=$((budget - ($(date +%s) - start)))
  [ $left -lt 15 ] && return
  echo $((limit < left ? limit : left))
}

# sceneSpec NAME: what bench and render are given for it.
sceneSpec() { [ "$1" = pack ] && echo "$pack" || echo "builtin:$1"; }

# field LOG PATTERN: the first number (a word starting with a digit) in the first match of
# PATTERN in LOG.
field() {
  grep -o "$2" "$1" | head -1 | awk '{ for (i = 1; i <= NF; ++i) if ($i ~ /^[0-9]/) { print $i; exit } }'
}

# variantFlags NAME: the texel cache's flags of a --variants name; NAME_NAME... joins them.
variantFlags() {
  local part
  for part in ${1//_/ }; do
    case $part in
      trilinear | stochastic) echo "--cache-filter $part" ;;
      finer) echo "--mip-bias 1" ;;
      secondary) echo "--cache-secondary-only" ;;
      refresh[0-9]*) echo "--cache-refresh ${part#refresh}" ;;
      *) echo "memo_scenes_device.sh: unknown variant $part" >&2; exit 2 ;;
    esac
  done
}
# Every variant is checked here, where an unknown one ends the script: inside the $(...) of
# a run it would only drop its own flags and run under the variant's name.
for v in $variants; do variantFlags "$v" >/dev/null; done

# bench SCENE NAME LIMIT FLAGS...: one bench run, its line appended to the table.
bench() {
  local scene=$1 name=$2 limit spec out csv ms hit share served
  [ -z "$runs" ] || [[ " $runs " == *" $name "* ]] || return 0
  limit=$(stepLimit "$3")
  shift 3
  if [ -z "$limit" ]; then
    echo "| $scene | $name | skipped: --budget spent | | | | |" >>"$table"
    return
  fi
  spec=$(sceneSpec "$scene")
  out="$work/${scene}_$name.txt" csv="$work/${scene}_$name.csv"
  echo "== $scene $name (limit $limit s, $(($(date +%s) - start)) s so far)" | tee -a "$log"
  timeout "$limit" "$m" bench "$spec" --sizes "$size" --paths 6 --bounces 4 --warmup "$warmup" \
    --frames "$frames" --time-limit $((limit - 10)) --label "$name" --shader-cache "$shaders" \
    --csv "$csv" "$@" >"$out" 2>&1
  echo "rc=$? $*" >>"$out"
  grep -v '^device:' "$out" | tee -a "$log"
  appendRow "$csv"
  ms=$(field "$out" 'median [0-9.e+-]* ms/frame')
  hit=$(field "$out" 'total [0-9.e+-]* %')
  share=$(field "$out" 'cached share [0-9.e+-]* %')
  served=$(field "$out" 'served from the cache [0-9.e+-]* %')
  domains=$(grep -o 'whole [^;]*' "$out" | head -1)
  [ "$name" = floor ] && floor_ms=$ms
  ratio=—
  if [ -n "${ms:-}" ] && [ -n "${floor_ms:-}" ]; then
    ratio=$(awk -v a="$ms" -v b="$floor_ms" 'BEGIN { printf "%.2f", a / b }')
  fi
  echo "| $scene | $name | ${ms:-failed} | $ratio | ${hit:-—} | ${share:-—} (${domains:-—}) | ${served:-—} |" >>"$table"
}

# render SCENE NAME LIMIT FLAGS...: a still render for the picture comparison.
render() {
  local scene=$1 name=$2 limit spec
  limit=$(stepLimit "$3")
  shift 3
  [ -n "$limit" ] || { echo "== $scene render $name skipped: --budget spent" | tee -a "$log"; return; }
  spec=$(sceneSpec "$scene")
  echo "== $scene render $name (limit $limit s, $(($(date +%s) - start)) s so far)" | tee -a "$log"
  timeout "$limit" "$m" render "$spec" --size "$qsize" --paths 6 --bounces 4 --frames "$qframes" \
    --shader-cache "$shaders" --out "$work/${scene}_$name.pfm" "$@" 2>&1 | tail -3 | tee -a "$log"
}

# compare SCENE NAME: mean FLIP and bias of NAME against the uncached render, one table row.
compare() {
  local scene=$1 name=$2 d
  [ -f "$work/${scene}_none.pfm" ] && [ -f "$work/${scene}_$name.pfm" ] || {
    echo "| $scene | $name | failed | | | |" >>"$quality"
    return
  }
  d=$("$m" diff "$work/${scene}_none.pfm" "$work/${scene}_$name.pfm" --bias-block 8)
  echo "$d" >>"$log"
  echo "| $scene | $name | $(echo "$d" | awk '/^mean/ {print $2}') | $(echo "$d" | awk '/^block MAE/ {print $3}') | $(echo "$d" | awk '/^image mean/ {print $4}') | $(echo "$d" | awk '/^image mean/ {print $6}') |" >>"$quality"
}

device=$("$m" render --list-devices 2>/dev/null | head -1 | sed 's/^\[0\] //')
quality="$OUT/memo_scenes_quality.md"
{
  echo "# Memoization on the material scenes"
  echo
  echo "Generated by \`tools/bench/memo_scenes_device.sh\` on $device. Camera path, $size,"
  echo "P = 6, L = 4, $warmup warm-up and $frames timed frames (a cached frame depends on the ones"
  echo "before it, so every frame of the path is rendered). Time: median GPU ms a frame; x floor:"
  echo "against --floor-materials on the wavefront. Hit rate: over the timed frames. Cached"
  echo "share: of the estimated material cost (compiler cost estimates, each instance weighted by its graph's cost),"
  echo "by what is cached (whole uv-only graphs; cuts by key domain); served = cached share x"
  echo "hit rate."
  echo
  echo "| scene | run | ms/frame | x floor | hit rate % | cached share % | served % |"
  echo "| --- | --- | --- | --- | --- | --- | --- |"
} >"$table"
{
  echo "# Memoization on the material scenes: the converged picture"
  echo
  echo "Static camera, $qsize, P = 6, $qframes frames: $spp samples a pixel$([ $spp = 1536 ] ||
    echo " (not 1536: the device call's time limit)"). Against the uncached render at seed 0:"
  echo "mean LDR-FLIP, and"
  echo "the bias: mean absolute error of 8x8-block means and the image means (linear)."
  echo "\`none-seed7\` is the uncached render at another seed: the noise a bias must stay below."
  echo
  echo "| scene | render | mean FLIP | 8x8 block MAE | mean (seed 0) | mean (this) |"
  echo "| --- | --- | --- | --- | --- | --- |"
} >"$quality"

for scene in $scenes; do
  floor_ms=
  # Limits: the classroom compiles 88 graphs and its uncached megakernel frame is about 2.7 s
  # on an H200, so it gets fewer frames and longer limits.
  big=0 fewer=()
  [ "$scene" = classroom ] && { big=1; fewer=(--frames $(((frames + 1) / 2)) --warmup 1); }
  l() { [ $big = 1 ] && echo "$2" || echo "$1"; }
  bench "$scene" floor "$(l 30 50)" --floor-materials --shading wavefront "${fewer[@]}"
  bench "$scene" none-megakernel "$(l 30 70)" --shading megakernel "${fewer[@]}"
  bench "$scene" none-wavefront "$(l 30 50)" --shading wavefront "${fewer[@]}"
  bench "$scene" texel-wavefront "$(l 30 50)" --shading wavefront --cache texel "${fewer[@]}"
  for v in $variants; do
    # shellcheck disable=SC2046  # the variant's flags are words
    bench "$scene" "texel-wavefront-$v" "$(l 30 50)" --shading wavefront --cache texel \
      $(variantFlags "$v") "${fewer[@]}"
  done
  # One key domain at a time (--cache-keys): what each domain's materials serve on the
  # Blender scene, whose graphs key all three (the built-ins' cached graphs are uv-only).
  if [ "$scene" = pack ]; then
    for keys in uv object world; do
      bench "$scene" "texel-wavefront-$keys" 30 --shading wavefront --cache texel \
        --cache-keys "$keys"
    done
  fi
  # The megakernel keys cuts with the switch dispatch only: one shader holding every graph,
  # too large for the classroom's 88.
  [ $big = 1 ] || bench "$scene" texel-megakernel-switch 40 --shading megakernel \
    --material-dispatch switch --cache texel
  bench "$scene" tile-megakernel "$(l 30 50)" --shading megakernel --cache tile "${tile[@]}" \
    "${fewer[@]}"

  # The picture: a still camera (the pack's path's middle camera; the built-ins' own).
  still=()
  if [ "$scene" = pack ] && [ -f "$camera" ]; then
    grep -v '^#' "$camera" | grep -v '^ *$' | awk '{ l[NR] = $0 } END { print l[int((NR + 1) / 2)] }' \
      >"$work/still.camera"
    still=(--camera-path "$work/still.camera")
  fi
  render "$scene" none "$(l 25 40)" --shading "$qshading" "${still[@]}"
  render "$scene" none-seed7 "$(l 25 40)" --shading "$qshading" --seed 7 "${still[@]}"
  render "$scene" texel "$(l 25 40)" --shading "$qshading" --cache texel "${still[@]}"
  for v in $variants; do
    # shellcheck disable=SC2046
    render "$scene" "texel-$v" "$(l 25 40)" --shading "$qshading" --cache texel \
      $(variantFlags "$v") "${still[@]}"
  done
  compare "$scene" none-seed7
  compare "$scene" texel
  for v in $variants; do compare "$scene" "texel-$v"; done
  if [ $keep = 1 ]; then
    for name in none texel $(for v in $variants; do echo "texel-$v"; done); do
      [ -f "$work/${scene}_$name.pfm" ] && cp "$work/${scene}_$name.pfm" "$OUT/"
    done
  fi
done
echo "memo_scenes_device.sh: $(($(date +%s) - start)) s; wrote $table and $quality" | tee -a "$log"
cat "$table" "$quality"
