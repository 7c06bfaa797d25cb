#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang (build-fuzz/), assembles their seed corpus
# and runs each target for a bounded time (docs/reliability.md, "Fuzzing").
#   scripts/fuzz.sh [--seconds-per-target S] [--jobs J] [--targets "obj gltf ..."] [--unoptimised]
# S: seconds of fuzzing per target (default 20; CI uses 15, a long run e.g. 3600). J: parallel
# fuzzing processes per target (libFuzzer -fork; default 1). Targets: obj tgf dmat tmat pose odsk gltf network rig fit.
# --unoptimised: build at -O0 into build-fuzz-O0/ (CI: the instrumented engine compiles in less than
# half the CPU time of -O1, at a lower fuzzing rate, which short runs can afford).
# Exits non-zero when a target crashes, leaks, runs out of memory (2 GiB) or spends over 10 s on one
# input; the input is saved under build-fuzz/findings/<target>/ and its path printed. The corpus
# grows in build-fuzz/corpus/<target>/ from run to run; tests/fuzz/regressions/<target>/ (inputs
# that once failed) is replayed first on every run. ODESKIN_FUZZ_BUILD_DIR overrides build-fuzz/.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds=20
opt=1
jobs=1
targets="obj tgf dmat tmat pose odsk gltf network rig fit"
while (($#)); do
  case "$1" in
    --seconds-per-target) seconds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --targets) targets="$2"; shift 2 ;;
    --unoptimised) opt=0; shift ;;
    -h|--help) sed -n '2,13p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -ge 1 ]] || { echo "fuzz.sh: --seconds-per-target must be a whole number >= 1" >&2; exit 2; }
[[ "$jobs" =~ ^[0-9]+$ && "$jobs" -ge 1 ]] || { echo "fuzz.sh: --jobs must be a whole number >= 1" >&2; exit 2; }

default_build="$root/build-fuzz"
((opt == 0)) && default_build="$root/build-fuzz-O0"
build="${ODESKIN_FUZZ_BUILD_DIR:-$default_build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
command -v clang++ > /dev/null || { echo "fuzz.sh: clang++ not found (scripts/install-deps.sh installs clang)" >&2; exit 1; }

launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
start=$(date +%s)
if [[ ! -f "$build/build.ninja" ]]; then
  # Line tables only: reports still name file and line, and the compile is cheaper than with -g.
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
    -DCMAKE_CXX_FLAGS="-O$opt -gline-tables-only" \
    -DODESKIN_BUILD_FUZZERS=ON -DODESKIN_BUILD_HOST=OFF -DODESKIN_BUILD_TESTS=OFF -DODESKIN_BUILD_BENCH=OFF \
    "${launcher[@]}" > /dev/null
fi
ninja -C "$build" -j"${ODESKIN_BUILD_JOBS:-$(nproc)}" odeskin_fuzzers | grep -v '^\[' || true
[[ -x "$build/tests/fuzz/fuzz_obj" ]] || { echo "fuzz.sh: build failed" >&2; exit 1; }
echo "fuzz.sh: built in $(($(date +%s) - start)) s"

# ---- seeds: a few small files per format from ../shared/data and samples/, tiny hand-written
# edge cases, and what the engine's own writers produce (odeskin_fuzz_seeds) -------------------------
seeds="$build/seeds"
rm -rf "$seeds"
mkdir -p "$seeds"/{obj,tgf,dmat,tmat,pose,odsk,gltf,network,rig,fit}
"$build/tests/fuzz/odeskin_fuzz_seeds" "$seeds"
copy_if_there() {  # copy_if_there DEST FILE...: data files are optional (a checkout without ../shared)
  local dest="$1"; shift
  for f in "$@"; do [[ -f "$f" ]] && install -m 644 "$f" "$dest/"; done
  return 0
}
copy_if_there "$seeds/obj" "$data/cylinder/cylinder.obj"
copy_if_there "$seeds/tgf" "$data/cylinder/cylinder.tgf" "$data/cheburashka/cheburashka.tgf"
copy_if_there "$seeds/dmat" "$data/cylinder/cylinder.DMAT" "$data/cylinder/poses-1/cylinder-1.DMAT"
cp "$root"/samples/surfaces/networks/*.json "$seeds/network/"
# EXT_meshopt_compression (engine/io/gltf_meshopt.hpp): the compact arm through gltfpack, without and
# with its filters (-cc), and with a fallback buffer (-cf; the fuzzer reads no .bin beside a file,
# and odeskin skips a fallback buffer, so its .bin is dropped).
if command -v gltfpack > /dev/null; then
  for mode in c cc cf; do
    gltfpack -$mode -i "$seeds/gltf/arm-compact.glb" -o "$seeds/gltf/arm-meshopt-$mode.glb" > /dev/null
  done
  rm -f "$seeds"/gltf/*.bin
fi
printf 'v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 0 0 1e-1\r\nf 1 2 3\r\nf 1/1 -1/2 -2/3\r\nf 1//1 2/2/2 4//3 3\r\n' > "$seeds/obj/tetra-crlf.obj"
printf 'v 0 0 0 # x y z\nvt 0 0\nvn 0 0 1\ng part\nv 1 0 0\nv 1 1 0\nf 1 2 3' > "$seeds/obj/triangle-no-newline.obj"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 1 0.25\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/-1/-1 4/4/1\n' > "$seeds/obj/square-uv-seam.obj"
printf '1 0 0 0\n2 0 1 0\n3 0 2 0\n#\n1 2\n2 3\n#\n' > "$seeds/tgf/chain.tgf"
printf '2 3\n0.5 0.25 1\n0.5 0.75 0\n' > "$seeds/dmat/small.dmat"
# .Tmat and pose .json seeds start with the byte their target reads as the bone count (1 + byte % 32).
with_bones() {  # with_bones BONES SRC DEST: DEST is the byte BONES - 1, then SRC (skipped if SRC is missing)
  [[ -f "$2" ]] || return 0
  { printf "\\$(printf '%03o' "$(($1 - 1))")"; cat "$2"; } > "$3"
}
with_bones 4 "$data/cylinder/poses-1/cylinder-1.Tmat" "$seeds/tmat/cylinder-1.Tmat"
with_bones 11 "$data/cheburashka/poses-1/cheburashka-1.Tmat" "$seeds/tmat/cheburashka-1.Tmat"
with_bones 4 "$data/cylinder/poses-2/cylinder-1.json" "$seeds/pose/cylinder-1.json"
with_bones 11 "$data/cheburashka/poses-1/cheburashka-1.json" "$seeds/pose/cheburashka-1.json"
printf '\001{"dQ-1": [0, 0, 0.6, 0.8], "threshold": 1, "Camera": {}}' > "$seeds/pose/two-bones.json"
# The rig's seeds: the OBJ seeds, and an open tube of quads (the edge loops' path).
cp "$seeds/obj"/* "$seeds/rig/"
awk 'BEGIN { pi = atan2(0, -1); s = 8; r = 10
  for (i = 0; i < r; ++i) for (j = 0; j < s; ++j) printf "v %g %g %g\n", cos(2 * pi * j / s), sin(2 * pi * j / s), 0.5 * i
  for (i = 0; i + 1 < r; ++i) for (j = 0; j < s; ++j) { a = i * s + j + 1; b = i * s + (j + 1) % s + 1; printf "f %d %d %d %d\n", a, b, b + s, a + s } }' \
  > "$seeds/rig/quad-tube.obj"
# The fit's seeds: the rig's (the last byte of each picks the fit's options: see fit_fuzzer.cpp),
# and a closed tube of 194 vertices in triangles, below the target's 300 (the cylinder is above).
cp "$seeds/rig"/* "$seeds/fit/"
awk 'BEGIN { pi = atan2(0, -1); s = 12; r = 16
  for (i = 0; i < r; ++i) for (j = 0; j < s; ++j) printf "v %g %g %g\n", 0.4 * cos(2 * pi * j / s), 0.4 * sin(2 * pi * j / s), 0.25 * i
  printf "v 0 0 -0.2\nv 0 0 %g\n", 0.25 * (r - 1) + 0.2
  for (i = 0; i + 1 < r; ++i) for (j = 0; j < s; ++j) { a = i * s + j + 1; b = i * s + (j + 1) % s + 1; printf "f %d %d %d\nf %d %d %d\n", a, b, b + s, a, b + s, a + s }
  for (j = 0; j < s; ++j) { printf "f %d %d %d\n", r * s + 1, (j + 1) % s + 1, j + 1; printf "f %d %d %d\n", r * s + 2, (r - 1) * s + j + 1, (r - 1) * s + (j + 1) % s + 1 } }' \
  > "$seeds/fit/tri-tube.obj"
# The quad tube again with a last byte (0x10) that asks for a third pose.
{ cat "$seeds/rig/quad-tube.obj"; printf '\020'; } > "$seeds/fit/quad-tube-three-poses.obj"

max_len() {  # inputs past this length are cut: big enough for the seeds that matter, small enough to run fast
  case "$1" in
    obj|dmat|rig|fit) echo 40000 ;;
    gltf) echo 65536 ;;
    odsk) echo 32768 ;;
    *) echo 8192 ;;
  esac
}

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
failed=()
logs="$build/fuzz-logs"
mkdir -p "$logs"
for t in $targets; do
  bin="$build/tests/fuzz/fuzz_$t"
  [[ -x "$bin" ]] || { echo "fuzz.sh: no target '$t' (obj tgf dmat tmat pose odsk gltf network rig fit)" >&2; exit 2; }
  corpus="$build/corpus/$t"
  findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  cp -n "$seeds/$t"/* "$corpus/" 2> /dev/null || true
  regressions="$root/tests/fuzz/regressions/$t"
  dirs=("$corpus")
  [[ -d "$regressions" ]] && dirs+=("$regressions")
  parallel=()
  ((jobs > 1)) && parallel=(-fork="$jobs")
  log="$logs/$t.log"
  t0=$(date +%s)
  set +e
  "$bin" "${dirs[@]}" "${parallel[@]}" -max_total_time="$seconds" -max_len="$(max_len "$t")" -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 > "$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1 || true)
  if [[ -z "$execs" ]]; then  # -fork prints no final stats; its last progress line has "#inputs: cov: ... exec/s N"
    last=$(grep -E '^#[0-9]+: cov:' "$log" | tail -1 || true)
    execs=$(sed -E 's/^#([0-9]+):.*/\1/' <<< "$last")
    rate=$(grep -oE 'exec/s [0-9]+' <<< "$last" | grep -oE '[0-9]+' || true)
  fi
  units=$(ls "$corpus" | wc -l)
  if ((rc != 0)); then
    failed+=("$t")
    echo "fuzz.sh: $t FAILED (exit $rc) after $(($(date +%s) - t0)) s; log: $log"
    grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|odeskin fuzz:|.*(Test unit|artifact) written to)' "$log" | head -8 | sed 's/^/  /' || true
  else
    echo "fuzz.sh: $t ok: ${execs:-?} inputs in $(($(date +%s) - t0)) s (${rate:-?}/s), corpus $units files"
  fi
done
echo "fuzz.sh: done in $(($(date +%s) - start)) s"
if ((${#failed[@]})); then
  echo "fuzz.sh: findings in: ${failed[*]} (inputs under $build/findings/; replay one with" \
    "build-fuzz/tests/fuzz/fuzz_<target> <file>)" >&2
  exit 1
fi
