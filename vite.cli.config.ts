import { defineConfig } from 'vite';

// The CLI as one ES module for Node: dist/cli/lantern.mjs. Everything is bundled except Dawn (a native
// addon, and the only package the GPU machine's prepare script carries), so the bundle runs anywhere
// `webgpu` can be imported. Shaders are inlined at build time by import.meta.glob.
export default defineConfig({
  build: {
    ssr: 'src/cli/main.ts',
    outDir: 'dist/cli',
    emptyOutDir: true,
    target: 'node20',
    minify: false,
    sourcemap: true,
    rollupOptions: {
      output: { entryFileNames: 'lantern.mjs', banner: '#!/usr/bin/env node' },
    },
  },
  ssr: {
    noExternal: true,
    external: ['webgpu'],
  },
});
