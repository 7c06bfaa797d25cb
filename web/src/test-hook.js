import { deformedPositions } from './deformed-positions.js';

// window.odeskinViewer: what the end-to-end test (web/test/viewer-e2e.mjs) reads and drives, and a
// handle for poking at the page from the developer console. The page itself never uses it.
export function installTestHook(app) {
  window.odeskinViewer = {
    // 'empty', 'loading', 'ready' or 'error'; error() says what went wrong.
    state: () => app.state,
    error: () => app.error,
    duration: () => app.playback?.duration ?? 0,
    time: () => app.playback?.time ?? 0,
    playing: () => app.playback?.playing ?? false,
    frameTimeMs: () => app.frameTimer.averageMs,
    // Pauses, shows the pose at `seconds`, and returns its deformed vertex positions in world space
    // as a flat [x, y, z, ...] array over every mesh, in the file's vertex order.
    positionsAt(seconds) {
      if (app.viewer.model === null) throw new Error('positionsAt: no model is loaded');
      app.setPlaying(false);
      app.seek(seconds);
      return deformedPositions(app.viewer.model);
    },
  };
}
