#!/usr/bin/env bash
# The cache checks on the GPU machine (docs/design/memoization.md, "Concurrency (§5.3.4)"; docs/results.md, "Cache correctness on the GPU"):
# the torn-read stress test in every mode (`memograph selftest`), then bench rows of the
# classroom at 1920x1080, P = 6, L = 4 over the 300-camera path, as the memoization sweep
# runs Table 6.1: the default-flag rows (`--cache texel`, `--cache tile` and nothing else)
# and the best rows beside them. After tools/bundle_device.sh, on the GPU machine (carry
# bundle, .gl and tools):
#   bash tools/bench/cache_checks_device.sh [selftest] [ROW...]
# ROW: texel_default, tile_default, texel_best, tile_best. MEMOGRAPH=path picks another
# binary (an older bundle's, for an A/B in one run) and LABEL_SUFFIX tells its rows apart.
set -uo pipefail
source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=${MEMOGRAPH:-bundle/memograph}
source tools/bench/megakernel_flags.sh  # shadingFlags
suffix=${LABEL_SUFFIX:-}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/env.txt" 2>&1
selftest() {
  echo "== selftest" | tee -a "$OUT/selftest.txt"
  timeout 150 $m selftest --invocations 65536 --iterations 512 --rounds 3 2>&1 |
    tee -a "$OUT/selftest.txt"
  echo "selftest rc=${PIPESTATUS[0]}" | tee -a "$OUT/selftest.txt"
}
row() {
  local label=$1$suffix limit=$2
  shift 2
  echo "== $label: $*" | tee -a "$OUT/bench_log.txt"
  timeout "$limit" $m bench builtin:classroom --sizes 1920x1080 --paths 6 --bounces 4 \
    --warmup 2 --frames 300 --camera-frames 300 --time-limit $((limit - 10)) \
    --shader-cache /tmp/sc --label "$label" --csv "/tmp/$label.csv" "${shadingFlags[@]}" "$@" 2>&1 |
    tail -25 >>"$OUT/bench_log.txt"
  echo "rc=${PIPESTATUS[0]}" >>"$OUT/bench_log.txt"
  if [ -f "$OUT/bench_rows.csv" ]; then tail -n +2 "/tmp/$label.csv"; else cat "/tmp/$label.csv"; fi \
    >>"$OUT/bench_rows.csv" 2>/dev/null
}
[ $# -gt 0 ] || set -- selftest texel_default tile_default texel_best tile_best
for what in "$@"; do
  case $what in
  selftest) selftest ;;
  texel_default) row texel_default 110 --cache texel ;;
  tile_default) row tile_default 110 --cache tile ;;
  texel_best) row texel_best 110 --cache texel --cache-entries 16777216 --eviction lru \
    --clock counter ;;
  tile_best) row tile_best 110 --cache tile --tile 4x4 --filter nearest \
    --cache-entries 1048576 --eviction lru --clock counter ;;
  *) echo "cache_checks_device.sh: unknown step '$what'" >&2; exit 2 ;;
  esac
done
echo done >>"$OUT/bench_log.txt"
