#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs every test (ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
# lavapipe and vulkaninfo want a runtime directory; CI may have none.
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
# On a clean machine (CI) lavapipe's LLVM code generation of every pipeline takes most of the
# suite's time; without LLVM's optimisation passes the slowest tests run 2.2x faster
# (docs/design/testing.md, "Time"). Only this command's tests are affected: a render outside
# them keeps the driver's default.
export GALLIVM_PERF="${GALLIVM_PERF:-nopt}"
cd build
ctest --output-on-failure --timeout 900 -j 2
