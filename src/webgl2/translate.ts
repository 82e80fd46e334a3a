/**
 * One program's WGSL -> GLSL ES 3.00: naga's GLSL back end for each stage, the ES 3.10 built-ins it
 * uses defined (glsl-es300.ts), the interface read (glsl.ts). Pure given naga's `translate`: the
 * build passes the Node package's (scripts/glsl-translation.ts), the WebGL2 page the browser
 * package's, loaded only when a scene needs a tracer variant the build did not make
 * (webgl2-tracer.ts).
 */
import { LanternError } from '../errors.ts';
import { esslFixups } from './glsl-es300.ts';
import { parseGlslInterface, type GlslProgram } from './glsl.ts';
import type { WebGl2ProgramSpec } from './programs.ts';

/** naga-wasm's translate, as far as this uses it. */
export type NagaTranslate = (input: { from: 'wgsl'; to: 'glsl'; source: string; options: { version: '300 es'; stage: 'vertex' | 'fragment'; entryPoint: string } }) => string;

export function translateSpec(spec: WebGl2ProgramSpec, translate: NagaTranslate): GlslProgram {
  const stage = (stage: 'vertex' | 'fragment', entryPoint: string): string => {
    try {
      return esslFixups(translate({ from: 'wgsl', to: 'glsl', source: spec.wgsl, options: { version: '300 es', stage, entryPoint } }));
    } catch (e) {
      const formatted = (e as { formatted?: string }).formatted ?? (e as Error).message;
      throw new LanternError(`GLSL translation of the WebGL2 program '${spec.key}' (${spec.module}, ${stage} entry ${entryPoint}) failed: ${formatted.split('\n')[0]}`, undefined, { cause: e });
    }
  };
  const vertex = stage('vertex', spec.vertexEntry);
  const fragment = stage('fragment', spec.fragmentEntry);
  return { key: spec.key, module: spec.module, vertex, fragment, ...parseGlslInterface(vertex, fragment) };
}
