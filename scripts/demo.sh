#!/usr/bin/env bash
# The main job: install dependencies, build, and run `odeskin demo` on the embedded procedural arm
# (fit its two example poses, play 30 frames on Vulkan when a device exists, else on the CPU).
# Frames land in ./odeskin-demo (override with ODESKIN_DEMO_DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"  # silences the Vulkan loader's surface probing
"${ODESKIN_BUILD_DIR:-$root/build}/samples/odeskin" info
"${ODESKIN_BUILD_DIR:-$root/build}/samples/odeskin" demo -o "${ODESKIN_DEMO_DIR:-odeskin-demo}" "$@"
