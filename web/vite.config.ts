// Builds the viewer into dist/, which the pliant binary embeds at compile time
// (crates/server/build.rs). `npm run dev` proxies /ws to a `pliant serve` on port 8080.
import { defineConfig } from 'vite';

export default defineConfig({
  base: '/',
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 1500,
    sourcemap: false,
  },
  server: {
    proxy: { '/ws': { target: 'ws://127.0.0.1:8080', ws: true } },
  },
});
