import { defineConfig } from 'vite';
import { NODE_BUNDLE_DEFINE } from './node-bundle.ts';

// The long fuzz run (`npm run fuzz -- --minutes N`) as plain Node modules: dist/fuzz/fuzz.mjs drives,
// fuzz-worker.mjs runs the cases (a worker can be cut off when a case hangs). Bundled like the CLI,
// so the loaders run exactly as `lantern info` runs them.
export default defineConfig({
  define: NODE_BUNDLE_DEFINE,
  build: {
    ssr: true,
    outDir: 'dist/fuzz',
    emptyOutDir: true,
    target: 'node20',
    minify: false,
    sourcemap: true,
    rollupOptions: {
      input: { fuzz: 'scripts/fuzz.ts', 'fuzz-worker': 'scripts/fuzz-worker.ts' },
      output: { entryFileNames: '[name].mjs', chunkFileNames: '[name]-[hash].mjs' },
    },
  },
  ssr: { noExternal: true },
});
