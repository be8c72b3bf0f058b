#!/usr/bin/env bash
# Builds the GPU-machine bundle for issue 4's benchmark sweep: everything of
# tools/bundle_device.sh (bundle/memograph, the Vulkan loader in .gl/, bundle/run_device.sh)
# plus bundle/run_issue4.sh (tools/issue4/run_issue4.sh: the Tables 6.1-6.3 variants),
# bundle/quality.sh (tools/issue4/quality.sh: --gpu compares the variants' pictures) and
# bundle/VERSION (the commit the binary was built from, which the run records).
#
# Usage: tools/bundle_issue4.sh            (from the repository root)
# Then one device call (results come back under $OUT, 5 files):
#   run(kind="nvidia-h100-x1", carry=["bundle", ".gl"], timeout_s=600,
#       command="bash bundle/run_issue4.sh")
# and here: tools/results/make_tables --summary .../issue4_summary.csv \
#   --frames .../issue4_frames.tar.gz --steps .../issue4_steps.tsv
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash tools/bundle_device.sh
cp tools/issue4/run_issue4.sh bundle/run_issue4.sh
cp tools/issue4/quality.sh bundle/quality.sh
chmod +x bundle/run_issue4.sh bundle/quality.sh
dirty=""
if git status --porcelain --untracked-files=no | grep -q .; then
  dirty=" (with uncommitted changes)"
fi
echo "$(git rev-parse --short HEAD) $(git log -1 --format=%s)$dirty" >bundle/VERSION
echo "bundle_issue4: bundle/run_issue4.sh for $(cat bundle/VERSION)"
