#!/usr/bin/env bash
# Rays per second of the ray-traced ambient occlusion workload (seeds/004 §3; `--integrator
# ao`, docs/design/traced-inputs.md) on the GPU machine: `memograph bench` of each scene at
# 1920x1080, one primary ray a pixel (P = 1) and SPS AO rays from its hit, over the scene's
# camera path, for SPS = 8 (seeds/004 Table 3.2's setting) and 32. The rays counted are every
# ray traced (primary and AO); bench prints the median Mrays/s of the timed frames.
# Each of the 6 runs stops after 60 s of bench (90 s at most), so one device call of 600 s
# holds them. After tools/bundle_device.sh, on the GPU machine (carry bundle and .gl):
#   run(kind="nvidia-h100-x1", carry=["bundle", ".gl"], timeout_s=600,
#       command="OUT=$OUT bash tools/bench/ao_device.sh")
# Arguments: SCENE... (default builtin:classroom builtin:landscape builtin:city:scale=0.25).
# MEMOGRAPH=path picks another binary, SIZE=WxH another image size, SHADING=wavefront the
# wavefront's AO passes (default auto: the megakernel). Results: $OUT/ao_rays.csv (bench's CSV rows),
# $OUT/ao_log.txt (each run's summary), $OUT/env.txt (the GPU and driver).
set -uo pipefail
[ -n "${MEMOGRAPH:-}" ] || source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=${MEMOGRAPH:-bundle/memograph}
size=${SIZE:-1920x1080}
shading=${SHADING:-auto}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/env.txt" 2>&1
[ $# -gt 0 ] || set -- builtin:classroom builtin:landscape builtin:city:scale=0.25
for scene in "$@"; do
  for sps in 8 32; do
    label="ao_$(echo "$scene" | tr -c 'a-zA-Z0-9\n' '_')_sps${sps}${SHADING:+_$SHADING}"
    echo "== $label: $scene --ao-samples $sps --shading $shading" | tee -a "$OUT/ao_log.txt"
    timeout 90 "$m" bench "$scene" --sizes "$size" --paths 1 --integrator ao \
      --ao-samples "$sps" --shading "$shading" --warmup 3 --frames 60 --time-limit 60 \
      --shader-cache /tmp/sc \
      --label "$label" --csv "/tmp/$label.csv" 2>&1 | tail -8 | tee -a "$OUT/ao_log.txt"
    echo "rc=${PIPESTATUS[0]}" | tee -a "$OUT/ao_log.txt"
    if [ -f "$OUT/ao_rays.csv" ]; then tail -n +2 "/tmp/$label.csv"; else cat "/tmp/$label.csv"; fi \
      >>"$OUT/ao_rays.csv" 2>/dev/null
  done
done
echo done >>"$OUT/ao_log.txt"
