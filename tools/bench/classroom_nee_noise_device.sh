#!/usr/bin/env bash
# The classroom's noise at 96 samples per pixel, with and without emissive-triangle NEE,
# against a 4096-sample reference (docs/design/path-tracer.md, Light sampling). Run on the GPU machine
# after tools/bundle_device.sh (carry bundle and .gl): bash tools/bench/classroom_nee_noise_device.sh
# Uncached renders (the true picture), static camera, P = 6 or 64 paths a frame, L = 4.
# Back here: memograph diff REF.pfm X.pfm gives the mean LDR-FLIP; the per-frame GPU times in
# the stats CSVs give the cost of each at equal sample count.
set -uo pipefail
[ -f bundle/device_env.sh ] && source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
m=${MEMOGRAPH:-bundle/memograph}
source tools/bench/megakernel_flags.sh  # shadingFlags
size=${SIZE:-320x180}
mkdir -p "$OUT"
common=(builtin:classroom:nee=1 --size "$size" --bounces 4 --shader-cache /tmp/noise_shaders)
step() {
  local label=$1 limit=$2
  shift 2
  echo "== $label: $*"
  local t0=$(date +%s)
  timeout "$limit" "$m" render "${common[@]}" "${shadingFlags[@]}" "$@" --out "$OUT/classroom_$label.pfm" \
    --stats "$OUT/classroom_${label}_stats.csv" 2>&1 | tail -3
  echo "rc=${PIPESTATUS[0]} seconds=$(($(date +%s) - t0))"
}
{
  step ref4096 240 --paths 64 --frames 64 --seed 7
  step nee96 60 --paths 6 --frames 16 --seed 1
  step bsdf96 60 --paths 6 --frames 16 --seed 1 --no-emissive-nee
} 2>&1 | tee "$OUT/classroom_noise_log.txt"
