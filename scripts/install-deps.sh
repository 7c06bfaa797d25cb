#!/usr/bin/env bash
# Installs odeskin's build and test dependencies from Debian 12 packages (run as root), then the web
# viewer's npm packages. Only what is missing is installed, so repeated runs are fast and need no network.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config ccache
  locales  # tests/engine/locale_test.cpp compiles de_DE from its sources (localedef)
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools
  libglm-dev libeigen3-dev libtbb-dev libtinygltf-dev nlohmann-json3-dev libstb-dev zlib1g-dev libopenmesh-dev
  libmeshoptimizer-dev  # EXT_meshopt_compression input (gltfpack -c)
  libcli11-dev libgtest-dev libbenchmark-dev
  clang clang-14 libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer (libclang_rt.fuzzer) and the sanitizers
  cppcheck clang-tidy
  nodejs chromium
  blender python3-numpy  # tests/interop: odeskin's outputs opened in Blender (its glTF importer needs numpy)
  gltfpack  # tests/interop: a character quantized by gltfpack (KHR_mesh_quantization) read back
)
# Debian's npm package conflicts with a nodejs that bundles npm (NodeSource builds): ask for it only
# when no npm is on the PATH.
command -v npm > /dev/null 2>&1 || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "odeskin: all ${#packages[@]} packages already installed"
elif [[ $(id -u) -ne 0 ]]; then
  echo "odeskin: missing packages: ${missing[*]}; run this script as root (apt-get install)" >&2
  exit 1
else
  echo "odeskin: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The browser viewer, its end-to-end test and the glTF-Validator check: npm packages pinned by
# web/package-lock.json, installed from the npm registry only when the lock file changed.
web="$(cd "$(dirname "${BASH_SOURCE[0]}")/../web" && pwd)"
stamp="$web/node_modules/.odeskin-lock"
if ! cmp -s "$web/package-lock.json" "$stamp" 2>/dev/null; then
  echo "odeskin: installing web/ npm packages"
  (cd "$web" && npm install --no-audit --no-fund --loglevel=error)
  cp "$web/package-lock.json" "$stamp"
fi
