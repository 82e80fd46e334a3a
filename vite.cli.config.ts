import { defineConfig } from 'vite';
import { NODE_BUNDLE_DEFINE } from './scripts/node-bundle.ts';
import { shaderReflection } from './scripts/shader-reflection.ts';

// The CLI as an ES module for Node: dist/cli/lantern.mjs, with bvh-worker.mjs beside it (the BVH build's
// worker threads; the code both use lands in one more .mjs there). Everything is bundled except Dawn (a native
// addon, and the only package the GPU machine's prepare script carries), so the bundle runs anywhere
// `webgpu` can be imported. Shaders are inlined at build time by import.meta.glob, and so is their
// reflection (scripts/shader-reflection.ts): a run parses no WGSL for layouts or bindings.
export default defineConfig({
  define: NODE_BUNDLE_DEFINE,
  plugins: [shaderReflection()],
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
