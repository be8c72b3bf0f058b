#!/usr/bin/env bash
# Builds the GPU bundle (tools/bundle_device.sh) and, beside it, the same memograph binary at
# other commits, so that one device call can compare them on the same GPU (an A/B, or a
# bisection of a performance change): bundle/ab/<short-rev>/memograph. Everything must stay
# under the 64 MiB a device call carries (about 10 MiB a binary: four revisions at most).
#
# Usage: tools/bundle_ab.sh [--material-scene] REV...    (from the repository root)
# --material-scene: the bundle of tools/bundle_memo_scenes.sh instead, with the Blender
# material scene's pack (ab_device.sh's scene `pack`; needs Blender and the io build).
# Then, on the GPU machine (carry bundle and .gl):
#   bash tools/bench/ab_device.sh [--scenes "pack classroom"] [--frames N] [bench flags...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bundle_script=tools/bundle_device.sh
if [ "${1:-}" = --material-scene ]; then
  bundle_script=tools/bundle_memo_scenes.sh
  shift
fi
[ $# -ge 1 ] || { echo "usage: tools/bundle_ab.sh [--material-scene] REV..." >&2; exit 2; }
[ $# -le 4 ] || { echo "bundle_ab: at most 4 revisions fit beside the bundle" >&2; exit 2; }
for rev in "$@"; do
  git rev-parse --verify --quiet "$rev^{commit}" >/dev/null ||
    { echo "bundle_ab: '$rev' is not a commit" >&2; exit 2; }
done

bash "$bundle_script"
rm -rf bundle/ab
for rev in "$@"; do
  short=$(git rev-parse --short=7 "$rev")
  # A fixed source path per revision, so that its build folder (whose CMake cache names the
  # source) is reused by the next call instead of refused.
  tree=/tmp/memograph_ab_src/$short
  git worktree remove --force "$tree" 2>/dev/null || rm -rf "$tree"
  git worktree prune
  mkdir -p /tmp/memograph_ab_src
  git worktree add --quiet --detach "$tree" "$rev"
  build="$root/build-ab/$short"
  cmake -S "$tree" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMEMOGRAPH_BUILD_TESTS=OFF \
    -DMEMOGRAPH_BUILD_IO=OFF -DCMAKE_EXE_LINKER_FLAGS="-static-libstdc++ -static-libgcc" >/dev/null
  cmake --build "$build" --target memograph -j"${JOBS:-2}"
  mkdir -p "bundle/ab/$short"
  cp "$build/tools/memograph" "bundle/ab/$short/memograph"
  strip "bundle/ab/$short/memograph"
  git -C "$tree" log -1 --format='%h %s' >"bundle/ab/$short/VERSION"
  git worktree remove --force "$tree"
done
git log -1 --format='%h %s' >bundle/VERSION
size=$(du -sm bundle .gl | awk '{s += $1} END {print s}')
echo "bundle_ab: bundle/ (with $(ls bundle/ab | wc -l) other revisions) and .gl/ hold ${size} MiB (limit 64)"
[ "$size" -le 64 ] || { echo "bundle_ab: too large; fewer revisions" >&2; exit 1; }
