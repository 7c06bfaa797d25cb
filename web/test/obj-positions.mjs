// Vertex positions from an OBJ file as one flat [x, y, z, ...] array: only the `v` lines matter
// when comparing index by index with the viewer.
import { readFile } from 'node:fs/promises';

export async function readObjPositions(file) {
  const positions = [];
  for (const line of (await readFile(file, 'utf8')).split('\n')) {
    if (!line.startsWith('v ')) continue;
    const xyz = line.trim().split(/\s+/).slice(1, 4).map(Number);
    if (xyz.length !== 3 || !xyz.every(Number.isFinite)) throw new Error(`${file}: bad vertex line '${line.trim()}'`);
    positions.push(...xyz);
  }
  return positions;
}

// The longest side of the positions' axis-aligned bounding box.
export function longestSide(positions) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i++) {
    min[i % 3] = Math.min(min[i % 3], positions[i]);
    max[i % 3] = Math.max(max[i % 3], positions[i]);
  }
  return Math.max(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
}
