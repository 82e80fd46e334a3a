import { defineConfig } from 'vite';

// The browser page: index.html at the root, built into dist/app with relative URLs so the folder
// can be served from anywhere.
export default defineConfig({
  base: './',
  build: { outDir: 'dist/app', emptyOutDir: true, target: 'es2022' },
});
