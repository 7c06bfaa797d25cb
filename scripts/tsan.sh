#!/usr/bin/env bash
# Builds the tests of odeskin's threaded CPU paths (CTest label "threaded", target
# odeskin_threaded_tests) with ThreadSanitizer into ${ODESKIN_BUILD_DIR:-build}-tsan, engine only, and
# runs them. Any report fails: it aborts the test program, and a report in a test that passed anyway
# is caught in CTest's log. engine/core/parallel.hpp annotates TBB's fork and join for TSan;
# tests/sanitizers/tsan.supp names the TBB-internal reports it cannot (docs/reliability.md,
# "ThreadSanitizer"). ODESKIN_JOBS sets the parallelism (default: nproc).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tsan="${ODESKIN_BUILD_DIR:-$root/build}-tsan"
jobs="${ODESKIN_JOBS:-$(nproc)}"

launcher=()
if command -v ccache > /dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}" CCACHE_NOHASHDIR=1
fi
cmake -S "$root" -B "$tsan" -G Ninja -DCMAKE_BUILD_TYPE=Release -DODESKIN_SANITIZE=thread \
  -DODESKIN_BUILD_HOST=OFF -DODESKIN_BUILD_BENCH=OFF -DODESKIN_WERROR=ON "${launcher[@]}" > /dev/null
cmake --build "$tsan" -j "$jobs" --target odeskin_threaded_tests

# halt_on_error + abort_on_error: the first report kills the test program (SIGABRT), which fails
# every kind of CTest test (docs/reliability.md, "Sanitizers").
export TSAN_OPTIONS="halt_on_error=1:abort_on_error=1:disable_coredump=1:second_deadlock_stack=1:suppressions=$root/tests/sanitizers/tsan.supp"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
ctest --test-dir "$tsan" -L threaded --output-on-failure -j "$jobs"
log="$tsan/Testing/Temporary/LastTest.log"
if grep -q "WARNING: ThreadSanitizer" "$log"; then
  grep -n -A20 "WARNING: ThreadSanitizer" "$log" >&2
  echo "odeskin: ThreadSanitizer reported (see $log)" >&2
  exit 1
fi
echo "odeskin: the threaded tests run clean under ThreadSanitizer"
