/**
 * A translated program (glsl.ts GlslProgram) compiled and linked on a WebGL2 context, asynchronously:
 * with KHR_parallel_shader_compile the link is polled (COMPLETION_STATUS_KHR) once a frame, so the page
 * keeps drawing its wait while ANGLE compiles (seconds for the path tracer); the time is measured.
 * Then the program is reflected: every uniform block and sampler the translation declared is found by
 * name, each sampler gets a texture unit, and each block's member offsets (std140, as the driver
 * reports them) are checked against the WGSL struct's layout, so the bytes the WebGPU path writes for
 * a uniform are the bytes this block reads. A mismatch, a compile error or a missing name is one
 * LanternError naming the program.
 */
import { LanternError } from '../errors.ts';
import type { StructLayout } from '../gpu/wgsl/reflect.ts';
import type { WebGl2Context } from './context.ts';
import type { GlslProgram } from './glsl.ts';

/** A uniform block of a linked program: its binding point (one per block) and its std140 size. */
export interface LinkedBlock {
  readonly group: number;
  readonly binding: number;
  readonly bindingPoint: number;
  readonly dataSize: number;
  readonly struct: string;
}

/** A sampler of a linked program: the texture unit it reads. */
export interface LinkedSampler {
  readonly group: number;
  readonly binding: number;
  readonly unit: number;
  readonly type: string;
}

export interface LinkedProgram {
  readonly key: string;
  readonly program: WebGLProgram;
  readonly blocks: readonly LinkedBlock[];
  readonly samplers: readonly LinkedSampler[];
  /** Milliseconds from the compile's start to a linked program (the polls' granularity included). */
  readonly compileMs: number;
}

/** How the program waits between polls: a frame on the page (requestAnimationFrame is the caller's to give). */
export type Wait = () => Promise<void>;

const timeout = (): Promise<void> => new Promise((resolve) => setTimeout(resolve, 16));

/**
 * Compiles and links `source`; resolves once linked (polling where the browser compiles in parallel).
 * `layouts` gives the WGSL layout of each uniform block's struct, checked against the driver's std140.
 */
export async function compileProgram(ctx: WebGl2Context, source: GlslProgram, layouts: (struct: string) => StructLayout, wait: Wait = timeout): Promise<LinkedProgram> {
  const { gl } = ctx;
  const started = performance.now();
  const shader = (type: number, text: string) => {
    const s = gl.createShader(type);
    if (!s) throw new LanternError(`WebGL2: could not create a shader for '${source.key}' (the context is lost?)`);
    gl.shaderSource(s, text);
    gl.compileShader(s);
    return s;
  };
  const vs = shader(gl.VERTEX_SHADER, source.vertex);
  const fs = shader(gl.FRAGMENT_SHADER, source.fragment);
  const program = gl.createProgram();
  gl.attachShader(program, vs);
  gl.attachShader(program, fs);
  gl.linkProgram(program);
  if (ctx.parallelCompile) {
    const status = ctx.parallelCompile.COMPLETION_STATUS_KHR;
    while (!(gl.getProgramParameter(program, status) as boolean)) {
      if (gl.isContextLost()) throw new LanternError(`WebGL2: the context was lost while compiling '${source.key}'`);
      await wait();
    }
  }
  if (!(gl.getProgramParameter(program, gl.LINK_STATUS) as boolean)) {
    const log = [gl.getShaderInfoLog(vs), gl.getShaderInfoLog(fs), gl.getProgramInfoLog(program)].filter((l) => l && l.trim() !== '').join(' / ');
    throw new LanternError(`WebGL2: the program '${source.key}' did not compile: ${firstLines(log)}`);
  }
  const compileMs = performance.now() - started;
  gl.deleteShader(vs);
  gl.deleteShader(fs);

  // A block or sampler the translation declared but the compiler found unused (a feature frozen off)
  // is inactive: nothing is bound for it.
  const blocks: LinkedBlock[] = [];
  for (const b of source.blocks) {
    const index = gl.getUniformBlockIndex(program, b.block);
    if (index === gl.INVALID_INDEX) continue;
    const bindingPoint = blocks.length;
    gl.uniformBlockBinding(program, index, bindingPoint);
    const dataSize = gl.getActiveUniformBlockParameter(program, index, gl.UNIFORM_BLOCK_DATA_SIZE) as number;
    checkBlockLayout(gl, program, index, source.key, b.block, b.instance, layouts(b.struct));
    blocks.push({ group: b.group, binding: b.binding, bindingPoint, dataSize, struct: b.struct });
  }
  gl.useProgram(program);
  const samplers: LinkedSampler[] = [];
  for (const s of source.samplers) {
    const location = gl.getUniformLocation(program, s.name);
    if (!location) continue;
    const unit = samplers.length;
    gl.uniform1i(location, unit);
    samplers.push({ group: s.group, binding: s.binding, unit, type: s.type });
  }
  if (samplers.length > ctx.limits.maxTextureImageUnits) {
    throw new LanternError(`WebGL2: the program '${source.key}' samples ${samplers.length} textures, this GPU allows ${ctx.limits.maxTextureImageUnits}`);
  }
  return { key: source.key, program, blocks, samplers, compileMs };
}

/**
 * Every member the driver reports in the block (std140 offsets) against the WGSL struct's fields:
 * a scalar or vector field at exactly its WGSL offset; a member inside a field (an array element, a
 * nested struct's field) within that field's bytes.
 */
export function checkBlockLayout(gl: WebGL2RenderingContext, program: WebGLProgram, blockIndex: number, key: string, block: string, instance: string, layout: StructLayout): void {
  const indices = gl.getActiveUniformBlockParameter(program, blockIndex, gl.UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES) as Uint32Array;
  const offsets = gl.getActiveUniforms(program, [...indices], gl.UNIFORM_OFFSET) as number[];
  const members = [...indices].map((index, i) => ({ name: gl.getActiveUniform(program, index)?.name ?? '', offset: offsets[i]! }));
  const problems = blockLayoutProblems(members, block, instance, layout);
  if (problems.length > 0) throw new LanternError(`WebGL2: the program '${key}' lays out ${layout.name} unlike WGSL: ${problems.join('; ')}`);
}

/** What differs between the driver's members of a block (`Block.instance.field...`, std140 offsets) and the WGSL layout; empty when they agree. */
export function blockLayoutProblems(members: readonly { name: string; offset: number }[], block: string, instance: string, layout: StructLayout): string[] {
  const problems: string[] = [];
  for (const { name, offset } of members) {
    const path = name.replace(`${block}.`, '').replace(`${instance}.`, '');
    const glslName = path.split(/[.[]/)[0]!;
    // naga's namer appends '_' to a name GLSL reserves (sampler) or one ending in a digit (p0).
    const fieldName = layout.fields.has(glslName) || !glslName.endsWith('_') ? glslName : glslName.slice(0, -1);
    const field = layout.fields.get(fieldName);
    if (!field) {
      problems.push(`${path} is no field of the WGSL struct`);
    } else if (path === glslName && offset !== field.offset) {
      problems.push(`${path} at byte ${offset}, WGSL has ${field.offset}`);
    } else if (path !== glslName && (offset < field.offset || offset >= field.offset + field.size)) {
      problems.push(`${path} at byte ${offset}, outside WGSL's ${fieldName} (${field.offset}..${field.offset + field.size})`);
    }
  }
  if (members.length === 0 && layout.fields.size > 0) problems.push('the driver reports no members');
  return problems;
}

function firstLines(log: string): string {
  const lines = log.split('\n').map((l) => l.trim()).filter((l) => l !== '');
  return lines.slice(0, 3).join(' | ');
}
