#!/usr/bin/env bash
# The main job: installs what is missing, builds, and compiles the bundled example graphs
# to GLSL and HLSL under out/materials.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
out=out/materials
./build/tools/memograph compile examples/graphs/*.mgraph --target both -o "$out" --quiet
count=$(ls "$out"/*.glsl | wc -l)
echo
echo "Compiled $count example materials to GLSL and HLSL in $out/:"
ls "$out" | sed 's/^/  /' | head -12
echo "  …"
echo
echo "Type-check one and see each link's inferred type:"
echo "  ./build/tools/memograph check examples/graphs/listing_5_1.mgraph"
./build/tools/memograph check examples/graphs/listing_5_1.mgraph
