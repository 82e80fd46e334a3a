/**
 * WGSL -> GLSL ES 3.00 for the WebGL2 backend, at build time (issue #30): every program of
 * src/webgl2/programs.ts translated by naga's GLSL back end (the naga-wasm package, a dev dependency:
 * Node loads its WebAssembly on import), its uniform blocks and samplers read from the output
 * (src/webgl2/glsl.ts parseGlslInterface), the ES 3.10 built-ins naga uses defined for ES 3.00
 * (src/webgl2/glsl-es300.ts). The Vite plugin puts the result in place of
 * src/webgl2/glsl-translated.ts for the page build and the dev server, so the page carries GLSL text
 * and no translator; tests call translateProgram directly. Translation is deterministic (its test).
 */
import { resolve } from 'node:path';
import { translate } from 'naga-wasm';
import { runnerImport, type Plugin } from 'vite';
import type { GlslProgram } from '../src/webgl2/glsl.ts';
import type { WebGl2ProgramSpec } from '../src/webgl2/programs.ts';

const TARGET = 'src/webgl2/glsl-translated.ts';
const PROGRAMS = 'src/webgl2/programs.ts';
const TRANSLATE = 'src/webgl2/translate.ts';

type TranslateSpec = typeof import('../src/webgl2/translate.ts').translateSpec;

/** One program translated with the Node package (src/webgl2/translate.ts translateSpec). */
export function translateProgram(spec: WebGl2ProgramSpec, translateSpec: TranslateSpec): GlslProgram {
  return translateSpec(spec, translate);
}

/** Every program, translated, as the JSON text glsl-translated.ts stands for; `extra` adds programs (a test's own). */
export async function translateAll(root: string, extra: readonly WebGl2ProgramSpec[] = []): Promise<string> {
  const { module: programs } = await runnerImport<{ webGl2ProgramSpecs: () => WebGl2ProgramSpec[] }>(resolve(root, PROGRAMS), { root, configFile: false, logLevel: 'error' });
  const { module: translation } = await runnerImport<{ translateSpec: TranslateSpec }>(resolve(root, TRANSLATE), { root, configFile: false, logLevel: 'error' });
  return JSON.stringify([...programs.webGl2ProgramSpecs(), ...extra].map((spec) => translateProgram(spec, translation.translateSpec)));
}

export interface GlslTranslationOptions {
  /** The repository's root (default: the Vite root): where src/webgl2 is. */
  readonly sourceRoot?: string;
  /** Programs translated besides the backend's own (a browser test's harness). */
  readonly extra?: readonly WebGl2ProgramSpec[];
}

/** Loads the translation in place of src/webgl2/glsl-translated.ts (the page build and the dev server alike). */
export function glslTranslation(options: GlslTranslationOptions = {}): Plugin {
  let root = options.sourceRoot ?? process.cwd();
  return {
    name: 'lantern:glsl-translation',
    configResolved(config) {
      root = options.sourceRoot ?? config.root;
    },
    async load(id) {
      if (id.split('?')[0] !== resolve(root, TARGET)) return null;
      const started = performance.now();
      const json = await translateAll(root, options.extra);
      this.info(`WGSL -> GLSL for WebGL2: ${(performance.now() - started).toFixed(0)} ms`);
      return `export const TRANSLATED_GLSL = ${JSON.stringify(json)};\n`;
    },
  };
}
