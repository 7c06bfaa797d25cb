#!/usr/bin/env bash
# Configures and builds odeskin (Release) into ${ODESKIN_BUILD_DIR:-build}.
# Without sanitizers unless the arguments ask (scripts/test.sh passes -DODESKIN_SANITIZE=...): the
# empty default comes first so a later -D wins and a reused folder never stays sanitized.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DODESKIN_WERROR=ON -DODESKIN_SANITIZE= "$@"
cmake --build "$build" -j "$(nproc)"
