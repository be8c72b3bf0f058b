#!/usr/bin/env bash
# The first frame's wall time on the GPU machine (docs/design/path-tracer.md, "Pipeline
# cache"): builtin:classroom at 1920x1080, P = 6, L = 4, one frame, each run a new process.
# Two rounds, each a cold run (empty --shader-cache folder) then a warm one (the same folder):
#   driver-cache-off  __GL_SHADER_DISK_CACHE=0 (the NVIDIA driver keeps no shaders of its own)
#   driver-cache-on   __GL_SHADER_DISK_CACHE=1 with a fresh __GL_SHADER_DISK_CACHE_PATH
# Prints a table (first_frame.txt): the process's wall time, and what render printed of its
# pipelines (created, found in the pipeline cache, their time, their creation calls' time
# summed and how many the driver compiled at a time, the first frame's wall time), after the
# machine's CPU count (the threads that create pipelines: one a core).
# FRAMES=2 renders a second frame too: render's line then also says how long the graphs' own
# material passes took to create before it (RendererOptions::ownMaterialPassesFromSecondFrame).
# After tools/bundle_device.sh, on the GPU machine (carry bundle and .gl):
#   OUT=$OUT [FRAMES=2] bash tools/bench/first_frame_device.sh
set -uo pipefail
source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
SCENE=${SCENE:-builtin:classroom}
SIZE=${SIZE:-1920x1080}
FRAMES=${FRAMES:-1}
mkdir -p "$OUT"
m=$PWD/bundle/memograph
table="$OUT/first_frame$([ "$FRAMES" = 1 ] || echo "_$FRAMES").txt"
printf '%-17s %-5s %9s  %s\n' driver_cache run wall_s "render's pipeline line" >"$table"
one_run() {
  local label=$1 run=$2 cache=$3
  local start end log
  log=$(mktemp)
  start=$(date +%s%N)
  timeout 280 "$m" render "$SCENE" --size "$SIZE" --paths 6 --bounces 4 --frames "$FRAMES" \
    --shader-cache "$cache" --out "/tmp/first_frame_${label}_${run}.pfm" >"$log" 2>&1
  local rc=$?
  end=$(date +%s%N)
  local pipeline
  pipeline=$(grep -oE 'pipeline [0-9.]+ ms.*' "$log" | tr '\n' ' ')
  printf '%-17s %-5s %9.2f  rc %d; %s\n' "$label" "$run" "$(awk -v a="$start" -v b="$end" 'BEGIN {print (b - a) / 1e9}')" "$rc" \
    "$pipeline" >>"$table"
  echo "== $label $run (rc $rc)"; cat "$log"
  rm -f "$log"
}
{
  nvidia-smi -L || true
  echo "CPUs: $(nproc)"
  c=$(mktemp -d)
  export __GL_SHADER_DISK_CACHE=0
  one_run driver-cache-off cold "$c"
  one_run driver-cache-off warm "$c"
  c=$(mktemp -d)
  export __GL_SHADER_DISK_CACHE=1 __GL_SHADER_DISK_CACHE_PATH=$(mktemp -d)
  one_run driver-cache-on cold "$c"
  one_run driver-cache-on warm "$c"
  cat "$table"
} 2>&1 | tee "$OUT/first_frame$([ "$FRAMES" = 1 ] || echo "_$FRAMES")_log.txt"
