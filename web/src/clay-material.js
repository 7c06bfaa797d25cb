import { DoubleSide, MeshStandardMaterial } from 'three';

// glTF's default material, used by primitives that name none (odeskin's baked files), is fully
// metallic; without an environment map it renders nearly black. Those meshes get a matte clay
// instead, keeping the loader's flat shading for files without normals, drawn on both sides. Materials a file defines
// are left alone.
export function useClayForDefaultMaterials(gltf) {
  gltf.scene.traverse((object) => {
    if (!object.isMesh) return;
    // The loader records the file's material index for every material it read (and for its
    // flat-shaded copies); the default material has none.
    if (gltf.parser.associations.get(object.material)?.materials !== undefined) return;
    object.material = new MeshStandardMaterial({
      color: 0xc9c2b6,
      roughness: 0.8,
      metalness: 0,
      flatShading: object.material.flatShading,
      // Open surfaces (odeskin surface's patches, a tube's inside) are seen from both sides.
      side: DoubleSide,
    });
  });
}
