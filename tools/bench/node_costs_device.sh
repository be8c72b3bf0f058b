#!/usr/bin/env bash
# Measures the cost of every node that compiler/cut.cpp's kNodeCosts estimates (docs/design/
# memoization.md, "Measuring the node costs"): tools/bench/node_cost_graphs.py writes graphs
# that evaluate one node as a dependent chain of copies a pixel (each copy's input is a
# uv-varying base plus the previous copy's output; about WORK Add units of estimated work a
# pixel, so hundreds of copies of a cheap node; an fBm node at Detail 2 and 8, for its
# octave term), Add and Mul (the unit), and baselines (the same chains without a node);
# `memograph bake --time` times each graph's evaluation dispatch at SIZE (median of
# DISPATCHES, timestamp queries, one float stored a pixel). stdout ends with the table:
# each node's ns per evaluation, copies, cost in Add units, the estimate and their ratio
# (also node_costs.txt; commit its rows as tools/bench/node_timings_<gpu>.txt and run
# `node_cost_graphs.py calibrate` over them).
# After tools/bundle_device.sh, on the GPU machine (carry bundle, .gl and tools; compiler/
# travels with the working tree):
#   OUT=$OUT bash tools/bench/node_costs_device.sh
# NODES="NoiseTexture WaveTexture" times only those nodes (with Add, Mul and the baselines).
# Here, on lavapipe (figures are CPU timings, meaningless as costs; this checks the script):
#   MEMOGRAPH=build/tools/memograph SIZE=32x32 WORK=16 BAKE_TIMEOUT=900 \
#     bash tools/bench/node_costs_device.sh
set -uo pipefail
[ -n "${MEMOGRAPH:-}" ] || source bundle/device_env.sh
m=${MEMOGRAPH:-bundle/memograph}
OUT=${OUT:-/tmp/out}
SIZE=${SIZE:-2048x2048}
WORK=${WORK:-1024}
DISPATCHES=${DISPATCHES:-7}
# The bake's bound, under the device run's 300 s (lavapipe compiles the long chains slowly:
# give it more there).
BAKE_TIMEOUT=${BAKE_TIMEOUT:-280}
mkdir -p "$OUT"
graphs=$(mktemp -d)
trap 'rm -rf "$graphs"' EXIT
gpu=$(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | head -1)
{
  echo "${gpu:-no nvidia-smi}"
  python3 tools/bench/node_cost_graphs.py write --memograph "$m" --out "$graphs" \
    --work "$WORK" || exit 1
  start=$(date +%s)
  # One process bakes every graph: one device, one shader compiler. The baselines first,
  # then Add and Mul (the unit) with the nodes in name order, so that a bake cut short by
  # its bound still gives the table every node it reached.
  if [ -n "${NODES:-}" ]; then
    # Only these nodes (with Add and Mul, the unit, and every baseline): a second call for
    # nodes that a first one timed badly. Its table is in its own call's Add units.
    timed=("$graphs"/Add.mgraph "$graphs"/Mul.mgraph)
    for node in $NODES; do
      timed+=("$graphs/$node".mgraph "$graphs/${node}"_detail*.mgraph)
    done
    timed=($(ls "${timed[@]}" 2>/dev/null))
  else
    timed=("$graphs"/[A-Z]*.mgraph)
  fi
  timeout "$BAKE_TIMEOUT" "$m" bake "$graphs"/baseline_*.mgraph "${timed[@]}" \
    --size "$SIZE" --time "$DISPATCHES" >"$OUT/node_times.txt"
  rc=$?
  echo "bake --time rc $rc in $(($(date +%s) - start)) s (size $SIZE, work $WORK)"
  cat "$OUT/node_times.txt"
  {
    echo "# ${gpu:-unknown device}; bake --time $DISPATCHES at $SIZE"
    python3 tools/bench/node_cost_graphs.py table --plan "$graphs/plan.json" \
      --times "$OUT/node_times.txt"
  } >"$OUT/node_costs.txt" || exit 1
  cp "$graphs/plan.json" "$OUT/node_cost_plan.json"
  cat "$OUT/node_costs.txt"
} 2>&1 | tee "$OUT/node_costs_log.txt"
exit "${PIPESTATUS[0]}"
