// End-to-end test of the viewer in headless Chromium (registered in CTest by web/CMakeLists.txt):
// builds the page, serves it with the GLB under test, plays it, compares the model's deformed
// vertex positions at a few times with odeskin's own CPU playback, and saves a screenshot.
//
//   node test/viewer-e2e.mjs --odeskin build/samples/odeskin --asset horse.odsk --glb horse.glb \
//     --out build/web/e2e [--times 0.4,1.7] [--tolerance 1e-4] [--page-screenshot viewer.png]
//
// --glb is the file under test, made from --asset by the command web/CMakeLists.txt names. --times
// are in the asset's key units (`odeskin play --t`); for a baked GLB (`play --fps F`) they must be
// frame times, since its STEP keys only hold exact poses there. Exits 1 on any failure, including
// a missing Chromium, odeskin or npm package: nothing is skipped.
import { execFile } from 'node:child_process';
import { existsSync } from 'node:fs';
import { mkdir, mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs, promisify } from 'node:util';

import { longestSide, readObjPositions } from './obj-positions.mjs';
import { serveStatic } from './static-server.mjs';

const WEB_DIR = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
// float32 positions in the browser against odeskin's doubles (--tolerance: more for a quantized
// file, whose rounding `odeskin export` prints).
const TOLERANCE = 1e-4;
const VIEWPORT = { width: 960, height: 600 };
// The machine running the tests has no network: keep Chromium from trying (and waiting).
const CHROMIUM_ARGS = [
  '--no-sandbox',
  // Software WebGL: the same pictures on every machine, GPU or not. Recent Chromium only falls back
  // to SwiftShader when told it is acceptable.
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--disable-quic',
  '--no-first-run',
];

const run = promisify(execFile);

class TestFailure extends Error {}

function check(condition, message) {
  if (!condition) throw new TestFailure(message);
}

function log(message) {
  console.log(`viewer-e2e: ${message}`);
}

function parseOptions() {
  const { values } = parseArgs({
    options: {
      odeskin: { type: 'string' },
      asset: { type: 'string' },
      glb: { type: 'string' },
      out: { type: 'string' },
      times: { type: 'string', default: '0.4,1.7' },
      tolerance: { type: 'string', default: String(TOLERANCE) },
      chromium: { type: 'string', default: '/usr/bin/chromium' },
      'page-screenshot': { type: 'string' },
    },
  });
  for (const name of ['odeskin', 'asset', 'glb', 'out']) check(values[name], `--${name} is required`);
  for (const name of ['odeskin', 'asset', 'glb']) check(existsSync(values[name]), `--${name} ${values[name]}: no such file`);
  check(existsSync(values.chromium), `${values.chromium}: no such file (install Debian's chromium package)`);
  const times = values.times.split(',').map(Number);
  check(times.length > 0 && times.every((t) => Number.isFinite(t) && t >= 0), `--times ${values.times}: expected t,t,...`);
  const tolerance = Number(values.tolerance);
  check(Number.isFinite(tolerance) && tolerance > 0, `--tolerance ${values.tolerance}: expected a positive number`);
  return { ...values, times, tolerance };
}

// Seconds per key-to-key segment, from `odeskin info` ("key poses: 3 (2 segments, 2 s)").
async function segmentSeconds(odeskin, asset) {
  const { stdout } = await run(odeskin, ['info', asset]);
  const match = /key poses:\s+\d+ \((\d+) segments?, ([^ ]+) s\)/.exec(stdout);
  check(match !== null, `odeskin info ${asset}: no 'key poses' line in:\n${stdout}`);
  return Number(match[2]) / Number(match[1]);
}

// odeskin's CPU evaluation at key time t, through the same command line a user would run.
async function referencePositions(options, t) {
  const file = path.join(options.out, `reference-t${t}.obj`);
  await run(options.odeskin, ['play', options.asset, '--t', String(t), '--quiet', '-o', file]);
  return readObjPositions(file);
}

// Imported on use, so a missing node_modules reads as a failure that says what to do.
async function importPackage(name) {
  try {
    return await import(name);
  } catch (error) {
    if (error?.code !== 'ERR_MODULE_NOT_FOUND') throw error;
    throw new TestFailure(`npm package ${name} is missing: run \`npm install\` in ${WEB_DIR} (scripts/install-deps.sh does)`);
  }
}

async function buildPage(outDir) {
  const { build } = await importPackage('vite');
  await build({ root: WEB_DIR, logLevel: 'warn', build: { outDir, emptyOutDir: true } });
}

async function launchChromium(options) {
  const { chromium } = await importPackage('playwright-core');
  // A fresh profile every run: nothing from earlier runs (caches, settings) leaks in.
  const profile = await mkdtemp(path.join(options.out, 'chromium-profile-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: options.chromium,
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: VIEWPORT,
  });
  return {
    context,
    close: async () => {
      await context.close();
      await rm(profile, { recursive: true, force: true });
    },
  };
}

// Plays for a while and checks that the clock moves and a frame time is shown; returns the frame
// time (ms, averaged by the page).
async function checkPlayback(page) {
  const viewer = (expression) => page.evaluate(expression);
  check(await page.isEnabled('#play'), 'the Play button is disabled for an animated file');
  await page.click('#play');
  check(await viewer(() => window.odeskinViewer.playing()), 'pressing Play did not start playback');
  await page.waitForTimeout(1000);
  const first = await viewer(() => window.odeskinViewer.time());
  await page.waitForTimeout(2000);
  const second = await viewer(() => window.odeskinViewer.time());
  check(first > 0 && second !== first, `time did not advance while playing (${first} s, then ${second} s)`);
  const frameMs = await viewer(() => window.odeskinViewer.frameTimeMs());
  const shown = await page.textContent('#frame-time');
  check(frameMs !== null && frameMs > 0, 'no frame time measured while playing');
  check(/^\d+\.\d ms\/frame$/.test(shown), `the page shows '${shown}' as its frame time`);
  await page.click('#play');
  check(!(await viewer(() => window.odeskinViewer.playing())), 'pressing Pause did not stop playback');
  return frameMs;
}

// Compares the page's deformed positions at key time t with odeskin's; returns the largest
// difference relative to the reference's bounding box.
async function checkPositions(page, options, secondsPerKey, t) {
  const reference = await referencePositions(options, t);
  // A key time stored as float32 may lie just above the double one; asking for the larger of the
  // two lands on the key itself (STEP keys hold from their time on) and moves a smooth animation
  // by less than a float32 ulp.
  const seconds = Math.max(t * secondsPerKey, Math.fround(t * secondsPerKey));
  const shown = await page.evaluate((s) => window.odeskinViewer.positionsAt(s), seconds);
  check(shown.length === reference.length,
    `t ${t}: the page has ${shown.length / 3} vertices, odeskin play ${reference.length / 3}`);
  const size = longestSide(reference);
  let worst = 0;
  let worstVertex = 0;
  for (let i = 0; i < shown.length; i++) {
    const difference = Math.abs(shown[i] - reference[i]);
    if (difference > worst) [worst, worstVertex] = [difference, Math.floor(i / 3)];
  }
  const relative = worst / size;
  log(`t ${t} (${seconds} s): ${reference.length / 3} vertices, largest difference ${worst.toExponential(2)} ` +
      `= ${relative.toExponential(2)} of the box (vertex ${worstVertex})`);
  check(relative <= options.tolerance, `t ${t}: vertex ${worstVertex} is ${relative.toExponential(2)} of the box ` +
      `away from odeskin play (tolerance ${options.tolerance})`);
  return relative;
}

// Saves the canvas alone (the bar never covers it) and checks WebGL drew the model: the PNG is
// decoded back in the page, and the lit model is the only thing brighter than the background and
// the grid lines.
async function checkScreenshot(page, file) {
  const png = await page.locator('#view').screenshot({ path: file });
  const share = await page.evaluate(async (base64) => {
    const image = new Image();
    image.src = `data:image/png;base64,${base64}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const { data } = context.getImageData(0, 0, image.width, image.height);
    let bright = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (0.2126 * data[i] + 0.7152 * data[i + 1] + 0.0722 * data[i + 2] > 120) bright++;
    }
    return bright / (data.length / 4);
  }, png.toString('base64'));
  log(`screenshot ${file}: the model covers ${(100 * share).toFixed(1)}% of the canvas`);
  check(share > 0.01 && share < 0.9, `${file}: the model covers ${(100 * share).toFixed(2)}% of the canvas ` +
      '(expected 1% to 90%): WebGL drew nothing, or nothing else');
}

// A file cut in half is named as such (the loader's own words were "Invalid typed array length"),
// and the page stays usable: the good file loads after it.
async function checkCutFile(page, server, goodUrl) {
  await page.goto(`${server.url}/?src=${encodeURIComponent('bad/cut.glb')}`);
  await page.waitForFunction(() => ['ready', 'error'].includes(window.odeskinViewer?.state()), null, { timeout: 60000 });
  const error = await page.evaluate(() => window.odeskinViewer.error());
  check(/^cut\.glb: cut short: its header declares \d+ bytes, the file has \d+$/.test(error ?? ''),
    `a cut .glb reads '${error}'`);
  await page.goto(goodUrl);
  await page.waitForFunction(() => ['ready', 'error'].includes(window.odeskinViewer?.state()), null, { timeout: 60000 });
  check((await page.evaluate(() => window.odeskinViewer.error())) === null, 'the good file did not load after a cut one');
}

async function main() {
  const options = parseOptions();
  await mkdir(options.out, { recursive: true });
  const secondsPerKey = await segmentSeconds(options.odeskin, options.asset);
  const dist = path.join(options.out, 'dist');
  await buildPage(dist);
  log(`built the page into ${dist}`);

  const bad = path.join(options.out, 'bad');
  await mkdir(bad, { recursive: true });
  const glb = await readFile(options.glb);
  await writeFile(path.join(bad, 'cut.glb'), glb.subarray(0, glb.length >> 1));
  const server = await serveStatic({ '/': dist, '/files/': path.dirname(path.resolve(options.glb)), '/bad/': bad });
  const browser = await launchChromium(options).catch(async (error) => {
    await server.close();
    throw error;
  });
  try {
    const page = await browser.context.newPage();
    const problems = [];
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    page.on('console', (message) => {
      if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
    });
    const url = `${server.url}/?src=${encodeURIComponent(`files/${path.basename(options.glb)}`)}`;
    await page.goto(url);
    await page.waitForFunction(() => ['ready', 'error'].includes(window.odeskinViewer?.state()), null, { timeout: 60000 });
    const error = await page.evaluate(() => window.odeskinViewer.error());
    check(error === null, `the page could not load ${options.glb}: ${error}`);
    const renderer = await page.evaluate(() => {
      const gl = document.createElement('canvas').getContext('webgl2');
      if (!gl) return 'no WebGL 2';
      const debug = gl.getExtension('WEBGL_debug_renderer_info');
      return gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
    });
    log(`loaded ${url} (WebGL: ${renderer}); ${await page.textContent('#status')}`);

    const frameMs = await checkPlayback(page);
    log(`frame time while playing: ${frameMs.toFixed(1)} ms (${(1000 / frameMs).toFixed(0)} fps), shown as ` +
        `'${await page.textContent('#frame-time')}'`);
    for (const t of options.times) await checkPositions(page, options, secondsPerKey, t);

    // Let the page draw the last pose asked for before the pictures are taken.
    await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));
    await checkScreenshot(page, path.join(options.out, 'viewer-canvas.png'));
    if (options['page-screenshot']) {
      await page.screenshot({ path: options['page-screenshot'] });
      log(`page screenshot: ${options['page-screenshot']}`);
    }
    await checkCutFile(page, server, url);
    log('a cut copy of the file is refused as cut short, and the file loads after it');
    check(problems.length === 0, `the page reported:\n  ${problems.join('\n  ')}`);
  } finally {
    await browser.close();
    await server.close();
  }
  log('passed');
}

main().catch((error) => {
  console.error(`viewer-e2e: FAILED: ${error instanceof TestFailure ? error.message : error.stack ?? error}`);
  process.exit(1);
});
