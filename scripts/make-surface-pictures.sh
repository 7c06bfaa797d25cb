#!/usr/bin/env bash
# Regenerates the blending-surface pictures in docs/images/blend-*.png (docs/surfaces.md): meshes
# from `odeskin blend` and odeskin_blend_samples, drawn headless by `odeskin render` (lavapipe is
# enough) under the Khronos validation layer. Needs a build with the odeskin program
# (${ODESKIN_BUILD_DIR:-build}, scripts/build.sh). The OBJ files go to a temporary folder that is
# removed at the end; pass KEEP=DIR to keep them there instead.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
odeskin="$build/samples/odeskin"
samples="$build/samples/surfaces/odeskin_blend_samples"
out="$root/docs/images"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"  # keeps the Vulkan loader quiet

for program in "$odeskin" "$samples"; do
  [[ -x "$program" ]] || { echo "make-surface-pictures: $program not found; build odeskin and odeskin_blend_samples" >&2; exit 1; }
done
if [[ -n "${KEEP:-}" ]]; then
  work="$KEEP"
  mkdir -p "$work"
else
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$out"
view=(--up z --validation)

# blend ID ALPHA BETA GAMMA FILE: one Eq 3.18-style blend with explicit parameters.
blend() { "$odeskin" -q blend --example "$1" --alpha "$2" --beta "$3" --gamma "$4" --res 64,256 -o "$5"; }

# row PNG PARAMETER-SETS...: Eq 3.18 blends for "alpha beta gamma" sets, side by side, one scale.
row() {
  local png="$1"; shift
  local files=() labels=()
  for set in "$@"; do
    read -r a b g <<<"$set"
    blend 3.18 "$a" "$b" "$g" "$work/shape_${a}_${b}_${g}.obj"
    files+=("$work/shape_${a}_${b}_${g}.obj")
    labels+=("$a; $b; $g")
  done
  "$odeskin" render "${files[@]}" "${view[@]}" --elevation 20 --labels "$(IFS=,; echo "${labels[*]}")" --size 1024x288 -o "$out/$png"
}

echo "== blend-examples.png: Eqs 3.15, 3.16, 3.17 with the thesis's parameters"
for id in 3.15 3.16 3.17; do "$odeskin" -q blend --example "$id" --res 64,256 -o "$work/ex_$id.obj"; done
"$odeskin" render "$work"/ex_3.15.obj "$work"/ex_3.16.obj "$work"/ex_3.17.obj "${view[@]}" --elevation 30 \
  --labels "Eq 3.15 (1; 2; 1),Eq 3.16 (1; 3; 1),Eq 3.17 (1; 1; 1)" --size 1024x384 -o "$out/blend-examples.png"

echo "== blend-fig35.png: Eq 3.18 with Fig. 3.5's four parameter sets (alpha; beta; gamma)"
row blend-fig35.png "1 0.5 1" "3.7 2.5 1" "3.7 2 18" "2 0.5 1"
echo "== blend-shape-alpha.png, -beta.png, -gamma.png: one parameter at a time (Fig. 3.6's study)"
row blend-shape-alpha.png "0.05 0.5 1" "0.2 0.5 1" "1 0.5 1" "20 0.5 1"
row blend-shape-beta.png "1 -40 1" "1 -5 1" "1 10 1" "1 30 1"
row blend-shape-gamma.png "1 0.5 -60" "1 0.5 1" "1 0.5 60" "1 0.5 250"

echo "== blend-fig37.png: the cubic Hermite blend (Eq 3.19) against Fig. 3.7's three ODE blends"
"$odeskin" -q blend --example 3.18 --hermite --res 64,256 -o "$work/hermite.obj"
blend 3.18 1 1 0.1 "$work/f37_green.obj"
blend 3.18 1 11 1 "$work/f37_pink.obj"
blend 3.18 1 17 1 "$work/f37_blue.obj"
"$odeskin" render "$work/hermite.obj" "$work/f37_green.obj" "$work/f37_pink.obj" "$work/f37_blue.obj" "${view[@]}" --elevation 20 \
  --labels "Hermite,1; 1; 0.1 (green),1; 11; 1 (pink),1; 17; 1 (blue)" --size 1024x288 -o "$out/blend-fig37.png"

echo "== blend-fig37-profiles.png and blend-corner.png: odeskin_blend_samples (self-checking)"
"$samples" "$work/samples"
cp "$work/samples/fig37-profiles.png" "$out/blend-fig37-profiles.png"
"$odeskin" render "$work/samples/corner.obj" "$work/samples/corner-half.obj" --up z --azimuth 300 --elevation 30 \
  --validation --labels "patch tangent scale s = -1 (C17 default),s = -1/2" --size 1024x384 -o "$out/blend-corner.png"

ls -l "$out"/blend-*.png
