import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// odeskin writes plain glTF 2.0 (no Draco or meshopt compression), so the bare loader reads it;
// nothing is fetched but the file itself.
const loader = new GLTFLoader();

export function loadGlbFromUrl(url) {
  return loader.loadAsync(url);
}

export async function loadGlbFromFile(file) {
  return loader.parseAsync(await file.arrayBuffer(), '');
}
