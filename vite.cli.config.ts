import { defineConfig } from 'vite';
import { NODE_BUNDLE_DEFINE } from './scripts/node-bundle.ts';

// The CLI as an ES module for Node: dist/cli/lantern.mjs, with bvh-worker.mjs beside it (the BVH build's
// worker threads; the code both use lands in one more .mjs there). Everything is bundled except Dawn (a native
// addon, and the only package the GPU machine's prepare script carries), so the bundle runs anywhere
// `webgpu` can be imported. Shaders are inlined at build time by import.meta.glob.
export default defineConfig({
  define: NODE_BUNDLE_DEFINE,
  build: {
    ssr: true,
    outDir: 'dist/cli',
    emptyOutDir: true,
    target: 'node20',
    minify: false,
    sourcemap: true,
    rollupOptions: {
      input: { lantern: 'src/cli/main.ts', 'bvh-worker': 'src/cli/bvh-worker.ts' },
      output: { entryFileNames: '[name].mjs', chunkFileNames: '[name]-[hash].mjs', banner: '#!/usr/bin/env node' },
    },
  },
  ssr: {
    noExternal: true,
    external: ['webgpu'],
  },
});
