#!/usr/bin/env bash
# Why every method has an MVE of 75-87 % on face-poses in leave-one-out (docs/results.md): checks the
# files' vertex correspondence and sets it against the per-pose errors of `odeskin evaluate`.
#  1. Per file: edges of the shared face list longer than 10x the file's mean edge length (a torn
#     triangle: its corners are not neighbours in that file), and how far each vertex is from the
#     neutral face-00.
#  2. Per left-out pose i (keys i-1, i+1, as scripts/evaluation-leave-one-out.sh): the largest distance
#     between pose i and the halfway blend of its neighbours, on the torn vertices and on the others,
#     next to each method's MVE from the JSON files of that script (run here if missing).
# Usage: scripts/evaluation-face-poses.sh OUT_DIR   (OUT_DIR as given to evaluation-leave-one-out.sh)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
out="${1:?usage: evaluation-face-poses.sh OUT_DIR}"
mkdir -p "$out"
face="$data/face-poses"
for i in $(seq 1 8); do
  json="$out/face-poses-$i.json"
  [[ -f "$json" ]] && continue
  [[ -x "$odeskin" ]] || { echo "evaluation-face-poses: $odeskin not found; build it first" >&2; exit 1; }
  "$odeskin" evaluate "$face/face-0$((i - 1)).obj" "$face/face-0$i.obj" "$face/face-0$((i + 1)).obj" --keys 0,2 \
    --pose-source truth --json "$json" --quiet
done

python3 - "$face" "$out" <<'PY'
import json, math, sys
face, out = sys.argv[1], sys.argv[2]

def read(path):
    verts, faces = [], []
    for line in open(path):
        if line.startswith("v "):
            verts.append(tuple(map(float, line.split()[1:4])))
        elif line.startswith("f "):
            faces.append(tuple(int(t.split("/")[0]) - 1 for t in line.split()[1:]))
    return verts, faces

meshes = [read(f"{face}/face-{i:02d}.obj") for i in range(10)]
faces = meshes[0][1]
assert all(m[1] == faces for m in meshes), "face lists differ"
edges = {(min(a, b), max(a, b)) for f in faces for a, b in zip(f, f[1:] + f[:1])}

def box_side(v):
    return max(max(p[k] for p in v) - min(p[k] for p in v) for k in range(3))

print("\n**face-poses: the shared face list against each file's positions**\n")
print("| file | mean edge | edges > 10x mean | longest edge | vertices on them | max distance to face-00 (% of box) | 99th percentile (%) |")
print("|---|---:|---:|---:|---:|---:|---:|")
torn = set()
neutral = meshes[0][0]
for i, (v, _) in enumerate(meshes):
    lengths = {e: math.dist(v[e[0]], v[e[1]]) for e in edges}
    mean = sum(lengths.values()) / len(lengths)
    long_edges = [e for e, l in lengths.items() if l > 10 * mean]
    here = {k for e in long_edges for k in e}
    torn |= here
    box = box_side(v)
    d = sorted(math.dist(a, b) / box for a, b in zip(v, neutral))
    print(f"| face-{i:02d} | {mean:.4f} | {len(long_edges)} | {max(lengths.values()):.3f} | {len(here)} | "
          f"{100 * d[-1]:.1f} | {100 * d[int(0.99 * len(d))]:.1f} |")
print(f"\nVertices on a torn edge in some file: {len(torn)} of {len(neutral)} (indices {min(torn)}-{max(torn)}).")
# The tearing files agree with each other there: distance to face-01, torn vertices against the rest.
first = meshes[1][0]
for i in range(3, 10):
    v = meshes[i][0]
    on = max(math.dist(v[k], first[k]) for k in torn)
    off = max(math.dist(v[k], first[k]) for k in range(len(v)) if k not in torn)
    print(f"face-{i:02d} against face-01: max distance {on:.3f} on the torn vertices, {off:.3f} on the others.")
# Where face-01 puts them: the nearest vertex of face-00 to each torn vertex of face-01.
by_x = sorted(range(len(neutral)), key=lambda j: neutral[j][0])
xs = [neutral[j][0] for j in by_x]
import bisect
other, dists = 0, []
for k in sorted(torn):
    q = first[k]
    lo, hi = bisect.bisect_left(xs, q[0] - 0.05), bisect.bisect_right(xs, q[0] + 0.05)
    d, j = min((math.dist(q, neutral[by_x[n]]), by_x[n]) for n in range(lo, hi)) if hi > lo else (math.inf, k)
    dists.append(d)
    other += j != k
dists.sort()
print(f"face-01's torn vertices: {other} of {len(torn)} lie nearest to a different face-00 vertex; "
      f"distance to it median {dists[len(dists) // 2]:.4f}, 90th percentile {dists[int(0.9 * len(dists))]:.4f} "
      f"(mean edge 0.0144).")

methods = ["linear", "lbs", "psd_lbs", "odeskin_static", "odeskin_dynamic"]
print("\n**face-poses leave-one-out: where the MVE comes from** (% of the box; keys i-1, i+1, truth skeleton)\n")
print("| left-out pose | blend of neighbours: max distance on torn vertices | on the other vertices | "
      + " | ".join(f"{m} MVE" for m in methods) + " |")
print("|---|---:|---:|" + "---:|" * len(methods))
for i in range(1, 9):
    a, b, t = meshes[i - 1][0], meshes[i + 1][0], meshes[i][0]
    box = box_side(t)
    dist = [math.dist(tuple(0.5 * (x + y) for x, y in zip(a[k], b[k])), t[k]) / box for k in range(len(t))]
    on = max(dist[k] for k in torn)
    off = max(dist[k] for k in range(len(t)) if k not in torn)
    doc = json.load(open(f"{out}/face-poses-{i}.json"))
    mve = [100 * doc["summary"][m]["mve_max"] for m in methods]
    print(f"| face-{i:02d} | {100 * on:.1f} | {100 * off:.1f} | " + " | ".join(f"{x:.1f}" for x in mve) + " |")
PY
