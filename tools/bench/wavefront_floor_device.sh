#!/usr/bin/env bash
# On the GPU machine, after tools/bundle_device.sh (carry bundle and .gl): the free-material
# floor as a megakernel and as the wavefront prototype (--shading wavefront;
# docs/design/architecture.md, "Material-coherent shading"), on the pipeline backend, one after
# the other in one call so that they compare on one GPU. Classroom and landscape at
# 1920x1080, P = 6, L = 4, every 10th camera of the built-in path (30 timed frames after 2
# warm-up frames); each run under its own time limit, all within about 500 s. --local runs
# here (no carried Vulkan loader), e.g. --local --size 64x36 --frames 2 on lavapipe to check
# the script. --materials: the scenes' material graphs without a cache instead of the floor
# (the wavefront's per-material passes against the megakernel's callables), in a call of its
# own (its limits also add up to about 500 s). --texel-cache: the graphs with the default
# texel cache (--cache texel: what a user gets), the wavefront's lookup pass against the
# megakernel's lookups, in a call of its own too: a cached frame depends on the frames
# before it, so these render the first 100 cameras of the path one after another (--frames
# sets how many) instead of every 10th. --tile-cache: the same with the default tile cache
# (--cache tile; the megakernel's subgroup fill against the wavefront's material passes
# computing the queued tiles). --traced-inputs: the graphs without a cache, each with an
# Ambient Occlusion node of 8 samples on its base colour and a Bevel node of 4 as its normal
# (the built-in scenes' ao=8,bevel=4; docs/design/traced-inputs.md): the wavefront's
# traced-inputs pass against the megakernel's rays traced in place, in a call of its own.
#   bash tools/bench/wavefront_floor_device.sh [--local] [--materials | --texel-cache |
#        --tile-cache | --traced-inputs]
#        [--size WxH] [--frames N]
# e.g. run(carry=["bundle", ".gl"], command="bash tools/bench/wavefront_floor_device.sh").
# Results in $OUT: wavefront_rows.csv (one bench line a run, with the wavefront's pass
# columns median_wavefront_{trace,shade,shadow,queue,bin,material,lookup,traced_inputs}_gpu_ms)
# and wavefront_log.txt.
set -uo pipefail
frames= size=1920x1080 local=0 materials=0 cache=() sceneOptions=
while [ $# -gt 0 ]; do
  case $1 in
  --local) local=1; shift ;;
  --materials) materials=1; shift ;;
  --texel-cache) materials=1; cache=(--cache texel); shift ;;
  --tile-cache) materials=1; cache=(--cache tile); shift ;;
  --traced-inputs) materials=1; sceneOptions=:ao=8,bevel=4; shift ;;
  --size) size=$2; shift 2 ;;
  --frames) frames=$2; shift 2 ;;
  *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
done
log_name=wavefront_log.txt rows_name=wavefront_rows.csv
source tools/bench/wavefront_device_setup.sh
# scene, limit in seconds (the classroom compiles 88 graphs before its first frame; with its
# graphs the megakernel's frame is about 2.7 s on the H200).
entries="landscape:100 classroom:140" floor=--floor-materials
[ $materials = 0 ] || { entries="landscape:80 classroom:160"; floor=; }
stride=(--frame-stride 10)
[ ${#cache[@]} = 0 ] || { entries="landscape:90 classroom:150"; stride=(--camera-frames 300); }
frames=${frames:-$([ ${#cache[@]} = 0 ] && echo 30 || echo 100)}
for entry in $entries; do
  scene=${entry%%:*}
  limit=${entry##*:}
  for shading in megakernel wavefront; do
    echo "== $scene $shading $size (limit $limit s)" | tee -a "$log"
    t0=$(date +%s)
    csv="/tmp/wavefront_${scene}_${shading}.csv"
    rm -f "$csv"
    timeout "$limit" "$m" bench "builtin:$scene$sceneOptions" --backend pipeline --sizes "$size" --paths 6 \
      --bounces 4 --warmup 2 --frames "$frames" "${stride[@]}" $floor "${cache[@]}" \
      --shading "$shading" --time-limit $((limit - 15)) --label "$shading" \
      --shader-cache /tmp/wavefront_shaders --csv "$csv" 2>&1 | tail -6 | tee -a "$log"
    echo "rc=${PIPESTATUS[0]} seconds=$(($(date +%s) - t0))" | tee -a "$log"
    appendRow "$csv"
  done
done
