// The page's wiring: where files come from, what the bar's buttons do, and the draw loop.
import './style.css';
import { useClayForDefaultMaterials } from './clay-material.js';
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

function show(gltf, name) {
  app.playback?.dispose();
  useClayForDefaultMaterials(gltf);
  // Pose the model at time 0 before the viewer frames it.
  app.playback = new Playback(gltf.scene, gltf.animations);
  app.viewer.show(gltf.scene);
  bar.setDuration(app.playback.duration);
  bar.setPlaying(false);
  bar.setTime(0);
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
  onUrl: (url) => load(url.split('/').pop(), () => loadGlbFromUrl(url)),
});
