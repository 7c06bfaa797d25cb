#!/usr/bin/env bash
# How much the curve rig's skeleton depends on things that do not change the shape
# (docs/rigging.md, "Limitations"): `odeskin rig MESH -o x.tgf` on the cat, the horse and
# Cheburashka as given, with their vertices renumbered (a seeded shuffle, faces remapped) and with
# every coordinate moved by a seeded uniform jitter of 1e-9, 1e-6 and 1e-4 of the box diagonal.
# Prints a Markdown table of bone counts, and for Cheburashka the distances of `--compare` to its
# artist's skeleton. A rig that did not depend on the vertex order would print one count per row.
# Usage: scripts/rig-invariance.sh [SEEDS]   (default 4; about 15 s)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
[[ -x "$odeskin" ]] || { echo "rig-invariance: $odeskin not found; build it first" >&2; exit 1; }
seeds="${1:-4}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

perturb() {  # perturb IN OUT renumber|jitter:FRACTION SEED
  python3 - "$@" <<'PY'
import random, sys
src, dst, mode, seed = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
rng = random.Random(seed)
vertices, faces = [], []
for line in open(src):
    p = line.split()
    if p and p[0] == "v":
        vertices.append([float(x) for x in p[1:4]])
    elif p and p[0] == "f":
        faces.append([int(c.split("/")[0]) - 1 for c in p[1:]])
order = list(range(len(vertices)))  # order[i]: the new index of vertex i
if mode == "renumber":
    rng.shuffle(order)
else:
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    step = float(mode.split(":")[1]) * sum((h - l) ** 2 for h, l in zip(hi, lo)) ** 0.5
    vertices = [[x + rng.uniform(-step, step) for x in v] for v in vertices]
moved = [None] * len(vertices)
for i, v in enumerate(vertices):
    moved[order[i]] = v
with open(dst, "w") as f:
    f.writelines("v %.17g %.17g %.17g\n" % tuple(v) for v in moved)
    f.writelines("f " + " ".join(str(order[i] + 1) for i in face) + "\n" for face in faces)
PY
}

bones() {  # bones MESH [rig options...]: the bone count `rig` reports
  "$odeskin" rig "$@" -o "$out/x.tgf" 2>&1 | sed -n 's/^skeleton: \([0-9]*\) bones.*/\1/p'
}

meshes=(cat-poses/cat-00.obj horse-gallop/horse-01.obj cheburashka/cheburashka.obj)
echo "| mesh | as given | renumbered, seeds 1-$seeds | jitter 1e-9 | jitter 1e-6 | jitter 1e-4 |"
echo "|---|---:|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  row="| ${mesh##*/} | $(bones "$data/$mesh") |"
  for mode in renumber jitter:1e-9 jitter:1e-6 jitter:1e-4; do
    counts=()
    for ((seed = 1; seed <= seeds; ++seed)); do
      perturb "$data/$mesh" "$out/p.obj" "$mode" "$seed"
      counts+=("$(bones "$out/p.obj")")
    done
    row+=" $(IFS=,; echo "${counts[*]}" | sed 's/,/, /g') |"
  done
  echo "$row"
done

echo
echo "Cheburashka against its artist's skeleton (truth -> ours, mean and max % of the box diagonal):"
truth="$data/cheburashka/cheburashka.tgf"
compare() { "$odeskin" rig "$1" -o "$out/x.tgf" --compare "$truth" 2>&1 | sed -n 's/.*truth -> nearest ours mean \([0-9.]*\)% max \([0-9.]*\)%.*/\1 \2/p'; }
echo "- as given: $(compare "$data/cheburashka/cheburashka.obj")"
for ((seed = 1; seed <= seeds; ++seed)); do
  perturb "$data/cheburashka/cheburashka.obj" "$out/p.obj" renumber "$seed"
  echo "- renumbered, seed $seed: $(compare "$out/p.obj")"
done
