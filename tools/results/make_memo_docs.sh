#!/usr/bin/env bash
# Rebuilds docs/results/memoization_tables.md and docs/results/memoization_plots/ from every
# device call kept under docs/results/: the H100 runs of the first session
# (memoization_h100/run*), then the H200 calls (memoization_h200/call*), oldest first, so a
# later call's run of the same scene and label replaces an earlier one (run 1's tile rows
# predate the rank-based tile computation and are replaced that way).
#   bash tools/results/make_memo_docs.sh [--no-png]
# --resweep: the re-sweep of the fixed code instead (bundle 50db56c, H200 calls 24 onwards, one
# binary on one machine), into docs/results/memoization_resweep_tables.md and
# docs/results/memoization_resweep_plots/ (OUT=… and PLOTS=… redirect them).
#   bash tools/results/make_memo_docs.sh --resweep [--no-png]
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ "${1:-}" = --resweep ]; then
  shift
  args=()
  for summary in $(printf "%s\n" docs/results/memoization_h200/call*_summary.csv | sort -V); do
    call=${summary%_summary.csv}
    number=${call##*call}
    [ "$number" -ge 24 ] || continue
    args+=(--summary "$summary" --frames "${call}_frames.tar.gz" --steps "${call}_steps.tsv")
  done
  python3 tools/results/make_tables "${args[@]}" \
    --out "${OUT:-docs/results/memoization_resweep_tables.md}" \
    --plots "${PLOTS:-docs/results/memoization_resweep_plots}" \
    --title "Memoization tables (thesis §6): the re-sweep of the fixed code, H200 calls 24 onwards (bundle 50db56c)" "$@"
  exit
fi
args=()
for call in docs/results/memoization_h100/run1 docs/results/memoization_h100/run2 \
  docs/results/memoization_h200/call1 docs/results/memoization_h200/call2 \
  docs/results/memoization_h200/call3 docs/results/memoization_h200/call4 \
  docs/results/memoization_h200/call5 docs/results/memoization_h200/call6 \
  docs/results/memoization_h200/call7 docs/results/memoization_h200/call8 \
  docs/results/memoization_h200/call9 docs/results/memoization_h200/call10 \
  docs/results/memoization_h200/call11 docs/results/memoization_h200/call12 \
  docs/results/memoization_h200/call13 docs/results/memoization_h200/call14 \
  docs/results/memoization_h200/call15 docs/results/memoization_h200/call17 \
  docs/results/memoization_h200/call18 docs/results/memoization_h200/call19 \
  docs/results/memoization_h200/call20; do
  args+=(--summary "${call}_summary.csv" --frames "${call}_frames.tar.gz"
    --steps "${call}_steps.tsv")
done
python3 tools/results/make_tables "${args[@]}" --out docs/results/memoization_tables.md \
  --plots docs/results/memoization_plots \
  --title "Memoization tables (thesis §6), H100 and H200 calls merged" "$@"
