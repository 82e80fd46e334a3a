/**
 * The GLSL ES 3.00 programs of the WebGL2 backend, as the build translated them from WGSL
 * (scripts/glsl-translation.ts, naga's GLSL back end), and what a program's interface is: naga names
 * a WGSL binding `_group_G_binding_B_vs|fs` (a texture and the sampler it is sampled with become one
 * sampler uniform named after the texture) and wraps a uniform buffer in a std140 block
 * `Struct_block_N<Stage>` holding one member of the WGSL struct. parseGlslInterface reads those
 * declarations from the translated text once, at build time; the host then finds each by name in the
 * linked program (getUniformBlockIndex, getUniformLocation) and checks the block's offsets against the
 * WGSL layout (program.ts). Pure: no GL, no DOM.
 */
import { LanternError } from '../errors.ts';
import { TRANSLATED_GLSL } from './glsl-translated.ts';

/** A std140 uniform block standing for a WGSL `var<uniform>` of struct type `struct`. */
export interface GlslUniformBlock {
  readonly group: number;
  readonly binding: number;
  readonly stage: 'vertex' | 'fragment';
  /** The block's name (what getUniformBlockIndex takes). */
  readonly block: string;
  /** The WGSL struct it holds. */
  readonly struct: string;
  /** The block's one member, the struct (its fields are reported as `block.instance.field`). */
  readonly instance: string;
}

/** A sampler uniform standing for a WGSL texture (with the sampler it is sampled with, if any). */
export interface GlslSampler {
  readonly group: number;
  readonly binding: number;
  readonly stage: 'vertex' | 'fragment';
  readonly name: string;
  /** sampler2D, usampler2D, sampler2DArray, ...: the texture the unit must hold. */
  readonly type: string;
}

/** One program of the backend: a WGSL module's vertex and fragment entries, translated. */
export interface GlslProgram {
  readonly key: string;
  /** The WGSL module of src/shaders it was translated from (its structs give the uniform layouts). */
  readonly module: string;
  readonly vertex: string;
  readonly fragment: string;
  readonly blocks: readonly GlslUniformBlock[];
  readonly samplers: readonly GlslSampler[];
}

const BLOCK = /^layout\(std140\) uniform (\w+) \{ (\w+) (_group_(\d+)_binding_(\d+)_(vs|fs)); \};$/gm;
const SAMPLER = /^uniform (?:highp |mediump |lowp )?(u?i?sampler\w+) (_group_(\d+)_binding_(\d+)_(vs|fs));$/gm;

/** The uniform blocks and samplers a translated program declares, both stages, each once per stage. */
export function parseGlslInterface(vertex: string, fragment: string): { blocks: GlslUniformBlock[]; samplers: GlslSampler[] } {
  const blocks: GlslUniformBlock[] = [];
  const samplers: GlslSampler[] = [];
  for (const text of [vertex, fragment]) {
    for (const m of text.matchAll(BLOCK)) {
      blocks.push({ block: m[1]!, struct: m[2]!, instance: m[3]!, group: Number(m[4]), binding: Number(m[5]), stage: m[6] === 'vs' ? 'vertex' : 'fragment' });
    }
    for (const m of text.matchAll(SAMPLER)) {
      samplers.push({ type: m[1]!, name: m[2]!, group: Number(m[3]), binding: Number(m[4]), stage: m[5] === 'vs' ? 'vertex' : 'fragment' });
    }
  }
  // Anything else declared `uniform` would be a binding the host does not know how to fill.
  for (const text of [vertex, fragment]) {
    for (const line of text.split('\n')) {
      if (/^(layout\(.*\) )?uniform /.test(line) && !blocks.some((b) => line.includes(` ${b.instance};`)) && !samplers.some((s) => line.endsWith(` ${s.name};`))) {
        throw new LanternError(`GLSL translation: a uniform declaration the WebGL2 host does not recognise: ${line.trim()}`);
      }
    }
  }
  return { blocks, samplers };
}

let decoded: Map<string, GlslProgram> | undefined;

/** Every program the build translated (src/webgl2/glsl-translated.ts, replaced at build time), by key. */
export function translatedPrograms(source: string | undefined = TRANSLATED_GLSL): ReadonlyMap<string, GlslProgram> {
  if (source === undefined) {
    throw new LanternError('the WebGL2 backend has no GLSL: its shaders are translated when the page is built', 'Run the built page (npm run build:app) or the dev server, not the sources alone');
  }
  if (source === TRANSLATED_GLSL && decoded) return decoded;
  const map = new Map((JSON.parse(source) as GlslProgram[]).map((p) => [p.key, p]));
  if (source === TRANSLATED_GLSL) decoded = map;
  return map;
}

/** The translated program `key`; a one-line error naming the programs there are if the build made none of that name. */
export function translatedProgram(key: string, source?: string): GlslProgram {
  const programs = translatedPrograms(source);
  const p = programs.get(key);
  if (!p) throw new LanternError(`the WebGL2 backend has no translated program '${key}' (the build made: ${[...programs.keys()].join(', ')})`);
  return p;
}
