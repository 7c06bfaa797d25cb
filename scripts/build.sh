#!/usr/bin/env bash
# Configures and builds odeskin (Release) into ${ODESKIN_BUILD_DIR:-build}.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DODESKIN_WERROR=ON "$@"
cmake --build "$build" -j "$(nproc)"
