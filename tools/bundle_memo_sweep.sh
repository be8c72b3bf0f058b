#!/usr/bin/env bash
# Builds the GPU-machine bundle for the memoization benchmark sweep: everything of
# tools/bundle_device.sh (bundle/memograph, the Vulkan loader in .gl/, bundle/run_device.sh)
# plus bundle/memo_sweep.sh (tools/bench/memo_sweep.sh: the Tables 6.1-6.3 variants),
# bundle/memo_quality.sh (tools/bench/memo_quality.sh: --gpu compares the variants'
# pictures) and bundle/VERSION (the commit the binary was built from, which the run records).
#
# Usage: tools/bundle_memo_sweep.sh        (from the repository root)
# Then one device call (results come back under $OUT, 5 files):
#   run(kind="nvidia-h200", carry=["bundle", ".gl"], timeout_s=600,
#       command="bash bundle/memo_sweep.sh")
# and here: tools/results/make_tables --summary .../summary.csv \
#   --frames .../frames.tar.gz --steps .../steps.tsv
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash tools/bundle_device.sh
cp tools/bench/memo_sweep.sh bundle/memo_sweep.sh
cp tools/bench/memo_quality.sh bundle/memo_quality.sh
chmod +x bundle/memo_sweep.sh bundle/memo_quality.sh
dirty=""
if git status --porcelain --untracked-files=no | grep -q .; then
  dirty=" (with uncommitted changes)"
fi
echo "$(git rev-parse --short HEAD) $(git log -1 --format=%s)$dirty" >bundle/VERSION
echo "bundle_memo_sweep: bundle/memo_sweep.sh for $(cat bundle/VERSION)"
