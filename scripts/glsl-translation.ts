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
const GLSL = 'src/webgl2/glsl.ts';
const FIXUPS = 'src/webgl2/glsl-es300.ts';

type ParseInterface = typeof import('../src/webgl2/glsl.ts').parseGlslInterface;
type Fixups = typeof import('../src/webgl2/glsl-es300.ts').esslFixups;

/** One program's two stages translated and its interface read; naga's message (module:line) on a failure, naming the program. */
export function translateProgram(spec: WebGl2ProgramSpec, parseGlslInterface: ParseInterface, esslFixups: Fixups): GlslProgram {
  const stage = (stage: 'vertex' | 'fragment', entryPoint: string): string => {
    try {
      return esslFixups(translate({ from: 'wgsl', to: 'glsl', source: spec.wgsl, options: { version: '300 es', stage, entryPoint } }));
    } catch (e) {
      const formatted = (e as { formatted?: string }).formatted ?? (e as Error).message;
      throw new Error(`GLSL translation of the WebGL2 program '${spec.key}' (${spec.module}, ${stage} entry ${entryPoint}) failed:\n${formatted}`, { cause: e });
    }
  };
  const vertex = stage('vertex', spec.vertexEntry);
  const fragment = stage('fragment', spec.fragmentEntry);
  return { key: spec.key, module: spec.module, vertex, fragment, ...parseGlslInterface(vertex, fragment) };
}

/** Every program, translated, as the JSON text glsl-translated.ts stands for; `extra` adds programs (a test's own). */
export async function translateAll(root: string, extra: readonly WebGl2ProgramSpec[] = []): Promise<string> {
  const { module: programs } = await runnerImport<{ webGl2ProgramSpecs: () => WebGl2ProgramSpec[] }>(resolve(root, PROGRAMS), { root, configFile: false, logLevel: 'error' });
  const { module: glsl } = await runnerImport<{ parseGlslInterface: ParseInterface }>(resolve(root, GLSL), { root, configFile: false, logLevel: 'error' });
  const { module: es300 } = await runnerImport<{ esslFixups: Fixups }>(resolve(root, FIXUPS), { root, configFile: false, logLevel: 'error' });
  return JSON.stringify([...programs.webGl2ProgramSpecs(), ...extra].map((spec) => translateProgram(spec, glsl.parseGlslInterface, es300.esslFixups)));
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
