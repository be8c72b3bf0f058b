#!/usr/bin/env bash
# Installs everything memograph needs on Debian 12 (bookworm), idempotently: a second run
# with everything present only checks and returns in about a second.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  glslang-dev glslang-tools
  libvulkan-dev vulkan-tools vulkan-validationlayers spirv-tools
  libglm-dev libopenimageio-dev openimageio-tools libassimp-dev
  libmeshoptimizer-dev  # the city's mesh LODs (runtime/scene/builtin/mesh_lods.cpp)
  libgtest-dev libgmock-dev libbenchmark-dev
  python3
  blender  # 3.4: the reference for the Blender node tests (tests/blender/) and the exporter
  python3-numpy  # Blender's glTF exporter (io_scene_gltf2, scene export) imports numpy
  slurm-wlm munge  # the Slurm job arrays' test starts its own cluster (tests/slurm/)
)
# lavapipe with ray tracing comes only from bookworm-backports (../shared/GPU.md).
backports_mesa=mesa-vulkan-drivers

sudo_if_needed() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
mesa_version=$(dpkg-query -W -f='${Version}' "$backports_mesa" 2>/dev/null || true)
need_mesa=0
case "$mesa_version" in *bpo*) ;; *) need_mesa=1 ;; esac

if [ ${#missing[@]} -eq 0 ] && [ $need_mesa -eq 0 ]; then
  exit 0
fi

backports_file=/etc/apt/sources.list.d/memograph-backports.sources
if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  # The archive and keyring of the machine's own Debian entries (a mirror, a proxy), not a
  # fixed host: tools/apt_backports_source.sh, tested by its _test.sh.
  echo "setup: adding the bookworm-backports suite ($backports_file)"
  bash "$(dirname "${BASH_SOURCE[0]}")/apt_backports_source.sh" |
    sudo_if_needed tee "$backports_file" >/dev/null
fi

export DEBIAN_FRONTEND=noninteractive
echo "setup: installing ${missing[*]:-} ${need_mesa:+(and Mesa from backports)}"
sudo_if_needed apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  sudo_if_needed apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ $need_mesa -eq 1 ]; then
  sudo_if_needed apt-get install -y -qq --no-install-recommends -t bookworm-backports \
    "$backports_mesa"
fi
