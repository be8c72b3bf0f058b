#!/usr/bin/env bash
# The Slurm job arrays for real (issue 44): a private single-node cluster (munged,
# slurmctld, slurmd; slurm_cluster.sh) runs tools/slurm/memograph_array.sbatch on lavapipe.
#   1. A 4-task array renders 8 frames of a tiny built-in scene; one task is cancelled
#      before it starts and one finished frame is deleted (a preempted task's loss). The
#      collector names the two tasks; requeued with the same arguments (the script passes
#      --resume), they complete the set, and every frame is byte-identical to one local run.
#   2. A 3-task array bakes a small library in shards; the union is the unsharded bake,
#      byte for byte.
# usage: slurm_array_test.sh MEMOGRAPH REPOSITORY
set -euo pipefail
memograph=$(realpath "$1")
repo=$(realpath "$2")
here=$(dirname "$(realpath "${BASH_SOURCE[0]}")")
source "$here/slurm_cluster.sh"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/memograph-slurm.XXXXXX")
cleanup() {
  stop_slurm_cluster
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 1' INT TERM  # a ctest timeout or ^C still stops the daemons (through EXIT)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$tmp}
start=$SECONDS
start_slurm_cluster "$tmp/cluster" "$(nproc)"
echo "cluster up in $((SECONDS - start)) s"

fail() {
  echo "FAIL: $*"
  for log in "$tmp"/logs/*.out; do
    [ -f "$log" ] && { echo "--- $log"; cat "$log"; }
  done
  exit 1
}

# Waits for every task of job $1 to leave the queue (at most $2 seconds).
wait_for_job() {
  local job=$1 limit=$2 waited=0
  while [ -n "$(squeue -h -j "$job" -o %i 2>/dev/null)" ]; do
    [ "$waited" -lt $((limit * 5)) ] || {
      squeue -j "$job"
      fail "job $job still queued after $limit s"
    }
    sleep 0.2
    waited=$((waited + 1))
  done
}

# No GPU here: the tasks ask for none (the script's --gres=gpu:1 is overridden the way a
# site without gres would) and render on lavapipe; one CPU a task so that two run at once.
export SBATCH_GRES=none SBATCH_CPUS_PER_TASK=1
export MEMOGRAPH=$memograph MEMOGRAPH_CACHE_HOME=$tmp/node-cache
# The node cache holds memograph's SPIR-V; Mesa's shader cache stays where it is without that
# XDG_CACHE_HOME, since a fresh one compiles every lavapipe pipeline anew, seconds a render.
mesa_cache=${MESA_SHADER_CACHE_DIR:-${XDG_CACHE_HOME:-${HOME:+$HOME/.cache}}}
[ -z "$mesa_cache" ] || export MESA_SHADER_CACHE_DIR=$mesa_cache
script=$repo/tools/slurm/memograph_array.sbatch
collect=(python3 "$repo/tools/slurm/collect_frames.py")
mkdir -p "$tmp/logs" "$tmp/frames" "$tmp/local"

scene=builtin:landscape:terrain=2
render_args=(--camera-path "$repo/examples/camera_paths/landscape.campath" --size 16x9
  --bounces 2 --paths 2 --seed 7)

# The reference: one local run of all 8 frames.
XDG_CACHE_HOME=$tmp/node-cache "$memograph" render "$scene" "${render_args[@]}" \
  --frame-range 0:7 --out "$tmp/local/frame_####.pfm" 2>"$tmp/logs/local.out" ||
  fail "the local render failed"

# Held at submission, so that task 2 is cancelled before it runs, whatever the timing.
job=$(sbatch --parsable --hold --array=0-3 --chdir="$tmp" --output="$tmp/logs/render_%a.out" \
  "$script" render 0:7 2 -- "$scene" "${render_args[@]}" --out "$tmp/frames/frame_####.pfm")
scancel "${job}_2"
scontrol release "$job"
wait_for_job "$job" 120
ls "$tmp/frames"

# A frame that task 0 finished is lost (as a node's local copy would be on preemption).
rm "$tmp/frames/frame_0001.pfm"
set +e
report=$("${collect[@]}" --out "$tmp/frames/frame_####.pfm" --frame-range 0:7 --per-task 2)
status=$?
set -e
echo "$report"
[ "$status" -eq 1 ] || fail "the collector returned $status with frames missing, not 1"
tasks=$(sed -n 's/^tasks: //p' <<<"$report")
[ "$tasks" = "0 2" ] || fail "the collector lists tasks '$tasks' to requeue, not '0 2'"

# The requeue: the same arguments, only the tasks the collector named.
requeue=$(sbatch --parsable --array="${tasks// /,}" --chdir="$tmp" \
  --output="$tmp/logs/requeue_%a.out" \
  "$script" render 0:7 2 -- "$scene" "${render_args[@]}" --out "$tmp/frames/frame_####.pfm")
wait_for_job "$requeue" 120
"${collect[@]}" --out "$tmp/frames/frame_####.pfm" --frame-range 0:7 --per-task 2 ||
  fail "frames still missing after the requeue"
grep -q "1 written, 1 complete already" "$tmp/logs/requeue_0.out" ||
  fail "the requeued task 0 did not skip its complete frame (--resume)"
for f in 0 1 2 3 4 5 6 7; do
  name=frame_000$f.pfm
  cmp "$tmp/local/$name" "$tmp/frames/$name" || fail "$name differs from the local run's"
done
echo "render: 8 frames over 4 tasks and a requeue match one local run byte for byte"

# The bake: 5 graphs in 3 shards against one unsharded bake.
mkdir -p "$tmp/library"
for graph in car_paint ceramic_tiles checker_floor lava marble; do
  cp "$repo/examples/graphs/$graph.mgraph" "$tmp/library/"
done
bake_args=("$tmp/library" --size 8x8 --format pfm --quiet)
XDG_CACHE_HOME=$tmp/node-cache "$memograph" bake "${bake_args[@]}" --out "$tmp/baked_local" \
  >"$tmp/logs/bake_local.out" 2>&1 || fail "the local bake failed"
bake=$(sbatch --parsable --array=0-2 --chdir="$tmp" --output="$tmp/logs/bake_%a.out" \
  "$script" bake 3 -- "${bake_args[@]}" --out "$tmp/baked_sharded")
wait_for_job "$bake" 120
diff -r "$tmp/baked_local" "$tmp/baked_sharded" || fail "the sharded bake differs"
[ "$(ls "$tmp/baked_local" | wc -l)" -gt 5 ] || fail "the bake wrote too few images"
echo "bake: 3 shards make the unsharded bake byte for byte"
echo "PASS in $((SECONDS - start)) s"
