#!/usr/bin/env bash
# Regenerates the pictures in docs/images with `odeskin render` and `odeskin play --png`, headless
# (lavapipe is enough), every call under the Khronos validation layer. Needs a built odeskin in
# ${ODESKIN_BUILD_DIR:-build} (scripts/build.sh) and the meshes in ${ODESKIN_SHARED_DIR:-../shared}/data.
# The fitted assets and intermediate frames go to a temporary folder that is removed at the end.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ODESKIN_BUILD_DIR:-$root/build}"
data="${ODESKIN_SHARED_DIR:-$root/../shared}/data"
odeskin="$build/samples/odeskin"
out="$root/docs/images"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"  # keeps the Vulkan loader quiet

[[ -x "$odeskin" ]] || { echo "make-pictures: $odeskin not found; run scripts/build.sh first" >&2; exit 1; }
[[ -d "$data/horse-gallop" ]] || { echo "make-pictures: no meshes in $data" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
horse="$data/horse-gallop"
cyl="$data/cylinder"
side=(--azimuth 60 --elevation 10)  # the horse faces +z: a three-quarter side view

echo "== fitting the horse on horse-01, -05, -09 (key times t = 0, 1, 2)"
"$odeskin" fit "$horse/horse-01.obj" "$horse/horse-05.obj" "$horse/horse-09.obj" --quiet -o "$work/horse.odsk"
echo "== fitting the cylinder on its libigl rig"
"$odeskin" fit "$cyl"/poses-1/cylinder-{1,2,3,4}.obj --bind "$cyl/cylinder.obj" --rig "$cyl/cylinder.tgf" \
  --weights "$cyl/cylinder.DMAT" --quiet -o "$work/cylinder.odsk"

echo "== horse-shaded.png: one example pose, shaded"
"$odeskin" render "$horse/horse-01.obj" "${side[@]}" --size 720x540 --validation -o "$out/horse-shaded.png"

echo "== horse-key-heat.png: at key pose horse-05, skinning alone vs odeskin vs the pose itself"
"$odeskin" render "$work/horse.odsk" "$horse/horse-05.obj" --t 1 --lbs --heat "$horse/horse-05.obj" "${side[@]}" \
  --labels "LBS only (t = 1),odeskin (t = 1),ground truth horse-05" --size 1800x450 --validation \
  -o "$out/horse-key-heat.png"

echo "== horse-inbetween-heat.png: half way between keys horse-01 and horse-05, against horse-03"
"$odeskin" render "$work/horse.odsk" "$horse/horse-03.obj" --t 0.5 --lbs --heat "$horse/horse-03.obj" "${side[@]}" \
  --labels "LBS only (t = 0.5),odeskin (t = 0.5),ground truth horse-03" --size 1800x450 --validation \
  -o "$out/horse-inbetween-heat.png"

echo "== horse-curves.png and cylinder-curves.png: iso-parametric curves over the surface"
"$odeskin" render "$work/horse.odsk" --t 0.5 --curves "${side[@]}" --size 720x540 --validation \
  -o "$out/horse-curves.png"
"$odeskin" render "$work/cylinder.odsk" --t 2 --curves --azimuth 20 --elevation 20 --size 720x540 --validation \
  -o "$out/cylinder-curves.png"

echo "== horse-turntable.png: eight turntable frames as one strip"
"$odeskin" render "$work/horse.odsk" --t 1.5 --turntable 8 --size 480x360 --validation \
  -o "$work/turntable/horse_%02d.png" --strip "$out/horse-turntable.png"

echo "== horse-play-strip.png: the contact sheet of odeskin play --png"
"$odeskin" play "$work/horse.odsk" --fps 4 --png "$work/play" --size 480x360 "${side[@]}" --validation --quiet
cp "$work/play/strip.png" "$out/horse-play-strip.png"

ls -l "$out"
