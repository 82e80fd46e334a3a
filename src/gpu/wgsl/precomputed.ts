/**
 * The bundles' precomputed reflection of src/shaders (reflect.ts PrecomputedReflection, as JSON text).
 * Run from sources (Vitest, the dev server) this file is what it says: undefined, and reflect.ts
 * reflects every module live. A build (vite.config.ts, vite.cli.config.ts) does not read this file:
 * scripts/shader-reflection.ts loads ./precompute.ts's output in its place.
 */
export const PRECOMPUTED_REFLECTION: string | undefined = undefined;
