// The page's wiring: where files come from, what the bar's buttons do, and the draw loop.
import './style.css';
import { useClayForDefaultMaterials } from './clay-material.js';
import { deformedPositions } from './deformed-positions.js';
import { FrameTimer } from './frame-timer.js';
import { watchGlbSources } from './glb-sources.js';
import { loadGlbFromFile, loadGlbFromUrl } from './load-glb.js';
import { PlayerBar } from './player-bar.js';
import { Playback } from './playback.js';
import { installTestHook } from './test-hook.js';
import { Viewer } from './viewer.js';

const app = {
  state: 'empty',
  error: null,
  playback: null,
  frameTimer: new FrameTimer(),
  viewer: null,
  setPlaying,
  seek,
};

const bar = new PlayerBar({ onTogglePlay: () => setPlaying(!app.playback?.playing), onSeek: seek });
app.viewer = new Viewer(document.getElementById('view'), requestDraw);
installTestHook(app);

// Draw on demand: one frame per request, and every frame while playing. The frame timer only
// counts consecutive frames of playback.
let drawRequested = false;
let previousFrame = null;

function requestDraw() {
  if (drawRequested) return;
  drawRequested = true;
  requestAnimationFrame(draw);
}

function draw(now) {
  drawRequested = false;
  const playing = app.playback?.playing ?? false;
  if (playing && previousFrame !== null) {
    app.playback.advance((now - previousFrame) / 1000);
    bar.setTime(app.playback.time);
  }
  app.viewer.render();
  if (playing) {
    app.frameTimer.tick(now);
    bar.setFrameTime(app.frameTimer.averageMs);
    previousFrame = now;
    requestDraw();
  } else {
    app.frameTimer.pause();
    previousFrame = null;
  }
}

function setPlaying(playing) {
  if (app.playback === null || !app.playback.animated) return;
  app.playback.playing = playing;
  bar.setPlaying(playing);
  requestDraw();
}

function seek(seconds) {
  if (app.playback === null) return;
  app.playback.seek(seconds);
  bar.setTime(app.playback.time);
  requestDraw();
}

// A later load wins over one still in flight.
let loadCount = 0;

async function load(name, read) {
  const ticket = ++loadCount;
  app.state = 'loading';
  bar.setStatus(`Loading ${name}…`);
  try {
    const gltf = await read();
    if (ticket === loadCount) show(gltf, name);
  } catch (error) {
    if (ticket !== loadCount) return;
    app.state = 'error';
    app.error = `${name}: ${error?.message ?? error}`;
    bar.setStatus(app.error, true);
  }
}

// Checked before anything of the shown file is let go: a file that fails here leaves the last one
// playing as it was.
function checkShowable(gltf) {
  if (!gltf.scene) throw new Error('the file has no scene to show');
  let meshes = 0;
  const layers = app.viewer.maxMorphTargets();
  gltf.scene.traverse((object) => {
    if (!object.isMesh) return;
    meshes += 1;
    const targets = object.geometry.morphAttributes.position?.length ?? 0;
    if (targets > layers) {
      throw new Error(
        `${targets} morph targets, more than the ${layers} this browser's WebGL draws ` +
          '(MAX_ARRAY_TEXTURE_LAYERS); bake fewer frames (a lower --fps) or use odeskin export',
      );
    }
  });
  if (meshes === 0) throw new Error('the file has no mesh');
}

// The model's poses at a few times over its animation, one flat array: the camera frames them all.
function posesOverTime(playback, root) {
  const samples = playback.animated ? 8 : 0;
  const positions = [];
  for (let k = 0; k <= samples; k++) {
    playback.seek((playback.duration * k) / Math.max(samples, 1));
    for (const p of deformedPositions(root)) positions.push(p);
  }
  playback.seek(0);
  return positions;
}

function show(gltf, name) {
  checkShowable(gltf);
  app.playback?.dispose();
  useClayForDefaultMaterials(gltf);
  app.playback = new Playback(gltf.scene, gltf.animations);
  app.viewer.show(gltf.scene, posesOverTime(app.playback, gltf.scene));
  bar.setDuration(app.playback.duration);
  bar.setPlaying(false);
  bar.setTime(0);
  app.frameTimer = new FrameTimer();
  bar.setFrameTime(null);
  bar.setStatus(`${name}: ${describe(gltf.scene)}`);
  document.body.classList.add('loaded');
  app.state = 'ready';
  app.error = null;
  requestDraw();
}

// "8431 vertices, 60 morph targets, 12 bones": what kind of file this is at a glance.
function describe(root) {
  let vertices = 0;
  let targets = 0;
  const bones = new Set();
  root.traverse((object) => {
    if (!object.isMesh) return;
    vertices += object.geometry.attributes.position.count;
    targets = Math.max(targets, object.geometry.morphAttributes.position?.length ?? 0);
    for (const bone of object.skeleton?.bones ?? []) bones.add(bone);
  });
  const parts = [`${vertices} vertices`];
  if (targets > 0) parts.push(`${targets} morph targets`);
  if (bones.size > 0) parts.push(`${bones.size} bones`);
  return parts.join(', ');
}

watchGlbSources({
  onFile: (file) => load(file.name, () => loadGlbFromFile(file)),
  onUrl: (url) => load(url.split('/').filter(Boolean).pop() ?? url, () => loadGlbFromUrl(url)),
});
