#!/usr/bin/env bash
# Builds the GPU-machine bundle for the material scenes' memoization table
# (tools/bench/memo_scenes_device.sh): everything of tools/bundle_device.sh (bundle/memograph
# without the io module, the Vulkan loader in .gl/) plus bundle/material_scene.mgpack, the
# Blender material scene (examples/blender/material_scene.blend) imported here through
# Blender and assimp and written as a scene pack with its camera path, which the bundle's
# binary reads without assimp or OpenImageIO; bundle/material_scene.camera (the path, for
# the still camera of the picture comparison) and bundle/VERSION.
#
# Needs a full build with the io module (MEMOGRAPH, default build/tools/memograph) and
# Blender 3.4 on the PATH (BLENDER, default blender).
# Usage: tools/bundle_memo_scenes.sh        (from the repository root)
# Then one device call (results come back under $OUT, 3 files):
#   run(kind="nvidia-h100-x1", carry=["bundle", ".gl"], timeout_s=600,
#       command="bash tools/bench/memo_scenes_device.sh")
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
m=${MEMOGRAPH:-build/tools/memograph}
[ -x "$m" ] || { echo "bundle_memo_scenes: no $m (build with the io module first)" >&2; exit 1; }
bash tools/bundle_device.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$m" import-blender examples/blender/material_scene.blend --out "$work/material_scene" --scene \
  ${BLENDER:+--blender "$BLENDER"}
"$m" pack "$work/material_scene/scene.gltf" --materials "$work/material_scene" \
  --camera-path examples/blender/material_scene.camera --out bundle/material_scene.mgpack
cp examples/blender/material_scene.camera bundle/material_scene.camera
dirty=""
if git status --porcelain --untracked-files=no | grep -q .; then
  dirty=" (with uncommitted changes)"
fi
echo "$(git rev-parse --short HEAD) $(git log -1 --format=%s)$dirty" >bundle/VERSION
size=$(du -sm bundle .gl | awk '{s += $1} END {print s}')
echo "bundle_memo_scenes: bundle/ and .gl/ hold ${size} MiB (limit 64)"
[ "$size" -le 64 ] || { echo "bundle_memo_scenes: too large" >&2; exit 1; }
