#!/usr/bin/env bash
# On the GPU machine, after tools/bundle_ab.sh: the same bench row for bundle/memograph and
# for every bundle/ab/<rev>/memograph, one after the other in one call, so that their frame
# times compare on one GPU (docs/gpu-results.md: calls differ by about 3 %). The row is the
# classroom's texel row of Table 6.1 at 1920x1080, P = 6, L = 4 over the first --frames
# cameras of the built-in path; extra arguments replace its cache flags. --local runs here
# (no carried Vulkan loader), e.g. --local --scene landscape --size 32x18 --frames 2 on
# lavapipe to check the script.
#   bash tools/bench/ab_device.sh [--local] [--scene S] [--size WxH] [--frames N] [--limit S] [bench flags...]
# Results in $OUT: ab_log.txt (each run's summary) and ab_rows.csv (one bench line a run).
set -uo pipefail
frames=150 limit=90 scene=classroom size=1920x1080 local=0
while [ $# -gt 0 ]; do
  case $1 in
  --local) local=1; shift ;;
  --scene) scene=$2; shift 2 ;;
  --size) size=$2; shift 2 ;;
  --frames) frames=$2; shift 2 ;;
  --limit) limit=$2; shift 2 ;;
  *) break ;;
  esac
done
[ $local = 1 ] || source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
flags=("$@")
[ ${#flags[@]} -gt 0 ] || flags=(--cache texel --cache-entries 16777216 --eviction lru
  --clock counter)
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/ab_env.txt" 2>&1 || true
# A second run in the same call appends to ab_rows.csv under the header already there.
first=1
[ -s "$OUT/ab_rows.csv" ] && first=0
for m in bundle/memograph bundle/ab/*/memograph; do
  [ -x "$m" ] || continue
  dir=$(dirname "$m")
  label=$(cut -d' ' -f1 "$dir/VERSION" 2>/dev/null || basename "$dir")
  echo "== $label ($(cat "$dir/VERSION" 2>/dev/null)): ${flags[*]}" | tee -a "$OUT/ab_log.txt"
  timeout "$limit" "$m" bench "builtin:$scene" --sizes "$size" --paths 6 --bounces 4 \
    --warmup 2 --frames "$frames" --camera-frames 300 --time-limit $((limit - 10)) \
    --shader-cache "/tmp/ab_shaders_$label" --label "$label" --csv "/tmp/ab_$label.csv" \
    "${flags[@]}" 2>&1 | tail -6 | tee -a "$OUT/ab_log.txt"
  if [ $first = 1 ]; then cat "/tmp/ab_$label.csv"; first=0; else tail -n +2 "/tmp/ab_$label.csv"; fi \
    >>"$OUT/ab_rows.csv" 2>/dev/null
done
