#!/usr/bin/env bash
# The rig's stage times against the thesis's Table 5.1 (docs/rigging.md, "Speed against the
# thesis's Table 5.1"): `odeskin rig MESH --weights --repeat N` on the four meshes with a ground
# truth or a Table 5.1 row, ROUNDS rounds, printed as a Markdown table of each stage's fastest run
# (the range over the rounds, since a shared machine moves medians far more than minima).
# Usage: scripts/rig-speed.sh [ROUNDS] [REPEAT]   (defaults 2 and 200; about a minute)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
[[ -x "$odeskin" ]] || { echo "rig-speed: $odeskin not found; build it first" >&2; exit 1; }
rounds="${1:-2}"
repeat="${2:-200}"
meshes=(cylinder/cylinder.obj cat-poses/cat-00.obj horse-gallop/horse-01.obj cheburashka/cheburashka.obj)
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | xargs), $(nproc) cores; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for ((round = 1; round <= rounds; ++round)); do
  for mesh in "${meshes[@]}"; do
    name="$(basename "$mesh" .obj)"
    "$odeskin" rig "$data/$mesh" -o "$out/x.tgf" --weights "$out/x.dmat" --repeat "$repeat" >"$out/$name.$round.txt"
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$out" "$rounds" "${meshes[@]}" <<'PY'
import os, re, sys
out, rounds, meshes = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
stages = ["mesh edges", "curve (vertex) identification", "skeleton creation", "weights",
          "centre section", "edge distances", "coarse levels", "fast marching", "fine levels"]

def fastest(text, stage):
    # "STAGE MEDIAN / FASTEST ms" on the summary lines
    m = re.search(re.escape(stage) + r" [0-9.]+ / ([0-9.]+) ms", text)
    return float(m.group(1)) if m else None

def cell(values):
    values = [v for v in values if v is not None]
    if not values:
        return "-"
    lo, hi = min(values), max(values)
    return f"{lo:.3f}" if f"{lo:.3f}" == f"{hi:.3f}" else f"{lo:.3f}-{hi:.3f}"

print("\nfastest run of each round, the rounds' range, ms\n")
print("| mesh | " + " | ".join(stages) + " |")
print("|---|" + "---:|" * len(stages))
for mesh in meshes:
    name = os.path.basename(mesh).removesuffix(".obj")
    texts = [open(os.path.join(out, f"{name}.{r}.txt")).read() for r in range(1, rounds + 1)]
    print(f"| {name} | " + " | ".join(cell([fastest(t, s) for t in texts]) for s in stages) + " |")
print("\nthesis Table 5.1, cat: vertex identification 1.32 ms, skeleton creation 0.269 ms")
PY
