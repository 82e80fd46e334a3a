import { defineConfig } from 'vite';
import { glslTranslation } from './scripts/glsl-translation.ts';
import { shaderReflection } from './scripts/shader-reflection.ts';

// The browser page: index.html at the root, built into dist/app with relative URLs so the folder
// can be served from anywhere. The WGSL's reflection is made at build time (scripts/shader-reflection.ts),
// for the page and its workers alike; the dev server reflects live. The WebGL2 backend's GLSL is
// translated from the WGSL here too (scripts/glsl-translation.ts): the page carries no translator.
export default defineConfig({
  base: './',
  plugins: [shaderReflection(), glslTranslation()],
  worker: { plugins: () => [shaderReflection()] },
  // The page's script is ~700 kB (WGSL text, the WGSL reflector, Tweakpane, image codecs): one file
  // loaded once is fine for a local tool, so the warning threshold sits above it.
  build: { outDir: 'dist/app', emptyOutDir: true, target: 'es2022', chunkSizeWarningLimit: 1024 },
});
