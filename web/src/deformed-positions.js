import { Vector3 } from 'three';

// The vertex positions three.js draws, computed on the CPU: Mesh.getVertexPosition adds the morph
// targets and SkinnedMesh's override then applies the skin, the order the glTF specification (and
// three's vertex shader) use. Returned in world space, so they compare with odeskin's own output
// directly, as one flat [x, y, z, ...] array over every mesh in scene order.
export function deformedPositions(root) {
  root.updateMatrixWorld(true);
  const positions = [];
  const vertex = new Vector3();
  root.traverse((object) => {
    if (!object.isMesh) return;
    const count = object.geometry.attributes.position.count;
    for (let i = 0; i < count; i++) {
      object.getVertexPosition(i, vertex).applyMatrix4(object.matrixWorld);
      positions.push(vertex.x, vertex.y, vertex.z);
    }
  });
  return positions;
}
