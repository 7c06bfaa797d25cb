// Vite settings for the viewer. `npm run build` writes web/dist/; the end-to-end test builds into the
// CMake build tree instead (it passes its own outDir).
import { defineConfig } from 'vite';

export default defineConfig({
  // Relative asset URLs, so the built page works from any folder of any static server.
  base: './',
  build: {
    // three.js alone is about 700 kB minified; it is one file the page always needs, so splitting it
    // would buy nothing.
    chunkSizeWarningLimit: 1024,
  },
});
