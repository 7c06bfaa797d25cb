#!/bin/sh
# gltfpack's compressed outputs (EXT_meshopt_compression) of the horse's export, read back and fitted:
# -c as GLB and as .gltf with its .bin, -cf (a fallback .bin beside the GLB), and -cc (the octahedral,
# quaternion and exponential filters). The first three hold the same compressed data in different
# framing, so their fits must be the same to the byte.
#   gltfpack_compressed.sh ODESKIN OUT_DIR GLTFPACK
set -eu
odeskin=$1 out=$2 gltfpack=$3
"$odeskin" -q export "$out/horse.odsk" -o "$out/meshopt-in.glb"
"$gltfpack" -c -i "$out/meshopt-in.glb" -o "$out/meshopt-c.glb"
"$gltfpack" -c -i "$out/meshopt-in.glb" -o "$out/meshopt-c.gltf"
"$gltfpack" -cf -i "$out/meshopt-in.glb" -o "$out/meshopt-cf.glb"
"$gltfpack" -cc -i "$out/meshopt-in.glb" -o "$out/meshopt-cc.glb"
for f in c.glb c.gltf cf.glb cc.glb; do
  "$odeskin" fit "$out/meshopt-$f" --times 0 0.5 1 1.5 2 -o "$out/meshopt-$f.odsk"
done
cmp "$out/meshopt-c.glb.odsk" "$out/meshopt-c.gltf.odsk"
cmp "$out/meshopt-c.glb.odsk" "$out/meshopt-cf.glb.odsk"
echo "gltfpack -c, -cf and .gltf: the same asset"
