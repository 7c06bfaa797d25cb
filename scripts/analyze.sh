#!/usr/bin/env bash
# Static analysis of odeskin's own code: cppcheck, then clang-tidy (configured by the checked-in
# .clang-tidy), over every translation unit in the build's compile_commands.json. Exits non-zero on
# any finding. Needs a configured and built tree (scripts/build.sh), since sources include the SPIR-V
# headers generated into the build folder. See docs/reliability.md, "Static analysis".
#
#   scripts/analyze.sh                    cppcheck and clang-tidy on everything
#   scripts/analyze.sh --cppcheck-only    cppcheck only (the part scripts/test.sh runs)
#   scripts/analyze.sh --clang-tidy-only [REGEX...]   clang-tidy only, on files whose path matches
#
# ODESKIN_BUILD_DIR picks the build folder (default build/), ODESKIN_ANALYZE_JOBS the parallelism
# (default: the number of cores).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
jobs="${ODESKIN_ANALYZE_JOBS:-$(nproc)}"

run_cppcheck=1
run_tidy=1
case "${1:-}" in
  --cppcheck-only) run_cppcheck=1; run_tidy=0; shift ;;
  --clang-tidy-only) run_cppcheck=0; run_tidy=1; shift ;;
esac
# clang-tidy file filters: regexes on the absolute path; by default all of our sources, less
# engine/visual/stb_png.cpp, which only compiles Debian's stb_image_write implementation (upstream
# code: the analyzer finds a leak on an out-of-memory path inside stbi_write_png_to_mem).
filters=("$@")
((${#filters[@]} > 0)) || filters=("^$root/(engine|host|samples|bench|tests)/(?!visual/stb_png\\.cpp$)")

if [[ ! -f "$build/compile_commands.json" ]]; then
  echo "odeskin: $build/compile_commands.json is missing; build first (scripts/build.sh)" >&2
  exit 1
fi

status=0
if ((run_cppcheck)); then
  command -v cppcheck > /dev/null || { echo "odeskin: cppcheck is not installed (scripts/install-deps.sh)" >&2; exit 1; }
  mkdir -p "$build/cppcheck"
  start=$SECONDS
  # Our code only: system headers (Eigen, OpenMesh, tinygltf, GoogleTest, Vulkan...) and generated
  # headers are not reported. --cppcheck-build-dir makes a second run incremental.
  cppcheck --project="$build/compile_commands.json" --cppcheck-build-dir="$build/cppcheck" \
    --enable=warning,performance,portability,style --library=googletest \
    --inline-suppr --suppressions-list="$root/scripts/cppcheck-suppressions.txt" \
    --suppress='*:/usr/*' --suppress="*:$build/*" \
    --error-exitcode=1 --quiet -j "$jobs" \
    --template='{file}:{line}:{column}: {severity}: {message} [{id}]' || status=1
  echo "odeskin: cppcheck $( ((status == 0)) && echo clean || echo FOUND PROBLEMS ) ($((SECONDS - start)) s)"
fi

if ((run_tidy)); then
  tidy_runner="$(command -v run-clang-tidy-14 || command -v run-clang-tidy || true)"
  tidy="$(command -v clang-tidy-14 || command -v clang-tidy || true)"
  if [[ -z "$tidy_runner" || -z "$tidy" ]]; then
    echo "odeskin: clang-tidy is not installed (scripts/install-deps.sh)" >&2
    exit 1
  fi
  start=$SECONDS
  tidy_status=0
  # run-clang-tidy fails when any file has a finding (.clang-tidy sets WarningsAsErrors). Dropped
  # from its output: colour codes, the command line of each file, and the count of findings in
  # system headers that the header filter hides ("N warnings generated.").
  "$tidy_runner" -clang-tidy-binary "$tidy" -p "$build" -quiet -j "$jobs" "${filters[@]}" 2>&1 |
    sed -E 's/\x1b\[[0-9;]*m//g; /^[0-9]+ warnings? generated\.$/d; /^[^ ]*clang-tidy[^ ]* .* -quiet /d' ||
    tidy_status=1
  ((tidy_status == 0)) || status=1
  echo "odeskin: clang-tidy $( ((tidy_status == 0)) && echo clean || echo FOUND PROBLEMS ) ($((SECONDS - start)) s)"
fi
exit "$status"
