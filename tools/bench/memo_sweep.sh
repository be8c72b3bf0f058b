#!/usr/bin/env bash
# The memoization benchmark sweep: the runs behind the project's Tables 6.1-6.3 (thesis §6)
# at 1920x1080, P = 6, L = 4 over a 300-camera path, in ONE device call of at most 600 s.
# tools/bundle_memo_sweep.sh copies it to bundle/memo_sweep.sh; on the GPU machine:
#   bash bundle/memo_sweep.sh [--tables defaults,6.1,6.1s,6.1b,diag,6.2,6.3] [--match REGEX]
#                             [--skip-done STEPS.tsv]... [--budget S] [--order table|pipeline] [--list]
#   (--skip-done: leave out the rows an earlier call's steps.tsv lists as ok, e.g. the calls
#   of an interrupted sweep, carried with the working tree;
#   --order pipeline: run rows that differ only in --cache-entries one after the other, so the
#   driver compiles their pipeline once (35 s on the classroom) instead of once a row;
#   --list: print the rows selected and stop; MEMOGRAPH=bundle/ab/<rev>/memograph, after
#   tools/bundle_ab.sh <rev>, continues a sweep with an earlier commit's binary)
# and here, on lavapipe, end to end at a tiny size (64x36, a 4-camera path):
#   bash tools/bench/memo_sweep.sh --dry-run [--match REGEX]
#
# Results under $OUT (the device tool returns 8 files at most, each < 16 MB):
#   summary.csv    one `memograph bench --csv` line per run that finished
#   frames.tar.gz  every run's per-frame CSV (frames/<scene>_<label>_<W>x<H>.csv)
#   steps.tsv      each step: status (ok, partial: stopped by its time limit with the
#                  frames so far, timeout, skipped, failed), seconds, limit, table, scene, label, flags
#   log.txt        everything printed;   env.txt  GPU, driver, bundle commit
# tools/results/make_tables turns them into tables and plots (out/memoization_tables.md).
#
# Order is priority: a step whose time limit no longer fits in what is left of --budget is
# skipped (and listed as such), so a call always ends in time with the most important
# figures. Run the rest in later calls with --tables / --match.
set -uo pipefail
shopt -s extglob

usage() {
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
}

dry=0 list=0 tables="defaults,6.1,6.1s,6.1b,diag,6.2,6.3" match="" budget="" order=table
done_steps=()
while [ $# -gt 0 ]; do
  case $1 in
  --dry-run) dry=1 ;;
  --list) list=1 ;;
  --tables | --match | --budget | --skip-done | --order)
    [ $# -ge 2 ] || { echo "memo_sweep.sh: $1 needs a value" >&2; exit 2; }
    case $1 in
    --tables) tables=$2 ;; --match) match=$2 ;; --budget) budget=$2 ;; --order) order=$2 ;;
    --skip-done)
      [ -r "$2" ] || { echo "memo_sweep.sh: --skip-done: cannot read '$2'" >&2; exit 2; }
      done_steps+=("$2") ;;
    esac
    shift ;;
  -h | --help) usage; exit 0 ;;
  *) echo "memo_sweep.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [ "$order" != table ] && [ "$order" != pipeline ]; then
  echo "memo_sweep.sh: --order takes table or pipeline, not '$order'" >&2
  exit 2
fi
if [ -n "$budget" ] && ! [[ $budget =~ ^[0-9]+$ ]]; then
  echo "memo_sweep.sh: --budget takes whole seconds, not '$budget'" >&2
  exit 2
fi

# Variants: one row per run. limit = the step's time limit in seconds on an H100/H200 (about
# 1.5x the estimate, set-up included; raised for the rows that ran past it with bundles
# 422fe9f, whose materials cost more than the first sweep's, and 50db56c: the small tile
# caches' 520-650 ms frames (2^18 and 2^21 texels: 300 frames and a 25-37 s pipeline build),
# and the small texel caches without eviction or with random or LRW-counter eviction, which
# took 158, 169 and 103 s); cameras = path length; stride > 1 only without a cache (the
# bench refuses it otherwise). Labels are the contract with make_tables:
#   <kind>_s<log2 texels>_<eviction>[-<clock>][_sec]   kind: texel, tile (4x4 nearest),
#   tilebil (4x4 bilinear); sec: memoization at secondary hits only; none, floor: no cache.
# Sizes count texels, as the thesis does: a 4x4 tile entry holds 16 (2^24 texels = 2^20 tiles).
read -r -d '' VARIANTS <<'TABLE'
# limit table scene      label                 cameras stride flags
# defaults: what a user gets from `--cache texel` or `--cache tile` and nothing else, against
# Table 6.1's rows below (make_tables prints the ratio).
  120   defaults classroom texel_default       300     1      --cache texel
  120   defaults classroom tile_default        300     1      --cache tile
  150   6.1   classroom  none                  300     10     --cache none
  120   6.1   classroom  texel_s24_lru-counter 300     1      --cache texel --cache-entries 16777216 --eviction lru --clock counter
  120   6.1   classroom  tile_s24_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter
  130   6.1   classroom  tilebil_s24_lru-counter 300   1      --cache tile --tile 4x4 --filter bilinear --cache-entries 1048576 --eviction lru --clock counter
  40    6.1   classroom  floor                 300     10     --cache none --floor-materials
  60    6.1   landscape  none                  300     10     --cache none
  60    6.1   landscape  texel_s24_lru-counter 300     1      --cache texel --cache-entries 16777216 --eviction lru --clock counter
  60    6.1   landscape  tile_s24_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter
  60    6.1   landscape  tilebil_s24_lru-counter 300   1      --cache tile --tile 4x4 --filter bilinear --cache-entries 1048576 --eviction lru --clock counter
  20    6.1   landscape  floor                 300     10     --cache none --floor-materials
  200   6.1s  classroom  texel_s24_lru-counter_sec 300 1      --cache texel --cache-entries 16777216 --eviction lru --clock counter --cache-secondary-only
  230   6.1s  classroom  tile_s24_lru-counter_sec 300  1      --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --cache-secondary-only
  240   6.1s  classroom  tilebil_s24_lru-counter_sec 300 1    --cache tile --tile 4x4 --filter bilinear --cache-entries 1048576 --eviction lru --clock counter --cache-secondary-only
  110   6.1s  landscape  texel_s24_lru-counter_sec 300 1      --cache texel --cache-entries 16777216 --eviction lru --clock counter --cache-secondary-only
  120   6.1s  landscape  tile_s24_lru-counter_sec 300  1      --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --cache-secondary-only
  120   6.1s  landscape  tilebil_s24_lru-counter_sec 300 1    --cache tile --tile 4x4 --filter bilinear --cache-entries 1048576 --eviction lru --clock counter --cache-secondary-only
# diag: where the memoized frame's time over the floor goes. Frame time against misses per
# frame (make_tables' fit) leaves ~50 ms on the classroom at zero misses; these rows vary
# one suspect each: value bytes per lookup (fp16 halves them), the callable dispatch (a
# raygen with call sites keeps more state live; switch evaluates misses inline), the probe
# loop (D = 1) and the working set (a mip bias of -1: texels twice as wide). The switch rows
# get 400 s: the driver's compile of the 88 inlined materials ran past 180 s in call 1.
  120   diag  classroom  texel_s24_lru-counter_fp16 300 1     --cache texel --cache-entries 16777216 --eviction lru --clock counter --value-format fp16
  400   diag  classroom  texel_s24_lru-counter_switch 300 1   --cache texel --cache-entries 16777216 --eviction lru --clock counter --material-dispatch switch
  400   diag  classroom  tile_s24_lru-counter_switch 300 1    --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --material-dispatch switch
  120   diag  classroom  texel_s24_lru-counter_p1 300  1      --cache texel --cache-entries 16777216 --eviction lru --clock counter --probe 1
  120   diag  classroom  texel_s24_lru-counter_bias-1 300 1   --cache texel --cache-entries 16777216 --eviction lru --clock counter --mip-bias -1
# The cache's own cost: the floor's constant materials with the cache on (every lookup as
# in a real run, every miss free), against the floor without it.
  40    diag  classroom  floor_texel_s24_lru-counter 300 1    --cache texel --cache-entries 16777216 --eviction lru --clock counter --floor-materials
  40    diag  classroom  floor_tile_s24_lru-counter 300 1     --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --floor-materials
# The real materials with (almost) no misses: a static camera after warm-up. Against the
# floor with the cache (above) this separates what the callables cost by being there from
# what the misses cost, which the path's runs only give through a fit.
  120   diag  classroom  texel_s24_lru-counter_static 300 1   --cache texel --cache-entries 16777216 --eviction lru --clock counter --static-camera
  40    diag  classroom  floor_texel_s24_lru-counter_static 300 1 --cache texel --cache-entries 16777216 --eviction lru --clock counter --floor-materials --static-camera
# Thesis §5.1: one primary ray shared by the P paths of a pixel (`--shared-primary`), which
# makes a primary hit one lookup (or evaluation) instead of P: secondary-only caching then
# evaluates P times fewer primary graphs.
  110   diag  classroom  none_shared           300     10     --cache none --shared-primary
  120   diag  classroom  texel_s24_lru-counter_shared 300 1   --cache texel --cache-entries 16777216 --eviction lru --clock counter --shared-primary
  120   diag  classroom  texel_s24_lru-counter_sec_shared 300 1 --cache texel --cache-entries 16777216 --eviction lru --clock counter --cache-secondary-only --shared-primary
# Tile repacks on NVIDIA (docs/design/memoization.md, "The tile cache"): §5.4.4's grouping pairs tiles of one material
# in an iteration, so a pass's lanes call one callable; whether the driver then regroups
# lanes less shows in the repack and fallback counters.
  120   diag  classroom  tile_s24_lru-counter_group 300 1     --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --group-by-material
  40    diag  classroom  floor_tile_s24_lru-counter_group 300 1 --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --group-by-material --floor-materials
# The deferred tile fill (--tile-fill deferred): a missed tile is queued and computed by a
# second pass after the frame, one invocation per texel, so no lane has to come back from a
# callable in place (the repacks above). Against the subgroup rows: the large cache, the
# small one (2^17 tiles, where it loses: a frame's tiles no longer fit), the landscape, and
# the floor (its own cost).
  120   diag  classroom  tile_s24_lru-counter_deferred 300 1  --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --tile-fill deferred
  40    diag  classroom  floor_tile_s24_lru-counter_deferred 300 1 --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --tile-fill deferred --floor-materials
  60    diag  landscape  tile_s24_lru-counter_deferred 300 1  --cache tile --tile 4x4 --filter nearest --cache-entries 1048576 --eviction lru --clock counter --tile-fill deferred
  150   diag  classroom  tile_s21_lru-counter_deferred 300 1  --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction lru --clock counter --tile-fill deferred
  150   diag  classroom  tile_s21_random_deferred 300 1       --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction random --tile-fill deferred
# The hit-rate target (99.9 %): at 2^26 texels almost nothing is evicted (6.1b: 99.880 % tile,
# 99.758 % texel) and the remaining misses are texels the path shows for the first time;
# texels twice as wide (mip bias -1, twice the picture error) halve those.
  100   diag  classroom  tile_s26_lru-frame_bias-1 300 1      --cache tile --tile 4x4 --filter nearest --cache-entries 4194304 --eviction lru --clock frame --mip-bias -1
  100   diag  classroom  texel_s26_lru-frame_bias-1 300 1     --cache texel --cache-entries 67108864 --eviction lru --clock frame --mip-bias -1
# 6.1b: Table 6.1's variants with a 4x larger cache (2^26 texels = 2^22 4x4 tiles): the
# classroom's working set overflows 2^24 texels (occupancy reaches S within the path).
  100   6.1b  classroom  texel_s26_lru-frame   300     1      --cache texel --cache-entries 67108864 --eviction lru --clock frame
  100   6.1b  classroom  tile_s26_lru-frame    300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 4194304 --eviction lru --clock frame
  100   6.1b  classroom  tilebil_s26_lru-frame 300     1      --cache tile --tile 4x4 --filter bilinear --cache-entries 4194304 --eviction lru --clock frame
  50    6.1b  landscape  tile_s26_lru-frame    300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 4194304 --eviction lru --clock frame
# Table 6.2: eviction strategies on the classroom, large (2^23 texels) then small (2^21).
  160   6.2   classroom  texel_s23_none        300     1      --cache texel --cache-entries 8388608 --eviction none
  120   6.2   classroom  texel_s23_random      300     1      --cache texel --cache-entries 8388608 --eviction random
  120   6.2   classroom  texel_s23_lrw-frame   300     1      --cache texel --cache-entries 8388608 --eviction lrw --clock frame
  120   6.2   classroom  texel_s23_lru-frame   300     1      --cache texel --cache-entries 8388608 --eviction lru --clock frame
  120   6.2   classroom  texel_s23_lrw-counter 300     1      --cache texel --cache-entries 8388608 --eviction lrw --clock counter
  120   6.2   classroom  texel_s23_lru-counter 300     1      --cache texel --cache-entries 8388608 --eviction lru --clock counter
  180   6.2   classroom  tile_s23_none         300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction none
  120   6.2   classroom  tile_s23_random       300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction random
  120   6.2   classroom  tile_s23_lrw-frame    300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction lrw --clock frame
  120   6.2   classroom  tile_s23_lru-frame    300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction lru --clock frame
  120   6.2   classroom  tile_s23_lrw-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction lrw --clock counter
  120   6.2   classroom  tile_s23_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction lru --clock counter
  200   6.2   classroom  texel_s21_none        300     1      --cache texel --cache-entries 2097152 --eviction none
  190   6.2   classroom  texel_s21_random      300     1      --cache texel --cache-entries 2097152 --eviction random
  150   6.2   classroom  texel_s21_lrw-frame   300     1      --cache texel --cache-entries 2097152 --eviction lrw --clock frame
  150   6.2   classroom  texel_s21_lru-frame   300     1      --cache texel --cache-entries 2097152 --eviction lru --clock frame
  190   6.2   classroom  texel_s21_lrw-counter 300     1      --cache texel --cache-entries 2097152 --eviction lrw --clock counter
  150   6.2   classroom  texel_s21_lru-counter 300     1      --cache texel --cache-entries 2097152 --eviction lru --clock counter
  240   6.2   classroom  tile_s21_none         300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction none
  260   6.2   classroom  tile_s21_random       300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction random
  310   6.2   classroom  tile_s21_lrw-frame    300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction lrw --clock frame
  230   6.2   classroom  tile_s21_lru-frame    300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction lru --clock frame
  320   6.2   classroom  tile_s21_lrw-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction lrw --clock counter
  200   6.2   classroom  tile_s21_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction lru --clock counter
# Table 6.3: cache sizes, LRU with the counter clock (2^21 and 2^23 on the classroom are
# Table 6.2's lru-counter runs, so they are not repeated here).
  150   6.3   classroom  texel_s18_lru-counter 300     1      --cache texel --cache-entries 262144 --eviction lru --clock counter
  150   6.3   classroom  texel_s19_lru-counter 300     1      --cache texel --cache-entries 524288 --eviction lru --clock counter
  150   6.3   classroom  texel_s20_lru-counter 300     1      --cache texel --cache-entries 1048576 --eviction lru --clock counter
  150   6.3   classroom  texel_s22_lru-counter 300     1      --cache texel --cache-entries 4194304 --eviction lru --clock counter
  240   6.3   classroom  tile_s18_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 16384 --eviction lru --clock counter
  150   6.3   classroom  tile_s19_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 32768 --eviction lru --clock counter
  220   6.3   classroom  tile_s20_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 65536 --eviction lru --clock counter
  150   6.3   classroom  tile_s22_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 262144 --eviction lru --clock counter
  60    6.3   landscape  texel_s18_lru-counter 300     1      --cache texel --cache-entries 262144 --eviction lru --clock counter
  60    6.3   landscape  texel_s19_lru-counter 300     1      --cache texel --cache-entries 524288 --eviction lru --clock counter
  90    6.3   landscape  texel_s20_lru-counter 300     1      --cache texel --cache-entries 1048576 --eviction lru --clock counter
  60    6.3   landscape  texel_s21_lru-counter 300     1      --cache texel --cache-entries 2097152 --eviction lru --clock counter
  60    6.3   landscape  texel_s22_lru-counter 300     1      --cache texel --cache-entries 4194304 --eviction lru --clock counter
  60    6.3   landscape  texel_s23_lru-counter 300     1      --cache texel --cache-entries 8388608 --eviction lru --clock counter
  90    6.3   landscape  tile_s18_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 16384 --eviction lru --clock counter
  90    6.3   landscape  tile_s19_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 32768 --eviction lru --clock counter
  90    6.3   landscape  tile_s20_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 65536 --eviction lru --clock counter
  90    6.3   landscape  tile_s21_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 131072 --eviction lru --clock counter
  90    6.3   landscape  tile_s22_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 262144 --eviction lru --clock counter
  90    6.3   landscape  tile_s23_lru-counter  300     1      --cache tile --tile 4x4 --filter nearest --cache-entries 524288 --eviction lru --clock counter
TABLE

# Settings of a real run and of the dry run. The dry run keeps every variant and flag but
# renders 64x36 over a 4-camera path (strides become 2) with 4x2 subgroup tiles, so here on
# lavapipe it checks the script, the CLI's acceptance of each flag and make_tables end to
# end, not the figures; caches are capped at 2^16 entries (lavapipe's storage-buffer range
# is 128 MiB). lavapipe refuses two kinds of row, as it should: the classroom's
# subgroup-fill tile rows (its 88 materials need the pipeline backend, whose raygen has no
# subgroup operations on lavapipe) and the switch rows (88 materials in one shader).
size=1920x1080 warmup=2 paths=6 bounces=4
if [ $dry = 1 ]; then
  size=64x36 warmup=1 paths=1 bounces=2
  m=${MEMOGRAPH:-build/tools/memograph}
  OUT=${OUT:-/tmp/memo_sweep_dry}
  budget=${budget:-1000000}
else
  # MEMOGRAPH: another bundled binary, e.g. bundle/ab/<rev>/memograph of tools/bundle_ab.sh,
  # to continue a sweep with the binary its first calls used.
  m=${MEMOGRAPH:-bundle/memograph}
  OUT=${OUT:-/tmp/out}
  budget=${budget:-585} # the device call's 600 s, less packing and set-up
  source bundle/device_env.sh
fi
start=$(date +%s)
source tools/bench/megakernel_flags.sh  # shadingFlags
mkdir -p "$OUT"
work=$(mktemp -d /tmp/memo_sweep.XXXXXX)
mkdir -p "$work/csv" "$work/frames" "$work/claims" "$work/shaders"
log="$OUT/log.txt" steps="$OUT/steps.tsv"
: >"$log"
printf 'status\tseconds\tlimit_s\ttable\tscene\tlabel\tcameras\tstride\tflags\n' >"$steps"

# The rows selected by --tables and --match, less those --skip-done lists as ok, in order.
done_rows=""
if [ ${#done_steps[@]} -gt 0 ]; then
  done_rows=$(awk -F'\t' '$1 == "ok" { print $5 "/" $6 }' "${done_steps[@]}" | sort -u)
fi
rows=()
while IFS= read -r line; do
  line=${line%%#*}
  [ -n "${line// /}" ] || continue
  read -r limit table scene label cameras stride flags <<<"$line"
  [[ ",$tables," == *",$table,"* ]] || continue
  [ -z "$match" ] || [[ "$scene/$label" =~ $match ]] || continue
  [ -n "$done_rows" ] && grep -qxF "$scene/$label" <<<"$done_rows" && continue
  rows+=("$limit|$table|$scene|$label|$cameras|$stride|$flags")
done <<<"$VARIANTS"
# --order pipeline: a stable regrouping by scene and flags less the cache size, which is a
# buffer size and not part of the pipeline (eviction, clock, kind and filter are), so that the
# driver's shader cache (and --shader-cache) serves every row of a group after its first.
if [ "$order" = pipeline ] && [ ${#rows[@]} -gt 0 ]; then
  mapfile -t rows < <(for i in "${!rows[@]}"; do
    IFS='|' read -r _ _ scene _ _ _ flags <<<"${rows[$i]}"
    key="$scene ${flags/--cache-entries +([0-9])/}"
    printf '%s\t%06d\t%s\n' "$key" "$i" "${rows[$i]}"
  done | awk -F'\t' '!($1 in first) { first[$1] = NR } { printf "%06d\t%s\t%s\n", first[$1], $2, $3 }' |
    sort -k1,1n -k2,2n | cut -f3-)
fi
if [ $list = 1 ]; then
  for row in "${rows[@]}"; do
    IFS='|' read -r limit table scene label _ <<<"$row"
    printf '%s\t%s\t%s/%s\n' "$limit" "$table" "$scene" "$label"
  done
  exit 0
fi

# One step: a bench call under its own time limit, skipped when the budget cannot hold it.
run_step() {
  local i=$1 device=$2 limit table scene label cameras stride flags
  IFS='|' read -r limit table scene label cameras stride flags <<<"${rows[$i]}"
  if [ $dry = 1 ]; then
    cameras=4 limit=300
    [ "$stride" -gt 1 ] && stride=2
    # lavapipe's subgroups have 8 lanes: the subgroup fill's 4x4 tiles become 4x2 (the
    # deferred fill takes 4x4 as it is).
    [[ " $flags " == *" --tile-fill deferred "* ]] || flags=${flags//--tile 4x4/--tile 4x2}
    # Caches of at most 2^16 entries: the rows' sizes (up to 2.4 GB) exceed lavapipe's 128 MiB
    # storage-buffer range, and a 64x36 frame fills no more.
    if [[ $flags =~ --cache-entries\ ([0-9]+) ]] && [ "${BASH_REMATCH[1]}" -gt 65536 ]; then
      flags=${flags/--cache-entries ${BASH_REMATCH[1]}/--cache-entries 65536}
    fi
  fi
  local left=$((budget - ($(date +%s) - start)))
  if [ "$left" -lt "$limit" ]; then
    echo "== [$table] $scene $label: SKIPPED (needs ${limit} s, ${left} s left)"
    printf 'skipped\t0\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$limit" "$table" "$scene" "$label" \
      "$cameras" "$stride" "$flags" >>"$steps"
    return
  fi
  local strideFlags=() deviceFlags=() pathFlags=(--camera-frames "$cameras") limitFlags=()
  # The bench stops itself 10 s before the step's limit (its --time-limit counts set-up and
  # compiles too), so a run too slow for its limit still reports the frames it rendered
  # (status "partial") instead of being killed.
  [ "$limit" -gt 20 ] && limitFlags=(--time-limit $((limit - 10)))
  [ "$stride" -gt 1 ] && strideFlags=(--frame-stride "$stride")
  # A static camera renders `cameras` frames of the first camera (no path to length).
  [[ " $flags " == *" --static-camera "* ]] && pathFlags=()
  [ -n "$device" ] && deviceFlags=(--device "$device")
  echo "== [$table] $scene $label: $flags (limit ${limit} s)"
  local t0 status rc
  t0=$(date +%s)
  # shellcheck disable=SC2086 # $flags is a list of words from the table
  timeout "$limit" "$m" bench "builtin:$scene" --sizes "$size" --paths "$paths" \
    --bounces "$bounces" --warmup "$warmup" --frames $((cameras / stride)) \
    "${pathFlags[@]}" "${strideFlags[@]}" "${limitFlags[@]}" --label "$label" \
    --csv "$work/csv/$(printf %03d "$i").csv" --frames-csv "$work/frames/" \
    --shader-cache "$work/shaders" "${deviceFlags[@]}" "${shadingFlags[@]}" $flags
  rc=$?
  case $rc in 0) status=ok ;; 124 | 137) status=timeout ;; 2) status=usage ;; *) status=failed ;; esac
  # The summary line's last column: stopped_early (by --time-limit).
  if [ $status = ok ] && tail -n 1 "$work/csv/$(printf %03d "$i").csv" | grep -q ',1$'; then
    status=partial
  fi
  [ $rc = 0 ] || echo "STEP FAILED ($status, exit $rc): $scene $label"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$status" $(($(date +%s) - t0)) "$limit" \
    "$table" "$scene" "$label" "$cameras" "$stride" "$flags" >>"$steps"
}

# One lane per GPU: each takes the next unclaimed step (mkdir is atomic), so the order stays
# the priority order. DEVICES="0 1" on a 2-GPU machine; one lane, no --device, by default.
lane() {
  local device=$1 prefix=$2
  for i in "${!rows[@]}"; do
    mkdir "$work/claims/$i" 2>/dev/null || continue
    run_step "$i" "$device"
  done 2>&1 | sed -u "s/^/$prefix/" | tee -a "$log"
}
if [ -z "${DEVICES+x}" ] && [ $dry = 0 ]; then
  gpus=$(nvidia-smi -L 2>/dev/null | grep -c '^GPU' || true)
  DEVICES=""
  [ "${gpus:-0}" -gt 1 ] && DEVICES=$(seq -s ' ' 0 $((gpus - 1)))
fi
{
  if [ $dry = 1 ]; then
    echo "bundle: none, the working tree's build (dry run)"
  else
    echo "bundle: $(cat "$(dirname "$m")/VERSION" 2>/dev/null || echo "no VERSION beside $m")"
  fi
  nvidia-smi -L 2>/dev/null || true
  nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv 2>/dev/null || true
  "$m" render --list-devices 2>&1 || true
  echo "settings: $size P=$paths L=$bounces warmup=$warmup budget=${budget}s tables=$tables" \
    "match='$match' devices='${DEVICES:-}' steps=${#rows[@]}"
} 2>&1 | tee "$OUT/env.txt" | tee -a "$log"
if [ -z "${DEVICES:-}" ]; then
  lane "" ""
else
  for d in $DEVICES; do lane "$d" "[gpu$d] " & done
  wait
fi

# One summary CSV (the header once, steps in order) and one archive of per-frame CSVs: the
# device tool returns 8 files at most. A step that crashed may leave an empty CSV (its
# header still in the stream's buffer): skipped, so the next step's header is the one kept.
first=1
for f in "$work"/csv/*.csv; do
  [ -s "$f" ] || continue
  if [ $first = 1 ]; then cat "$f"; first=0; else tail -n +2 "$f"; fi
done >"$OUT/summary.csv"
tar czf "$OUT/frames.tar.gz" -C "$work" frames
echo "== done in $(($(date +%s) - start)) s: $(grep -c $'^ok\t' "$steps") ok," \
  "$(grep -c $'^partial\t' "$steps") partial, $(grep -c $'^skipped\t' "$steps") skipped," \
  "$(grep -cvE $'^(ok|partial|skipped|status)\t' "$steps") failed" |
  tee -a "$log"
rm -rf "$work"
