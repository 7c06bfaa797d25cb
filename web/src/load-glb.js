import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// odeskin writes plain glTF 2.0 (no Draco or meshopt compression), so the bare loader reads it;
// nothing is fetched but the file itself (and, for a .gltf URL, the buffers it names beside it).
const loader = new GLTFLoader();

export async function loadGlbFromUrl(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`HTTP ${response.status} ${response.statusText}`.trim());
  return parse(await response.arrayBuffer(), url.slice(0, url.lastIndexOf('/') + 1));
}

export async function loadGlbFromFile(file) {
  return parse(await file.arrayBuffer(), '');
}

// The loader's own words for a file that is not glTF are a parser's ("Invalid typed array length:
// 4", "Unexpected token"): the header says what is wrong first.
function parse(bytes, base) {
  const view = new DataView(bytes);
  const magic = bytes.byteLength >= 4 ? String.fromCharCode(...new Uint8Array(bytes, 0, 4)) : '';
  if (bytes.byteLength === 0) throw new Error('the file is empty');
  if (magic === 'glTF') {
    if (bytes.byteLength < 20) throw new Error(`${bytes.byteLength} bytes, too short for a glTF binary`);
    const declared = view.getUint32(8, true);
    if (declared > bytes.byteLength) {
      throw new Error(`cut short: its header declares ${declared} bytes, the file has ${bytes.byteLength}`);
    }
  } else if (!/^\s*\{/.test(new TextDecoder().decode(bytes.slice(0, 64)))) {
    throw new Error('not a glTF file (.glb, or .gltf JSON)');
  }
  return loader.parseAsync(bytes, base);
}
