/**
 * Every WGSL module of src/shaders, by path without extension ("lib/random", "passes/path-trace").
 * Vite inlines the files at build time (browser bundle, CLI bundle, Vitest), so no code path reads
 * shader files at run time.
 */
const files = import.meta.glob('./**/*.wgsl', { query: '?raw', import: 'default', eager: true }) as Record<string, string>;

export const SHADER_MODULES: ReadonlyMap<string, string> = new Map(
  Object.entries(files).map(([path, source]) => [path.replace(/^\.\//, '').replace(/\.wgsl$/, ''), source]),
);
