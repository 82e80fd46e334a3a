/**
 * What the bundles for Node (the CLI: vite.cli.config.ts; the fuzz run: fuzz.vite.config.ts) add to a
 * Vite build. They are ES modules, and a CommonJS package bundled into one loses the `__dirname` and
 * `__filename` that Node's CommonJS wrapper gives each module: Rolldown provides `require` there (from
 * `createRequire(import.meta.url)`) but leaves those two as free names (rolldown#9719), which throw
 * "__dirname is not defined" when read. draco3dgltf's Emscripten decoder reads `__dirname` as soon as
 * it starts under Node, although it is handed its .wasm and never opens a file (gltf/draco.ts). They
 * become the bundle file's own folder and name, as a bundler with CommonJS output would give them.
 */
export const NODE_BUNDLE_DEFINE = {
  __dirname: 'import.meta.dirname',
  __filename: 'import.meta.filename',
};
