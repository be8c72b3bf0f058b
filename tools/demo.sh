#!/usr/bin/env bash
# The main job: installs what is missing, builds, compiles the bundled example graphs to GLSL
# and HLSL (out/materials/), and path traces the showcase scene, whose objects wear those
# materials, to out/showcase.png (on lavapipe when there is no GPU: about a minute).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
memograph=./build/tools/memograph
out=out
$memograph compile examples/graphs/*.mgraph --target both -o "$out/materials" --quiet
echo "Compiled $(ls "$out"/materials/*.glsl | wc -l) example materials to GLSL and HLSL in $out/materials/"
echo "(try: $memograph check examples/graphs/listing_5_1.mgraph)"
echo
$memograph render examples/scenes/showcase.gltf --materials examples/graphs \
  --size 480x270 --paths 4 --bounces 4 --frames 4 --out "$out/showcase.png" \
  --stats "$out/showcase_stats.csv"
echo "Image: $out/showcase.png   per-frame statistics: $out/showcase_stats.csv"
