#!/usr/bin/env bash
# A real face rebuilt from a curve network of C2 patches (thesis sec. 4.7, issue 7 point 5;
# docs/surfaces.md, "Reconstructing a real face from a curve network"): regenerates the tables and
# docs/images/face-recon-*.png.
#  1. `odeskin reconstruct` on the neutral face-00 with the nine expressions face-01..09 as poses
#     (the default 16 x 16 network): per-expression deviation, flagged vertices, size, time.
#  2. The neutral face at other network sizes, and with other patch shapes.
#  3. Pictures (`odeskin render`, lavapipe is enough): the face beside the tessellated network, the
#     neutral reconstruction's heat map, and a contact sheet of four expressions' heat maps.
# Usage: scripts/face-reconstruction.sh [OUT_DIR]   (default: build/face-reconstruction; needs a
# build with the odeskin program, ${ODESKIN_BUILD_DIR:-build}). Takes about half a minute on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
odeskin="$build/samples/odeskin"
face="${ODESKIN_SHARED_DIR:-$root/../shared}/data/face-poses"
out="${1:-$build/face-reconstruction}"
images="$root/docs/images"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"  # keeps the Vulkan loader quiet

[[ -x "$odeskin" ]] || { echo "face-reconstruction: $odeskin not found; build it first" >&2; exit 1; }
[[ -f "$face/face-00.obj" ]] || { echo "face-reconstruction: no face-poses data in $face" >&2; exit 1; }
mkdir -p "$out" "$images"

# 1. The default network, moved to every expression.
"$odeskin" reconstruct "$face/face-00.obj" --poses "$face"/face-0{1..9}.obj -o "$out/recon.obj" \
  --network "$out/face-00-network.json" --json "$out/face-16x16.json"

# 2. Other network sizes (rows x cols, curve points per patch) and shapes, on the neutral face.
sizes=("4 4 2" "8 8 2" "12 12 2" "24 24 2" "32 32 2" "24 12 2" "16 16 1" "16 16 4")
for s in "${sizes[@]}"; do
  read -r r c k <<<"$s"
  "$odeskin" -q reconstruct "$face/face-00.obj" --rows "$r" --cols "$c" --points "$k" --json "$out/size-${r}x${c}x${k}.json"
done
shapes=("1,0,0" "1,20,0" "1,-20,0" "0.1,3,0.1")
for s in "${shapes[@]}"; do
  "$odeskin" -q reconstruct "$face/face-00.obj" --shape "$s" --json "$out/shape-$s.json"
done
fits=("6,4,1" "6,3,1" "6,4,0.75" "6,4,0.5" "12,3,0.5" "3,3,0.5")
for f in "${fits[@]}"; do
  "$odeskin" -q reconstruct "$face/face-00.obj" --derivative-fit "$f" --json "$out/fit-$f.json"
done

python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
r = json.load(open(f"{out}/face-16x16.json"))
print(f"\n**The default network ({r['rows']} x {r['columns']} patches, {r['curve_points']} points per curve) on every pose**\n")
print(f"Extraction from face-00: {r['extract_seconds']:.2f} s. Stored: {r['boundaries']} boundaries x 3 curves x "
      f"{r['curve_points']} points = {r['stored_points']} points ({r['stored_floats']} floats) against "
      f"{r['vertices']} vertices ({r['mesh_floats']} floats): {r['size_reduction']:.1f}x smaller.\n")
print("| pose | flagged vertices (left out) | mean | max | mean to surface | max to surface | flagged: max to file position | rebuilt in |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for p in r["poses"]:
    name = p["file"].split("/")[-1].removesuffix(".obj")
    flagged = f"{p['flagged_max'] * 100:.0f} %" if p["flagged_vertices"] else "-"
    print(f"| {name}{' (neutral)' if name == 'face-00' else ''} | {p['flagged_vertices']} | {p['mean'] * 100:.3f} % | "
          f"{p['max'] * 100:.2f} % | {p['mean_surface'] * 100:.3f} % | {p['max_surface'] * 100:.2f} % | {flagged} | "
          f"{p['reconstruct_seconds'] * 1e3:.0f} ms |")

print("\n**Network size on the neutral face**\n")
print("| rows x cols | points per curve | stored points | size reduction | mean | max | mean to surface | max to surface |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
rows = []
for s in ["4 4 2", "8 8 2", "12 12 2", "16 16 2", "24 24 2", "32 32 2", "24 12 2", "16 16 1", "16 16 4"]:
    rr, c, k = s.split()
    j = r if s == "16 16 2" else json.load(open(f"{out}/size-{rr}x{c}x{k}.json"))
    p = j["poses"][0]
    rows.append((j["stored_points"], f"| {rr} x {c} | {j['curve_points']} | {j['stored_points']} | {j['size_reduction']:.1f}x | "
                 f"{p['mean'] * 100:.3f} % | {p['max'] * 100:.2f} % | {p['mean_surface'] * 100:.3f} % | {p['max_surface'] * 100:.2f} % |"))
for _, line in sorted(rows):
    print(line)

print("\n**Patch shape on the neutral face (16 x 16)**\n")
print("| rho, eta, lambda | mean | max | mean to surface | max to surface |")
print("|---|---:|---:|---:|---:|")
for s in ["1,3,1", "1,0,0", "1,20,0", "1,-20,0", "0.1,3,0.1"]:
    j = r if s == "1,3,1" else json.load(open(f"{out}/shape-{s}.json"))
    p = j["poses"][0]
    print(f"| {s.replace(',', ', ')} | {p['mean'] * 100:.4f} % | {p['max'] * 100:.3f} % | {p['mean_surface'] * 100:.4f} % | "
          f"{p['max_surface'] * 100:.3f} % |")

print("\n**Derivative fit on the neutral face (16 x 16): samples per side, degree, reach in row heights**\n")
print("| points, degree, window | mean | max | mean to surface | max to surface |")
print("|---|---:|---:|---:|---:|")
for f in ["6,3,0.5", "6,4,1", "6,3,1", "6,4,0.75", "6,4,0.5", "12,3,0.5", "3,3,0.5"]:
    j = r if f == "6,3,0.5" else json.load(open(f"{out}/fit-{f}.json"))
    p = j["poses"][0]
    print(f"| {f.replace(',', ', ')} | {p['mean'] * 100:.4f} % | {p['max'] * 100:.3f} % | {p['mean_surface'] * 100:.4f} % | "
          f"{p['max_surface'] * 100:.3f} % |")
PY

# 3. Pictures. The face looks along +z with y up; one camera per picture.
view=(--azimuth 20 --elevation 10)
"$odeskin" -q surface "$out/face-00-network.json" -o "$out/face-00-network.glb" --res 9,9
"$odeskin" render "$face/face-00.obj" "$out/face-00-network.glb" --labels "face-00 (29299 vertices),16 x 16 patches (1683 curve points)" \
  --size 720x360 "${view[@]}" -o "$images/face-recon-network.png"
"$odeskin" render "$out/recon.obj" --heat "$face/face-00.obj" --heat-max 0.01 --labels "face-00 rebuilt" \
  --size 480x360 "${view[@]}" -o "$images/face-recon-neutral.png"
sheet=()
for i in 02 04 06 09; do
  reference="$out/recon-face-$i-reference.obj"
  [[ -f "$reference" ]] || reference="$face/face-$i.obj"
  "$odeskin" -q render "$out/recon-face-$i.obj" --heat "$reference" --heat-max 0.02 --labels "face-$i rebuilt" \
    --size 360x300 "${view[@]}" -o "$out/heat-$i.png"
  sheet+=("$out/heat-$i.png")
done
# A 2 x 2 contact sheet, PNG in and out with the standard library only.
python3 - "$images/face-recon-expressions.png" "${sheet[@]}" <<'PY'
import struct, sys, zlib

def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, f"{path}: 8-bit RGB(A) only"
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, prev = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b, c = prev[x], prev[x - channels] if x >= channels else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line[x] for x in range(stride) if x % channels < 3) if channels == 4 else bytes(line))
        prev = line
    return width, height, rows

target, files = sys.argv[1], sys.argv[2:]
tiles = [read_png(f) for f in files]
w, h = tiles[0][0], tiles[0][1]
assert all(t[0] == w and t[1] == h for t in tiles)
columns = 2
grid_rows = (len(tiles) + columns - 1) // columns
blank = b"\xf7\xf7\xf9" * w
def filtered(line, prev):
    """The row under the filter (Sub, Up or Paeth) whose bytes sum smallest, as PNG encoders choose."""
    best = None
    for kind in (1, 2, 4):
        row = bytearray(len(line))
        for x in range(len(line)):
            a, b = (line[x - 3] if x >= 3 else 0), prev[x]
            c = prev[x - 3] if x >= 3 else 0
            if kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                a = a if pa <= pb and pa <= pc else b if pb <= pc else c
            row[x] = (line[x] - (a if kind in (1, 4) else b)) & 255
        cost = sum(v if v < 128 else 256 - v for v in row)
        if best is None or cost < best[0]:
            best = (cost, bytes([kind]) + bytes(row))
    return best[1]

out, prev = [], bytes(w * columns * 3)
for gy in range(grid_rows):
    for y in range(h):
        line = b"".join(tiles[gy * columns + gx][2][y] if gy * columns + gx < len(tiles) else blank for gx in range(columns))
        out.append(filtered(line, prev))
        prev = line
chunk = lambda kind, body: struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w * columns, h * grid_rows, 8, 2, 0, 0, 0))
       + chunk(b"IDAT", zlib.compress(b"".join(out), 9)) + chunk(b"IEND", b""))
tmp = target + ".tmp"
open(tmp, "wb").write(png)
import os
os.replace(tmp, target)
print(f"{target}: {w * columns} x {h * grid_rows}, {len(tiles)} panels")
PY
