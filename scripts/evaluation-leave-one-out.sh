#!/usr/bin/env bash
# Leave-one-out prediction on the pose collections of docs/results.md (cat-poses, face-poses,
# cylinder poses-1, cheburashka poses-2): for every pose i with neighbours i-1 and i+1 in the
# collection's order, `odeskin evaluate` fits the two neighbours and predicts pose i at tau = 1/2
# (truth skeleton, rigid fit). This only measures something where pose i lies between its
# neighbours; the collections are independent poses, so the numbers say how far each pose is from
# the blend of its neighbours. Prints one Markdown table per dataset (means over i) to stdout.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
[[ -x "$odeskin" ]] || { echo "evaluation-leave-one-out: $odeskin not found; build it first" >&2; exit 1; }
out="${1:-$(mktemp -d)}"
mkdir -p "$out"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"

run() {  # run NAME RIG_ARGS -- FILES...
  local name="$1"; shift
  local rig=()
  while [[ "$1" != "--" ]]; do rig+=("$1"); shift; done
  shift
  local files=("$@") i
  for ((i = 1; i + 1 < ${#files[@]}; ++i)); do
    "$odeskin" evaluate "${files[i - 1]}" "${files[i]}" "${files[i + 1]}" --keys 0,2 --pose-source truth \
      "${rig[@]}" --json "$out/$name-$i.json" --quiet
  done
  python3 - "$out" "$name" $((${#files[@]} - 2)) <<'PY'
import json, sys
out, name, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
methods = ["linear", "lbs", "dqs", "psd_lbs", "psd_dqs", "fd_curve", "odeskin_static", "odeskin_dynamic"]
docs = [json.load(open(f"{out}/{name}-{i}.json")) for i in range(1, n + 1)]
print(f"\n**{name}** (leave-one-out over {n} poses, truth skeleton)\n")
print("| method | mean % | worst pose's mean % | MVE % (max) |")
print("|---|---:|---:|---:|")
for m in methods:
    means = [d["summary"][m]["mean_mean"] for d in docs]
    mve = max(d["summary"][m]["mve_max"] for d in docs)
    print(f"| {m} | {100 * sum(means) / n:.3f} | {100 * max(means):.3f} | {100 * mve:.2f} |")
PY
}

run cat-poses -- "$data"/cat-poses/cat-0{1..9}.obj
run face-poses -- "$data"/face-poses/face-0{0..9}.obj
# In one region of the mesh face-01 and face-03..09 number their vertices differently from face-00,
# face-02 and the shared face list (scripts/evaluation-face-poses.sh); face-03..09 agree with each
# other, so their leave-one-out measures the methods rather than the files' correspondence.
run face-poses-03-09 -- "$data"/face-poses/face-0{3..9}.obj
cyl="$data/cylinder"
run cylinder --rig "$cyl/cylinder.tgf" --bind "$cyl/cylinder.obj" --weights "$cyl/cylinder.DMAT" -- \
  "$cyl"/poses-1/cylinder-{1..4}.obj
che="$data/cheburashka"
run cheburashka --rig "$che/cheburashka.tgf" --bind "$che/cheburashka.obj" --weights "$che/cheburashka.DMAT" -- \
  "$che"/poses-2/cheburashka-{01..11}.obj
# The same with the LBS-optimal (SSDR) skeleton: the poses are LBS of this very rig, so LBS is exact
# there, which shows what the rigid skeleton leaves to the correctives.
run cheburashka-ssdr --rig "$che/cheburashka.tgf" --bind "$che/cheburashka.obj" --weights "$che/cheburashka.DMAT" \
  --skeleton-fit lbs -- "$che"/poses-2/cheburashka-{01..11}.obj
