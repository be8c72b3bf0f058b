#!/usr/bin/env bash
# Builds the GPU-machine bundle: bundle/memograph (renderer + compiler + built-in scenes,
# glslang and the C++ runtime linked statically; no OpenImageIO, no assimp) and
# bundle/run_device.sh, the command the `device` tool runs (with bundle/device_env.sh, the
# Vulkan set-up it and the memoization scripts source). The only non-system library the
# binary needs is libvulkan.so.1, which travels as Debian packages in .gl/ (the recipe of
# the device tool's README). Everything stays under 64 MiB.
#
# Usage: tools/bundle_device.sh            (from the repository root)
# Then run on the GPU machine (the device tool, one call; results come back under $OUT):
#   run(kind="nvidia-h100-x1", carry=["bundle", ".gl"], timeout_s=600,
#       command="bash bundle/run_device.sh")
# Images come back as .pfm; convert them here with `memograph` built with the io module
# (or oiiotool in.pfm -o out.png).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
build=build-device
bundle=bundle

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMEMOGRAPH_BUILD_TESTS=OFF \
  -DMEMOGRAPH_BUILD_IO=OFF \
  -DCMAKE_EXE_LINKER_FLAGS="-static-libstdc++ -static-libgcc" >/dev/null
cmake --build "$build" --target memograph -j"${JOBS:-2}"

rm -rf "$bundle"
mkdir -p "$bundle"
cp "$build/tools/memograph" "$bundle/memograph"
strip "$bundle/memograph"

# The binary may need only system libraries, the Vulkan loader and meshoptimizer (the city's
# mesh LODs; Debian ships it shared only), which travel as .gl/*.deb. meshoptimizer brings
# libstdc++ and libgcc_s, of which it needs only GLIBCXX_3.4 and CXXABI_1.3 (any libstdc++6):
# the GPU machine's own serve it.
unexpected=$(ldd "$bundle/memograph" | awk '{print $1}' |
  grep -vE '^(linux-vdso\.so|/lib64/ld-linux-x86-64\.so|libc\.so|libm\.so|libpthread\.so|libdl\.so|librt\.so|libvulkan\.so\.1|libmeshoptimizer\.so\.2d|libstdc\+\+\.so\.6|libgcc_s\.so\.1)' || true)
if [ -n "$unexpected" ]; then
  echo "bundle_device: the binary needs libraries that will not be on the GPU machine:" >&2
  echo "$unexpected" >&2
  echo "(configure without the io module: -DMEMOGRAPH_BUILD_IO=OFF)" >&2
  exit 1
fi

# The Vulkan loader as Debian packages (device tool README); fetched once.
# NVIDIA's ICD (libGLX_nvidia.so.0) needs libglvnd's dispatch libraries as well.
if ! ls .gl/libvulkan1_*.deb .gl/libglvnd0_*.deb .gl/libmeshoptimizer2d_*.deb >/dev/null 2>&1; then
  mkdir -p .gl /tmp/amd64/partial
  o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
  apt-get $o update -qq
  (cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 \
    libmeshoptimizer2d)
fi

cp tools/device_env.sh "$bundle/device_env.sh"
cat >"$bundle/run_device.sh" <<'RUN'
#!/usr/bin/env bash
# Runs on the GPU machine: installs the carried Vulkan loader, then the smoke test, the
# renders and the path tracer's benchmarks. Everything it measures lands in $OUT: 8 files at
# most (the device tool's limit), each under 16 MB.
set -uo pipefail
source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=bundle/memograph
# Each step has its own time limit, so one slow step cannot eat the whole call. The limits
# add up to 560 s (+ a few seconds of set-up) under the 600 s a device call may take. The
# landscape (4 materials) goes first and gets short limits; the classroom (88 materials)
# compiles many shaders on its first start, so its steps get the generous ones (its later
# steps reuse the SPIR-V disk cache and the driver's shader cache).
step() { local limit=$1; shift; timeout "$limit" "$@" || echo "STEP FAILED ($?): $*"; }
bench_csv=/tmp/bench_gpu_parts
rm -rf "$bench_csv" && mkdir -p "$bench_csv"
scene_steps() {
  local s=$1 smoke=$2 bench=$3 render=$4
  echo "== $s: smoke (320x180)"
  step "$smoke" $m render builtin:$s --size 320x180 --paths 1 --bounces 2 --frames 2 \
    --out "$OUT/smoke_$s.pfm"
  # Thesis settings (§6): 1920x1080, P = 6, L = 4; one bench per scene.
  echo "== $s: bench (1920x1080, P=6, L=4)"
  step "$bench" $m bench builtin:$s --sizes 1920x1080 --paths 6 --bounces 4 \
    --frames 30 --warmup 5 --csv "$bench_csv/$s.csv"
  # Images at 960x540: a 1080p PFM (25 MB) is over the 16 MB a returned file may have.
  echo "== $s: render (960x540, P=6, L=4)"
  step "$render" $m render builtin:$s --size 960x540 --paths 6 --bounces 4 --frames 8 \
    --out "$OUT/$s.pfm" --stats "$OUT/${s}_stats.csv"
}
{
  nvidia-smi -L || true
  $m render --list-devices
  scene_steps landscape 30 50 30
  # What the callable material dispatch costs: the landscape once more with the switch.
  echo "== landscape: bench with --material-dispatch switch"
  step 30 $m bench builtin:landscape --sizes 1920x1080 --paths 6 --bounces 4 --frames 30 \
    --warmup 5 --material-dispatch switch --csv "$bench_csv/landscape_switch.csv"
  scene_steps classroom 150 150 120
  # One bench CSV (the device call returns 8 files at most): the header once, then each
  # scene's lines.
  first=1
  for s in landscape landscape_switch classroom; do
    [ -f "$bench_csv/$s.csv" ] || continue
    if [ $first = 1 ]; then cat "$bench_csv/$s.csv"; first=0; else tail -n +2 "$bench_csv/$s.csv"; fi
  done >"$OUT/bench_gpu.csv"
} 2>&1 | tee "$OUT/log.txt"
RUN
chmod +x "$bundle/run_device.sh"

size=$(du -sm "$bundle" .gl | awk '{s += $1} END {print s}')
echo "bundle_device: $bundle/ and .gl/ hold ${size} MiB (limit 64)"
[ "$size" -le 64 ] || { echo "bundle_device: too large" >&2; exit 1; }
ldd "$bundle/memograph"
