# Sourced from the repository root by the wavefront's GPU-machine scripts
# (wavefront_floor_device.sh, wavefront_lookup_device.sh) once their arguments are read:
# the carried Vulkan set-up (not with local=1: lavapipe here), OUT (default /tmp/out) made,
# m the binary (MEMOGRAPH, default the bundle's), $log and $rows ($OUT/$log_name and
# $OUT/$rows_name, names the caller sets) emptied, and the GPU and its driver logged.
# appendRow CSV adds a bench CSV's line to $rows, the header only once.
[ "${local:-0}" = 1 ] || source bundle/device_env.sh
OUT=${OUT:-/tmp/out}
m=${MEMOGRAPH:-bundle/memograph}
mkdir -p "$OUT"
log="$OUT/$log_name" rows="$OUT/$rows_name"
: >"$log"
: >"$rows"
if command -v nvidia-smi >/dev/null; then
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >>"$log" 2>&1
fi
appendRow() {
  [ -s "$1" ] || return 0
  if [ -s "$rows" ]; then tail -n +2 "$1"; else cat "$1"; fi >>"$rows"
}
