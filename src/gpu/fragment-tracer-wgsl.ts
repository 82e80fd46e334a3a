/**
 * The fragment tracer's WGSL (shaders/passes/path-trace-fragment, issue #30) as one text that both
 * back ends compile: WebGPU as it is, WebGL2 after naga translates it to GLSL ES 3.00. Linked with
 * scene/bindings-textures in place of scene/bindings, and every `override` it pulls in frozen to a
 * `const` (naga's GLSL writer takes no pipeline constants): those given take the given value, the
 * rest keep their defaults, now constant expressions. docs/fragment-tracer.md.
 */
import { LanternError } from '../errors.ts';
import { featureConstants, spectralConstants } from './kernel-variants.ts';
import { TRACING_FEATURES } from './kernel.ts';
import type { SceneFeatures } from './pack/scene-pack.ts';
import { linkWgsl, type LinkedShader } from './wgsl/linker.ts';

export const FRAGMENT_TRACER_MODULE = 'passes/path-trace-fragment';
export const FRAGMENT_VERTEX_ENTRY = 'vs_fullscreen';
export const FRAGMENT_TRACER_ENTRY = 'fs_path_trace';
/** What the fragment tracer links in place of what: the scene's records from textures, bit operations ES 3.00 has. */
export const FRAGMENT_TRACER_SUBSTITUTES: ReadonlyMap<string, string> = new Map([
  ['scene/bindings', 'scene/bindings-textures'],
  // GLSL ES 3.00 has no bitfieldReverse, findLSB or bitCount.
  ['lib/bits', 'lib/bits-es300'],
]);
/** lib/random's SAMPLER_RANDOM and SAMPLER_SOBOL, by the names of passes/variants.ts SAMPLERS. */
export const FRAGMENT_SAMPLERS = { random: 0, sobol: 1 } as const;
export type FragmentSampler = keyof typeof FRAGMENT_SAMPLERS;
/** The accumulation targets' format (rgb = Σ radiance, a = Σ luminance²). */
export const FRAGMENT_ACCUMULATION_FORMAT: GPUTextureFormat = 'rgba32float';

/** `override NAME[: TYPE] [= EXPR];` on one line, as every override in src/shaders is written. */
const OVERRIDE = /^(\s*)override\s+([A-Za-z_][A-Za-z0-9_]*)\s*(?::\s*([A-Za-z0-9_]+))?\s*(?:=\s*([^;]+))?;(.*)$/;

function literal(name: string, type: string | undefined, value: number): string {
  switch (type) {
    case 'bool':
      return value ? 'true' : 'false';
    case 'u32':
      if (!Number.isInteger(value) || value < 0 || value > 0xffffffff) throw new LanternError(`override ${name}: ${value} is not a u32`);
      return `${value}u`;
    case 'i32':
      if (!Number.isInteger(value) || value < -(2 ** 31) || value >= 2 ** 31) throw new LanternError(`override ${name}: ${value} is not an i32`);
      return `${value}i`;
    case 'f32':
      return Number.isInteger(value) ? `${value}.0f` : `${value}f`;
    default:
      throw new LanternError(`override ${name}: give its type to freeze it (${type ?? 'none'})`);
  }
}

/**
 * `linked` with every override a const: `constants` (by name) where given, else the override's
 * default. Throws for a constant the code does not declare (as WebGPU refuses one) and for an
 * override with neither. One line for one line, so the line map still holds.
 */
export function freezeOverrides(linked: LinkedShader, constants: Readonly<Record<string, number>>): LinkedShader {
  const used = new Set<string>();
  const lines = linked.code.split('\n').map((line) => {
    const m = OVERRIDE.exec(line);
    if (!m) return line;
    const [, indent, name, type, initial, rest] = m as unknown as [string, string, string, string | undefined, string | undefined, string];
    const given = constants[name];
    if (given !== undefined) used.add(name);
    const value = given !== undefined ? literal(name, type, given) : initial?.trim();
    if (value === undefined) throw new LanternError(`override ${name} of '${linked.entry}' has no default and no value was given`);
    return `${indent}const ${name}${type ? `: ${type}` : ''} = ${value};${rest}`;
  });
  const unknown = Object.keys(constants).filter((name) => !used.has(name));
  if (unknown.length > 0) throw new LanternError(`'${linked.entry}' declares no override ${unknown.join(', ')}`);
  return { ...linked, code: lines.join('\n') };
}

/** The names of the overrides `linked` declares. */
export function declaredOverrides(linked: LinkedShader): string[] {
  return linked.code.split('\n').flatMap((line) => {
    const m = OVERRIDE.exec(line);
    return m ? [m[2]!] : [];
  });
}

/** The fragment tracer linked with its substitutes, overrides still overrides. */
export function linkFragmentTracer(): LinkedShader {
  return linkWgsl(FRAGMENT_TRACER_MODULE, undefined, FRAGMENT_TRACER_SUBSTITUTES);
}

/** What the fragment tracer is compiled for. */
export interface FragmentTracerOptions {
  /** The scene's features (PackedScene.features): the compute kernels' scene variant. */
  readonly features: SceneFeatures;
  /** The random numbers: PCG or the Sobol sampler (lib/random SAMPLER). */
  readonly sampler: FragmentSampler;
  /** SCENE_TEXTURE_ROW_SHIFT: SceneTextures.rowShift of the textures it reads. */
  readonly rowShift: number;
}

/** The override values of a fragment tracer: the compute kernel's for the scene and sampler, RGB, and the textures' row width. */
export function fragmentTracerConstants(o: FragmentTracerOptions): Record<string, number> {
  return { ...featureConstants(TRACING_FEATURES, o.features), ...spectralConstants(false), SAMPLER: FRAGMENT_SAMPLERS[o.sampler], SCENE_TEXTURE_ROW_SHIFT: o.rowShift };
}

/**
 * The exact WGSL of the fragment tracer for these constants (fragmentTracerConstants, or any
 * values by override name): no override left, no storage buffer, no atomics. What WebGPU compiles
 * and naga translates.
 */
export function fragmentTracerWgsl(constants: Readonly<Record<string, number>>): LinkedShader {
  return freezeOverrides(linkFragmentTracer(), constants);
}
