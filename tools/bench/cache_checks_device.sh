#!/usr/bin/env bash
# Issue 17 on the GPU machine (copy to bundle/run_cache_checks.sh after tools/bundle_device.sh;
# run with carry=["bundle", ".gl"], command="bash bundle/run_cache_checks.sh"): the cache's torn-read stress test in every mode, then the
# default-flag bench rows and the best rows beside them (classroom, 1080p, P=6, L=4, the
# 300-camera path, as the memoization sweep runs Table 6.1).
set -uo pipefail
source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=bundle/memograph
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/env.txt" 2>&1
echo "== selftest" | tee "$OUT/selftest.txt"
timeout 150 $m selftest --invocations 65536 --iterations 512 --rounds 3 2>&1 | tee -a "$OUT/selftest.txt"
echo "selftest rc=${PIPESTATUS[0]}" | tee -a "$OUT/selftest.txt"
row() {
  local label=$1 limit=$2; shift 2
  echo "== $label: $*" | tee -a "$OUT/bench_log.txt"
  timeout "$limit" $m bench builtin:classroom --sizes 1920x1080 --paths 6 --bounces 4 \
    --warmup 2 --frames 300 --camera-frames 300 --time-limit $((limit - 10)) \
    --shader-cache /tmp/sc --label "$label" --csv "/tmp/$label.csv" "$@" 2>&1 | tail -25 >> "$OUT/bench_log.txt"
  echo "rc=${PIPESTATUS[0]}" >> "$OUT/bench_log.txt"
  cat "/tmp/$label.csv" >> "$OUT/bench_rows.csv" 2>/dev/null
}
row texel_default 110 --cache texel
row tile_default 110 --cache tile
row texel_best 100 --cache texel --cache-entries 16777216 --eviction lru --clock counter --cache-read-check key
row tile_best 100 --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --cache-read-check key
echo done >> "$OUT/bench_log.txt"
