#!/usr/bin/env bash
# Installs dependencies, builds, and runs every test (GoogleTest via CTest, sample self-checks,
# GPU/CPU parity under whatever Vulkan device exists: lavapipe in CI). GPU tests fail rather than
# skip here (ODESKIN_REQUIRE_GPU=1), and the validation layer is on whenever it is installed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
"$root/scripts/analyze.sh" --cppcheck-only  # static analysis of our code (docs/reliability/analysis.md)

# engine/ must never see Vulkan (STYLE.md): check the sources and that the engine configures and
# builds on its own with the host switched off.
if grep -rnE '#include <vulkan|Vulkan::' "$root/engine"; then
  echo "odeskin: engine/ depends on Vulkan" >&2
  exit 1
fi
cmake -S "$root" -B "$build-engine-only" -G Ninja -DODESKIN_BUILD_HOST=OFF -DODESKIN_BUILD_TESTS=OFF \
  -DODESKIN_BUILD_BENCH=OFF -DODESKIN_WERROR=ON > /dev/null
cmake --build "$build-engine-only" -j "$(nproc)" > /dev/null
echo "odeskin: engine builds without Vulkan"

export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
export ODESKIN_REQUIRE_GPU="${ODESKIN_REQUIRE_GPU:-1}"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
