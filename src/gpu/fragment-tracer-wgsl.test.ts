import { NagaError, translate } from 'naga-wasm';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { SAMPLERS } from '../passes/variants.ts';
import { FRAGMENT_SAMPLERS, FRAGMENT_TRACER_ENTRY, FRAGMENT_VERTEX_ENTRY, declaredOverrides, fragmentTracerConstants, fragmentTracerWgsl, freezeOverrides, linkFragmentTracer } from './fragment-tracer-wgsl.ts';
import { PLAIN_SCENE } from './kernel.ts';
import type { SceneFeatures } from './pack/scene-pack.ts';
import { linkWgsl } from './wgsl/linker.ts';

/** Every switch on: the most code a scene can pull in (instances, spheres, masks, lights, the sky, every BSDF). */
const EVERYTHING: SceneFeatures = { alphaMasks: true, generalMaterials: true, punctualLights: true, environment: true, analyticPrimitives: true, instances: true, staticAccel: 'bvh2', shallowStack: false };

/** GLSL ES 3.00 has none of these (ES 3.10 and later) and WebGL2 has no storage buffers or atomics. */
const NOT_IN_ES300 = /\b(bitfieldReverse|bitfieldExtract|bitfieldInsert|findLSB|findMSB|bitCount|uaddCarry|usubBorrow|umulExtended|packUnorm4x8|unpackUnorm4x8|packSnorm4x8|unpackSnorm4x8|ldexp|frexp|textureGather|imageLoad|imageStore|atomic\w*|buffer|shared|memoryBarrier\w*|barrier)\s*\(|\bbuffer\s+\w+\s*\{|\bshared\s/;

describe('the fragment tracer WGSL', () => {
  it('links with the texture scene bindings and keeps no override, storage buffer or atomic', () => {
    const linked = linkFragmentTracer();
    expect(linked.modules).toContain('scene/bindings-textures');
    expect(linked.modules).toContain('lib/bits-es300');
    expect(linked.modules).not.toContain('scene/bindings');
    expect(linked.modules).not.toContain('lib/bits');
    expect(linked.modules).not.toContain('integrator/dispatch');
    expect(declaredOverrides(linked).length).toBeGreaterThan(10);
    const frozen = fragmentTracerWgsl(fragmentTracerConstants({ features: EVERYTHING, sampler: 'sobol', rowShift: 11 }));
    expect(declaredOverrides(frozen)).toEqual([]);
    expect(frozen.code).not.toMatch(/^\s*override\s/m);
    expect(frozen.code).not.toMatch(/var<storage|var<workgroup|atomic</);
    expect(frozen.code).toContain('const SCENE_HAS_INSTANCES: bool = true;');
    expect(frozen.code).toContain('const SAMPLER: u32 = 1u;');
    expect(frozen.code).toContain('const SCENE_TEXTURE_ROW_SHIFT: u32 = 11u;');
    expect(frozen.lineMap.length).toBe(frozen.code.split('\n').length);
  });

  it('names the samplers as passes/variants.ts does', () => {
    expect(Object.keys(FRAGMENT_SAMPLERS)).toEqual([...SAMPLERS]);
  });

  it('freezes overrides to consts, refusing unknown names and missing values', () => {
    const sources = new Map([['m', 'override A: u32 = 3u;\noverride B: bool = A > 2u; // why\noverride C: i32;\noverride D: f32 = 1.0;\nfn f() {}']]);
    const linked = linkWgsl('m', sources);
    const frozen = freezeOverrides(linked, { C: -4, D: 0.5 });
    expect(frozen.code).toContain('const A: u32 = 3u;\nconst B: bool = A > 2u; // why\nconst C: i32 = -4i;\nconst D: f32 = 0.5f;');
    expectLanternError(() => freezeOverrides(linked, { D: 1 }), /^override C of 'm' has no default and no value was given$/);
    expectLanternError(() => freezeOverrides(linked, { C: 1, E: 2 }), /^'m' declares no override E$/);
    expectLanternError(() => freezeOverrides(linked, { C: 1, A: -1 }), /^override A: -1 is not a u32$/);
  });

  for (const [what, features, sampler] of [['a plain scene, PCG', PLAIN_SCENE, 'random'], ['every feature, Sobol', EVERYTHING, 'sobol']] as const) {
    it(`translates to GLSL ES 3.00 for both stages with naga (${what})`, () => {
      const source = fragmentTracerWgsl(fragmentTracerConstants({ features, sampler, rowShift: 11 })).code;
      for (const [stage, entryPoint] of [['vertex', FRAGMENT_VERTEX_ENTRY], ['fragment', FRAGMENT_TRACER_ENTRY]] as const) {
        const t0 = performance.now();
        let glsl: string;
        try {
          glsl = translate({ from: 'wgsl', to: 'glsl', source, options: { version: '300 es', stage, entryPoint } });
        } catch (e) {
          throw new Error(e instanceof NagaError ? e.formatted : String(e));
        }
        const ms = performance.now() - t0;
        console.log(`${what}: ${stage} ${(source.length / 1024).toFixed(0)} KiB of WGSL -> ${(glsl.length / 1024).toFixed(0)} KiB of GLSL in ${ms.toFixed(0)} ms`);
        expect(glsl.startsWith('#version 300 es')).toBe(true);
        expect(glsl).toMatch(/void main\(\)/);
        expect(glsl.match(NOT_IN_ES300)?.[0]).toBeUndefined();
        if (stage === 'fragment') {
          expect(glsl).toMatch(/texelFetch\(/);
          expect(glsl).toMatch(/uniform highp usampler2D \w+;/);
          expect(glsl).toMatch(/layout\(location = 0\) out vec4 \w+;/);
        }
      }
    });
  }
});
