/**
 * Every program the WebGL2 backend draws with, as WGSL entry points: the single list that
 * scripts/glsl-translation.ts translates at build time (and its test checks). Each is a linked WGSL
 * module of src/shaders with a vertex and a fragment entry; the key is what the host asks
 * translatedProgram for. Pure: links WGSL text, no GL.
 */
import { FRAGMENT_TRACER_ENTRY, FRAGMENT_TRACER_MODULE, FRAGMENT_VERTEX_ENTRY, fragmentTracerConstants, fragmentTracerWgsl } from '../gpu/fragment-tracer-wgsl.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { DEFAULT_ROW_SHIFT } from '../gpu/pack/scene-textures.ts';
import { linkWgsl } from '../gpu/wgsl/linker.ts';

export interface WebGl2ProgramSpec {
  readonly key: string;
  /** The WGSL module of src/shaders the entries are in (for reflection: its uniform structs). */
  readonly module: string;
  /** The exact WGSL translated (the linked module, overrides frozen where the program has any). */
  readonly wgsl: string;
  readonly vertexEntry: string;
  readonly fragmentEntry: string;
}

function fromModule(key: string, module: string, vertexEntry: string, fragmentEntry: string): WebGl2ProgramSpec {
  return { key, module, wgsl: linkWgsl(module).code, vertexEntry, fragmentEntry };
}

/** The record textures' rows: 2^11 = 2048 texels, WebGL2's guaranteed MAX_TEXTURE_SIZE. */
export const WEBGL2_ROW_SHIFT = DEFAULT_ROW_SHIFT;

const FEATURE_FLAGS = ['alphaMasks', 'generalMaterials', 'punctualLights', 'environment', 'analyticPrimitives', 'instances', 'shallowStack'] as const;

/** The tracer variant's key for a scene's features: the flags set, in a fixed order ('path-trace:shallowStack'). */
export function webGl2TracerKey(features: SceneFeatures): string {
  return `path-trace:${FEATURE_FLAGS.filter((f) => features[f]).join('+') || 'none'}`;
}

/**
 * The fragment tracer for a scene's features (the compute kernels' scene variant), Sobol sampling,
 * 2048-texel rows. Per scene, not generic: SwiftShader (and ANGLE drivers) compile a tracer with
 * every feature on for minutes at its first draw, one with the Cornell box's in seconds.
 */
export function webGl2TracerSpec(features: SceneFeatures): WebGl2ProgramSpec {
  return {
    key: webGl2TracerKey(features),
    module: FRAGMENT_TRACER_MODULE,
    wgsl: fragmentTracerWgsl(fragmentTracerConstants({ features, sampler: 'sobol', rowShift: WEBGL2_ROW_SHIFT })).code,
    vertexEntry: FRAGMENT_VERTEX_ENTRY,
    fragmentEntry: FRAGMENT_TRACER_ENTRY,
  };
}

/**
 * The tracer variants the build translates, so that their scenes load no translator: the Cornell
 * box's (the page's first scene) and the white furnace's. Other scenes translate their variant in
 * the page (webgl2-tracer.ts), loading naga's WebAssembly then.
 */
export const PREBUILT_TRACER_FEATURES: readonly SceneFeatures[] = [
  { alphaMasks: false, generalMaterials: false, punctualLights: false, environment: false, analyticPrimitives: false, instances: false, staticAccel: 'bvh2', shallowStack: true },
  { alphaMasks: false, generalMaterials: false, punctualLights: false, environment: true, analyticPrimitives: true, instances: false, staticAccel: 'bvh2', shallowStack: true },
];

/** The programs, in a fixed order. */
export function webGl2ProgramSpecs(): WebGl2ProgramSpec[] {
  return [
    // The accumulated sums -> the tone-mapped 8-bit image (the image's size).
    fromModule('tonemap', 'passes/tonemap-fragment', 'vs_tonemap', 'fs_tonemap'),
    ...PREBUILT_TRACER_FEATURES.map(webGl2TracerSpec),
  ];
}
