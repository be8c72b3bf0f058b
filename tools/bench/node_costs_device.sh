#!/usr/bin/env bash
# Measures the cost of every node that compiler/cut.cpp's kNodeCosts estimates (docs/design/
# memoization.md, "Measuring the node costs"): tools/bench/node_cost_graphs.py writes graphs
# that evaluate one node COPIES times a pixel on inputs varying with uv (an fBm node at Detail
# 2 and 8, for its octave term), Add and Mul (the unit) and two baselines (the same inputs
# and sums without a node); `memograph bake --time` times each graph's evaluation dispatch
# at SIZE (median of DISPATCHES, timestamp queries); the table gives each node's ns per
# evaluation, its cost in Add units, the estimate and their ratio (node_costs.txt).
# After tools/bundle_device.sh, on the GPU machine (carry bundle, .gl and tools; compiler/
# travels with the working tree):
#   OUT=$OUT bash tools/bench/node_costs_device.sh
# Here, on lavapipe (figures are CPU timings, meaningless as costs; this checks the script):
#   MEMOGRAPH=build/tools/memograph SIZE=32x32 COPIES=4 bash tools/bench/node_costs_device.sh
set -uo pipefail
[ -n "${MEMOGRAPH:-}" ] || source bundle/device_env.sh
m=${MEMOGRAPH:-bundle/memograph}
OUT=${OUT:-/tmp/out}
SIZE=${SIZE:-2048x2048}
COPIES=${COPIES:-16}
DISPATCHES=${DISPATCHES:-7}
mkdir -p "$OUT"
graphs=$(mktemp -d)
trap 'rm -rf "$graphs"' EXIT
{
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || true
  python3 tools/bench/node_cost_graphs.py write --memograph "$m" --out "$graphs" \
    --copies "$COPIES" || exit 1
  start=$(date +%s)
  # One process bakes every graph: one device, one shader compiler.
  timeout 400 "$m" bake "$graphs" --size "$SIZE" --time "$DISPATCHES" >"$OUT/node_times.txt"
  rc=$?
  echo "bake --time rc $rc in $(($(date +%s) - start)) s (size $SIZE, $COPIES copies)"
  cat "$OUT/node_times.txt"
  python3 tools/bench/node_cost_graphs.py table --plan "$graphs/plan.json" \
    --times "$OUT/node_times.txt" >"$OUT/node_costs.txt" || exit 1
  cp "$graphs/plan.json" "$OUT/node_cost_plan.json"
  cat "$OUT/node_costs.txt"
} 2>&1 | tee "$OUT/node_costs_log.txt"
exit "${PIPESTATUS[0]}"
