#!/usr/bin/env bash
# The culling measurement on the GPU machine (docs/design/culling.md, "Measured"): builtin:city at
# 1920x1080, P = 6, L = 4 with --culling none, frustum and lipac.
#   bench      the city's camera path (360 frames; STRIDE=k renders every k-th camera):
#              per frame the trace's GPU time, BLAS and TLAS build times, AS bytes, instance
#              counts (frames_<mode>.csv), and bench's summary line per mode (bench.csv)
#   pictures   each mode at three cameras of the street path, two in the main street facing
#              the mirror (120: 336 m from it, 153: 84 m; what they see in it is behind them)
#              and one flying in (8): the 8 cameras before it, then 4 frames at it (the image
#              is those 4; PICTURE_FRAMES=32 accumulates 32), seed 1; LDR-FLIP of frustum and
#              lipac against none (pictures.txt,
#              each camera's role in its header). With SCENE=builtin:city:path=aerial, the
#              aerial path's cameras (city_aerial.campath): 120 and 135 facing the mirror, 60
#              flying in, as the culling results picture them
#   variants   LiPaC with other settings: VARIANTS="label:flags;label:flags" (for example
#              "every4:--feedback-every 4 --low-frames 2"), each a bench run of the path as
#              above (variants.csv: bench's summary line each, labelled lipac_<label>;
#              frames_lipac_<label>.csv: per frame); the pictures step pictures them too,
#              after the modes, each against none
#   looks      LiPaC's looks swept: --look-appearing in LOOKS (default "2 4 16"; 8 is the
#              bench step's lipac row), each a bench run of the path as above (looks.csv:
#              bench's summary line each, labelled lipac_appearing_N;
#              frames_lipac_<label>.csv: per frame, with the looks and their GPU time)
#   checks     LiPaC run twice must count and hold the same, proven on the GPU, where a
#              missing barrier or a lost atomic shows: the street path's cameras 137-152 at
#              CHECK_SIZE (default 480x270), P = PATHS, --feedback-every 2, seed 1, the second
#              run against the first (checks.txt): every frame's rays, instance and hitbox
#              counts, state changes, TLAS records, BLAS builds and looks the same, and the
#              picture bit-identical; then --culling none twice, the second against the first
#              (every flag moved by the vertex pass and its BLAS updated every frame); a line
#              `PASS label` or `FAIL label: why` each
# After tools/bundle_device.sh, on the GPU machine (tools/ and examples/ travel as tracked
# files; carry bundle and .gl):
#   bash tools/bench/culling_device.sh [bench] [pictures] [variants] [looks] [checks]
# and here, from the returned files (unpack culling_run.tar.gz into RUN_FOLDER first):
#   tools/results/make_culling_report RUN_FOLDER
#   (tools/results/make_culling_report writes the report and its plots).
# SHADING=wavefront measures the wavefront instead of the megakernel; BOUNCES (default 4) the
# rays a path; PICTURE_LIMIT (default 150) the seconds a picture's render may take;
# KEEP_PICTURES=1 keeps the pictures' renders (<camera>_<label>.pfm) in OUT.
# EXTRA="--cache texel" adds flags to every run; MODES="none lipac" runs only those modes (the
# pictures compare each with none, so keep none there); CAMERAS="120 153" pictures only those. Results under $OUT, each step under its own
# time limit (LIMIT seconds a bench run, default 170). Here, to check the script on lavapipe
# (figures meaningless), with the small city's own path:
#   build/tests/runtime/scene/builtin/scenes_write_camera_paths /tmp/paths 360 0.02
#   MEMOGRAPH=build/tools/memograph SCENE=builtin:city:scale=0.02 CAMPATH=/tmp/paths/city.campath
#   SIZE=64x36 CHECK_SIZE=64x36 PATHS=2 OUT=/tmp/culling bash tools/bench/culling_device.sh
set -uo pipefail
[ -n "${MEMOGRAPH:-}" ] || source bundle/device_env.sh # the GPU machine's Vulkan set-up
OUT=${OUT:-/tmp/out}
mkdir -p "$OUT"
m=${MEMOGRAPH:-bundle/memograph}
source tools/bench/megakernel_flags.sh  # shadingFlags
[ -z "${SHADING:-}" ] || shadingFlags=(--shading "$SHADING")
bounces=${BOUNCES:-4}
picture_frames=${PICTURE_FRAMES:-4}
stride=${STRIDE:-1}
scene=${SCENE:-builtin:city}
size=${SIZE:-1920x1080}
paths=${PATHS:-6}
limit=${LIMIT:-170}
path=examples/camera_paths/city.campath
declare -A role=([120]=mirror [153]=mirror [8]="flying in")
picture_cameras="120 153 8"
case $scene in
*path=aerial*)
  path=examples/camera_paths/city_aerial.campath
  role=([120]=mirror [135]=mirror [60]="flying in")
  picture_cameras="120 135 60"
  ;;
esac
# A smaller city has its own path: CAMPATH names its file (scenes_write_camera_paths).
path=${CAMPATH:-$path}
picture_cameras=${CAMERAS:-$picture_cameras}
modes=${MODES:-none frustum lipac}
work=$(mktemp -d)
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader >"$OUT/env.txt" 2>&1
cat bundle/VERSION >>"$OUT/env.txt" 2>/dev/null
echo "stride=$stride limit=$limit extra='${EXTRA:-}'" >>"$OUT/env.txt"

# Appends bench CSV $1 to $2, its header only when $2 is new. (A test inside a compound
# command redirected to $2 always found $2: the redirection creates it first, so bench.csv
# came back without its header.)
append_csv() {
  [ -f "$1" ] || return 0
  if [ -s "$2" ]; then tail -n +2 "$1" >>"$2"; else cat "$1" >"$2"; fi
}

# One bench run of the path: `label`, the summary CSV its line goes to, then its flags; its
# frames go to frames_<label>.csv.
bench_run() {
  local label=$1 summary=$2
  shift 2
  echo "== bench $label" | tee -a "$OUT/log.txt"
  # shellcheck disable=SC2086 # EXTRA is a list of flags
  timeout "$limit" "$m" bench "$scene" "${shadingFlags[@]}" --sizes "$size" --paths "$paths" --bounces "$bounces" \
    --warmup 0 --frames $((360 / stride)) --camera-frames 360 --frame-stride "$stride" \
    --time-limit $((limit - 10)) --label "$label" --shader-cache "$work/sc" \
    --csv "$work/bench_$label.csv" --frames-csv "$work/$label." "$@" ${EXTRA:-} 2>&1 |
    tail -8 >>"$OUT/log.txt"
  echo "rc=${PIPESTATUS[0]}" >>"$OUT/log.txt"
  append_csv "$work/bench_$label.csv" "$OUT/$summary"
  cp "$work/$label."*_"$size".csv "$OUT/frames_$label.csv" 2>/dev/null
}

# VARIANTS="label:flags;label:flags" as lipac_<label> and its flags, for the variants and
# pictures steps.
variant_labels=() variant_flags=()
IFS=';' read -ra variant_entries <<<"${VARIANTS:-}"
for entry in "${variant_entries[@]}"; do
  variant_labels+=("lipac_${entry%%:*}")
  variant_flags+=("${entry#*:}")
done

# The columns of a render's --stats CSV ($1) that say what a frame counted and held, one line
# a frame (quoted fields, such as lavapipe's device name with its comma, blanked first).
state_columns() {
  local -a names
  local fields="" i
  IFS=, read -ra names < <(head -1 "$1")
  for i in "${!names[@]}"; do
    case ${names[i]} in
    rays | active_instances | omitted_instances | inactive_instances | waiting_instances | \
      hitboxes | active_hitboxes | instance_state_changes | tlas_records | blas_builds | \
      blas_evictions | looks | look_rays | feedback_frame) fields+="$((i + 1))," ;;
    esac
  done
  sed 's/"[^"]*"/q/g' "$1" | cut -d, -f"${fields%,}"
}

checks() {
  local cameras label reference verdict flip d i
  mapfile -t cameras < <(grep -v '^#' "$path" | grep .)
  printf '%s\n' "${cameras[@]:137:16}" >"$work/checks.campath"
  # Each label's run against its reference's: each mode run twice (again, none_again), so
  # that a race (the vertex pass before the flags' BLAS updates, the counters) shows as two
  # runs that differ.
  local -a labels=(defaults again none none_again)
  local -a settings=("" "" "--culling none" "--culling none")
  local -a references=("" defaults "" none)
  for i in "${!labels[@]}"; do
    label=${labels[i]}
    echo "== check $label" | tee -a "$OUT/log.txt"
    # shellcheck disable=SC2086 # settings and EXTRA are lists of flags
    timeout 150 "$m" render "$scene" "${shadingFlags[@]}" --size "${CHECK_SIZE:-480x270}" \
      --paths "$paths" --bounces 4 --frames 16 --camera-path "$work/checks.campath" --seed 1 \
      --culling lipac --feedback-every 2 ${settings[i]} --shader-cache "$work/sc" \
      --out "$work/check_$label.pfm" --stats "$work/check_$label.csv" ${EXTRA:-} \
      >>"$OUT/log.txt" 2>&1
    echo "rc=$?" >>"$OUT/log.txt"
  done
  for i in "${!labels[@]}"; do
    label=${labels[i]}
    reference=${references[i]}
    [ -n "$reference" ] || continue
    verdict=""
    if [ ! -s "$work/check_$label.csv" ] || [ ! -s "$work/check_$label.pfm" ] ||
      [ ! -s "$work/check_$reference.csv" ] || [ ! -s "$work/check_$reference.pfm" ]; then
      verdict="no render (log.txt)"
    elif ! diff <(state_columns "$work/check_$reference.csv") \
      <(state_columns "$work/check_$label.csv") >"$OUT/checks_$label.diff"; then
      # CSV lines (1: the header, 2: frame 0): the first pair that differs; the whole diff in
      # checks_<label>.diff.
      d="$OUT/checks_$label.diff"
      verdict="the frames' counts and states differ at CSV lines $(head -1 "$d"): first"
      verdict+=" $(grep -m1 '^<' "$d") against $(grep -m1 '^>' "$d") (columns"
      verdict+=" $(state_columns "$work/check_$reference.csv" | head -1); checks_$label.diff)"
    elif ! cmp -s "$work/check_$reference.pfm" "$work/check_$label.pfm"; then
      flip=$("$m" diff "$work/check_$reference.pfm" "$work/check_$label.pfm" 2>&1 |
        awk '$1 == "mean" {print $2}')
      verdict="the picture differs (mean LDR-FLIP ${flip:-?})"
    fi
    [ -s "$OUT/checks_$label.diff" ] || rm -f "$OUT/checks_$label.diff"
    if [ -z "$verdict" ]; then echo "PASS $label"; else echo "FAIL $label: $verdict"; fi \
      >>"$OUT/checks.txt"
  done
  cat "$OUT/checks.txt"
}

looks() {
  for setting in ${LOOKS:-2 4 16}; do
    bench_run "lipac_appearing_$setting" looks.csv --culling lipac --look-appearing "$setting"
  done
}

variants() {
  for i in "${!variant_labels[@]}"; do
    # shellcheck disable=SC2086 # the flags are a list
    bench_run "${variant_labels[i]}" variants.csv --culling lipac ${variant_flags[i]}
  done
}

bench() {
  for mode in $modes; do
    bench_run "$mode" bench.csv --culling "$mode"
  done
}

pictures() {
  local cameras label flags
  mapfile -t cameras < <(grep -v '^#' "$path" | grep .)
  # What is pictured: each mode, then each variant (none first, as the modes list it, since
  # the others are compared with it).
  local -a labels=() settings=()
  for mode in $modes; do
    labels+=("$mode")
    settings+=("--culling $mode")
  done
  for i in "${!variant_labels[@]}"; do
    labels+=("${variant_labels[i]}")
    settings+=("--culling lipac ${variant_flags[i]}")
  done
  for k in $picture_cameras; do
    printf '%s\n' "${cameras[@]:k-8:8}" >"$work/path_$k.campath"
    for _ in $(seq 1 "$picture_frames"); do echo "${cameras[k]}" >>"$work/path_$k.campath"; done
    for i in "${!labels[@]}"; do
      label=${labels[i]}
      flags=${settings[i]}
      echo "== picture $k $label" | tee -a "$OUT/log.txt"
      # shellcheck disable=SC2086 # flags and EXTRA are lists of flags
      timeout "${PICTURE_LIMIT:-150}" "$m" render "$scene" "${shadingFlags[@]}" --size "$size" \
        --paths "$paths" --bounces "$bounces" --frames $((8 + picture_frames)) \
        --camera-path "$work/path_$k.campath" --seed 1 $flags \
        --shader-cache "$work/sc" --out "$work/${k}_$label.pfm" --stats "$work/${k}_$label.csv" \
        ${EXTRA:-} >>"$OUT/log.txt" 2>&1
      echo "rc=$?" >>"$OUT/log.txt"
      tail -n 1 "$work/${k}_$label.csv" | sed "s/^/$k,$label,/" >>"$OUT/pictures_stats.csv" 2>/dev/null
    done
    for label in "${labels[@]}"; do
      [ "$label" != none ] || continue
      echo "== camera $k (${role[$k]:-}): $label against none" >>"$OUT/pictures.txt"
      "$m" diff "$work/${k}_none.pfm" "$work/${k}_$label.pfm" >>"$OUT/pictures.txt" 2>&1
    done
    [ -z "${KEEP_PICTURES:-}" ] || cp "$work/${k}_"*.pfm "$OUT/" 2>/dev/null
  done
  head -1 "$work/${k}_none.csv" >"$OUT/pictures_stats_header.csv" 2>/dev/null
}

[ $# -gt 0 ] || set -- bench pictures
for step in "$@"; do
  case $step in
  bench) bench ;;
  pictures) pictures ;;
  looks) looks ;;
  variants) variants ;;
  checks) checks ;;
  *) echo "culling_device.sh: unknown step '$step'" >&2; exit 2 ;;
  esac
done
rm -rf "$work"
echo done >>"$OUT/log.txt"
# The device tool returns at most 8 files and a full run writes 9: on the GPU machine they
# come back as one archive (unpack it into the run folder for make_culling_report) beside
# the logs to read at once (log.txt, pictures.txt, checks.txt).
if [ -z "${MEMOGRAPH:-}" ]; then
  tar czf /tmp/culling_run.tar.gz -C "$OUT" .
  find "$OUT" -maxdepth 1 -type f ! -name log.txt ! -name pictures.txt ! -name checks.txt -delete
  mv /tmp/culling_run.tar.gz "$OUT/"
fi
