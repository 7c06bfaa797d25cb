// A tiny static file server for the end-to-end test: the built page and the GLB under test, on
// 127.0.0.1 at a free port the system picks. Node's own http module; no packages, no network.
import { createReadStream } from 'node:fs';
import { stat } from 'node:fs/promises';
import { createServer } from 'node:http';
import path from 'node:path';

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.glb': 'model/gltf-binary',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
};

// mounts: URL prefix (ending in '/') -> folder, e.g. { '/': dist, '/files/': glbFolder }. Resolves
// to { url, close() } once listening; url has no trailing slash.
export function serveStatic(mounts) {
  // Longest prefix first, so '/files/' wins over '/'.
  const ordered = Object.entries(mounts).sort(([a], [b]) => b.length - a.length);
  const server = createServer(async (request, response) => {
    const file = await resolveFile(ordered, request.url);
    if (file === null) {
      response.writeHead(404, { 'content-type': 'text/plain' }).end('not found\n');
      return;
    }
    response.writeHead(200, {
      'content-type': TYPES[path.extname(file).toLowerCase()] ?? 'application/octet-stream',
      'cache-control': 'no-store',
    });
    createReadStream(file).pipe(response);
  });
  return new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      resolve({
        url: `http://127.0.0.1:${port}`,
        close: () => new Promise((done) => server.close(done)),
      });
    });
  });
}

// The file a request names, or null: unknown mount, missing file, or a path that climbs out of
// its folder.
async function resolveFile(mounts, requestUrl) {
  let pathname;
  try {
    pathname = decodeURIComponent(new URL(requestUrl, 'http://localhost').pathname);
  } catch {
    return null;
  }
  for (const [prefix, folder] of mounts) {
    if (!pathname.startsWith(prefix)) continue;
    const root = path.resolve(folder);
    let file = path.resolve(root, '.' + pathname.slice(prefix.length - 1));
    if (file !== root && !file.startsWith(root + path.sep)) return null;
    try {
      if ((await stat(file)).isDirectory()) file = path.join(file, 'index.html');
      return (await stat(file)).isFile() ? file : null;
    } catch {
      return null;
    }
  }
  return null;
}
