/**
 * The WebGL2 backend's GLSL programs (glsl.ts GlslProgram[], as JSON text). Run from sources (Vitest)
 * this file is what it says: undefined. The page build and its dev server load
 * scripts/glsl-translation.ts's translation in its place (vite.config.ts), so the shipped page carries
 * GLSL strings and neither WGSL-to-GLSL translator nor its WebAssembly.
 */
export const TRANSLATED_GLSL: string | undefined = undefined;
