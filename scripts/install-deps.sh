#!/usr/bin/env bash
# Installs odeskin's build and test dependencies from Debian 12 packages (run as root). Only
# missing packages are installed, so repeated runs are fast and need no network.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools
  libglm-dev libeigen3-dev libtbb-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libopenmesh-dev
  libcli11-dev libgtest-dev libbenchmark-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "odeskin: all ${#packages[@]} packages already installed"
  exit 0
fi
if [[ $(id -u) -ne 0 ]]; then
  echo "odeskin: missing packages: ${missing[*]}; run this script as root (apt-get install)" >&2
  exit 1
fi
echo "odeskin: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
