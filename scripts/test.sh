#!/usr/bin/env bash
# Installs dependencies, then builds odeskin with AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer into ${ODESKIN_BUILD_DIR:-build}-asan and runs every test there (GoogleTest
# via CTest, sample self-checks, GPU/CPU parity under whatever Vulkan device exists: lavapipe in CI).
# GPU tests fail rather than skip here (ODESKIN_REQUIRE_GPU=1), and the validation layer is on
# whenever it is installed. It also checks that engine/ builds without Vulkan, as a subproject
# (tests/consumer), that the installed package serves the same consumer, and runs both. scripts/build.sh
# alone (scripts/demo.sh) still gives the plain Release build in ${ODESKIN_BUILD_DIR:-build}.
# docs/reliability.md ("Sanitizers") has the ThreadSanitizer build and why CI does not run it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
asan="$build-asan"
suppressions="$root/tests/sanitizers"
jobs="$(nproc)"
"$root/scripts/install-deps.sh"

# Every instrumented program the tests start (test executables, odeskin, the samples; also the
# test listing the build itself runs) reads these. A finding aborts the program (SIGABRT, no core
# file): CTest ignores the exit status of a test with PASS_REGULAR_EXPRESSION and inverts it for
# WILL_FAIL, so a sanitizer exit code could pass there, and 1 or 2 is what the failure-path tests
# expect from odeskin (cmake/ExpectFailure.cmake); a killed process fails every kind of test. Node.js
# and Chromium (web.viewer_e2e) are not instrumented and ignore these. tests/sanitizers/lsan.supp may
# name third-party libraries only (the Vulkan loader, Mesa, the validation layer), never odeskin code.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:disable_coredump=1:detect_leaks=1:check_initialization_order=1:strict_init_order=1"
export LSAN_OPTIONS="suppressions=$suppressions/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:abort_on_error=1:disable_coredump=1:print_stacktrace=1"

# ccache lets the engine-only build below reuse the objects of this one (same flags, same sources):
# the check then costs a configure and a cache lookup per file instead of a second engine build.
# NOHASHDIR: with -g the build folder's path is part of the hash otherwise, and the two folders differ.
launcher=()
if command -v ccache > /dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}" CCACHE_NOHASHDIR=1
fi
sanitize=(-DODESKIN_SANITIZE=address,undefined "${launcher[@]}")
# The Google Benchmark programs (bench/) run no test; they are built by scripts/build.sh (the demo's
# plain build), and skipping them here keeps CI within its time.
ODESKIN_BUILD_DIR="$asan" "$root/scripts/build.sh" "${sanitize[@]}" -DODESKIN_BUILD_BENCH=OFF
ODESKIN_BUILD_DIR="$asan" "$root/scripts/analyze.sh" --cppcheck-only  # static analysis of our code (docs/reliability.md, "Static analysis")

# engine/ must never see Vulkan (STYLE.md): check the sources and that the engine configures and
# builds on its own with the host switched off, the way an engine consumes it: tests/consumer
# adds odeskin with add_subdirectory, links odeskin::engine and odeskin::runtime and runs a CPU
# runtime frame against the reference (docs/runtime.md, "Building odeskin into an engine"). The
# sanitizer reaches the consumer's link only (its compile flags would miss the cache).
if grep -rnE '#include <vulkan|Vulkan::' "$root/engine"; then
  echo "odeskin: engine/ depends on Vulkan" >&2
  exit 1
fi
cmake -S "$root/tests/consumer" -B "$build-consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release -DODESKIN_BUILD_HOST=OFF \
  -DODESKIN_WERROR=ON "${sanitize[@]}" -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined > /dev/null
cmake --build "$build-consumer" -j "$jobs" > /dev/null
"$build-consumer/odeskin_consumer"
echo "odeskin: engine builds without Vulkan, and as a subproject"
# scripts/tsan.sh builds the tests with the host off, which no other step does: configuring that
# set-up here catches a test that needs the host's or the programs' packages (seconds, no build).
cmake -S "$root" -B "$build-engine-tests" -G Ninja -DCMAKE_BUILD_TYPE=Release -DODESKIN_BUILD_HOST=OFF \
  -DODESKIN_BUILD_BENCH=OFF > /dev/null
echo "odeskin: the tests configure with the host off (scripts/tsan.sh's build)"

# The installed package (cmake/OdeskinInstall.cmake): this build installed into a prefix, and the
# consumer built against it with find_package(odeskin) alone; with the host, it also runs its frame
# on the Vulkan runtime (lavapipe) against the CPU runtime.
rm -rf "$build-prefix"
cmake --install "$asan" --prefix "$build-prefix" > /dev/null
cmake -S "$root/tests/consumer" -B "$build-package-consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DODESKIN_CONSUMER_PACKAGE=ON -DCMAKE_PREFIX_PATH="$build-prefix" "${launcher[@]}" \
  -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined > /dev/null
cmake --build "$build-package-consumer" -j "$jobs" > /dev/null
XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}" "$build-package-consumer/odeskin_consumer"
echo "odeskin: the installed package builds a consumer (find_package(odeskin))"

export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
export ODESKIN_REQUIRE_GPU="${ODESKIN_REQUIRE_GPU:-1}"
ctest --test-dir "$asan" --output-on-failure -j "$jobs"

# libFuzzer on every file reader, the curve rig and the fit, 10 s per target after replaying
# tests/fuzz/regressions (docs/reliability.md, "Fuzzing").
"$root/scripts/fuzz.sh" --seconds-per-target 10 --unoptimised
