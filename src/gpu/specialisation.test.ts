import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { builtinScene } from '../loaders/builtin/index.ts';
import { prepareScene } from '../renderer/prepare.ts';
import { PRIMITIVES_MODULE } from './pack/primitives-module.ts';
import { declaredOverrides, materialKindsPresent, specialisedShader, specialiseScene, UNROLL_PRIMITIVE_LIMIT, unrollCost } from './specialisation.ts';

const settings = { maxBounces: 5, lightSampling: 1 };

describe('SceneSpecialisation', () => {
  it('knows the material kinds present, from the packed materials', () => {
    expect(materialKindsPresent(prepareScene(builtinScene('cornell')).packed)).toEqual({ metallicRoughness: false, dielectric: false });
    expect(materialKindsPresent(prepareScene(builtinScene('materials')).packed)).toEqual({ metallicRoughness: true, dielectric: true });
  });

  it('sets a constant for every feature, material kind and inlined setting', () => {
    const cornell = specialiseScene(prepareScene(builtinScene('cornell')).packed, 'cornell', settings);
    expect(cornell.constants).toEqual({
      SCENE_HAS_ALPHA_MASKS: 0,
      // No general path, no metallic-roughness or dielectric kind (MATERIALS_* of scene/bsdf.wgsl).
      SCENE_MATERIALS: 0,
      SCENE_HAS_PUNCTUAL_LIGHTS: 0,
      SCENE_HAS_ENVIRONMENT: 0,
      SCENE_HAS_ANALYTIC_PRIMITIVES: 0,
      SCENE_HAS_INSTANCES: 0,
      // ACCEL_BVH2 (scene/accel.wgsl).
      STATIC_ACCEL: 0,
      BVH_SHALLOW_STACK: 1,
      INLINED_MAX_BOUNCES: 5,
      INLINED_LIGHT_SAMPLING: 1,
      INLINED_LIGHT_COUNT: 2,
    });
    const materials = specialiseScene(prepareScene(builtinScene('materials')).packed, 'materials', { maxBounces: 0, lightSampling: 0 });
    expect(materials.constants).toMatchObject({ SCENE_MATERIALS: 1 | 2 | 4, INLINED_MAX_BOUNCES: 0 });
    // Without the kinds part the generic kernels' assumption stands: every kind may occur.
    const unnarrowed = specialiseScene(prepareScene(builtinScene('cornell')).packed, 'cornell', settings, { parts: ['bounces'] });
    expect(unnarrowed.constants.SCENE_MATERIALS).toBe(2 | 4);
  });

  it('unrolls scenes of at most the limit’s primitives, and only those', () => {
    const packed = prepareScene(builtinScene('cornell')).packed;
    const n = packed.counts.triangles;
    expect(n).toBeLessThanOrEqual(UNROLL_PRIMITIVE_LIMIT);
    expect(specialiseScene(packed, 'c', settings).unrolled).toContain(`const SCENE_PRIMITIVE_COUNT: u32 = ${n}u;`);
    expect(specialiseScene(packed, 'c', settings, { unrollLimit: n }).unrolled).toBeDefined();
    expect(specialiseScene(packed, 'c', settings, { unrollLimit: n - 1 }).unrolled).toBeUndefined();
    expect(specialiseScene(packed, 'c', settings, { unrollLimit: 0 }).unrolled).toBeUndefined();
    expect(specialiseScene(prepareScene(builtinScene('bvh-teaching')).packed, 'b', settings).unrolled).toBeUndefined();
    // Capsules weigh more: caffeine's 59 primitives (29 capsules) stay in the BVH; the 5 spheres of 'spheres' unroll.
    const caffeine = prepareScene(builtinScene('caffeine')).packed;
    expect(caffeine.counts.triangles).toBeLessThanOrEqual(UNROLL_PRIMITIVE_LIMIT);
    expect(unrollCost(caffeine.counts)).toBeGreaterThan(UNROLL_PRIMITIVE_LIMIT);
    expect(specialiseScene(caffeine, 'caffeine', settings).unrolled).toBeUndefined();
    expect(specialiseScene(prepareScene(builtinScene('spheres')).packed, 's', settings).unrolled).toBeDefined();
    expectLanternError(() => specialiseScene(packed, 'c', settings, { unrollLimit: -1 }), /unroll limit/);
    expectLanternError(() => specialiseScene(packed, 'c', { maxBounces: 1.5, lightSampling: 1 }), /max bounces/);
  });

  it('links the unrolled traversal in place of scene/bvh, and the generic traversal otherwise', () => {
    const packed = prepareScene(builtinScene('cornell')).packed;
    const unrolled = specialisedShader('passes/path-trace', specialiseScene(packed, 'c', settings));
    expect(unrolled.linked.modules).toContain('scene/traversal-unrolled');
    expect(unrolled.linked.modules).toContain(PRIMITIVES_MODULE);
    expect(unrolled.linked.modules).not.toContain('scene/bvh');
    expect(unrolled.linked.code.match(/^fn trace_closest\(/gm)).toHaveLength(1);
    const generic = specialisedShader('passes/path-trace', specialiseScene(packed, 'c', settings, { unrollLimit: 0 }));
    expect(generic.linked.modules).toContain('scene/bvh');
    expect(generic.linked.modules).not.toContain('scene/traversal-unrolled');
    // Every constant the specialisation sets is declared by the path tracer it specialises.
    const declared = declaredOverrides(unrolled.linked.code);
    for (const name of Object.keys(specialiseScene(packed, 'c', settings).constants)) expect(declared).toContain(name);
  });

  it('finds override declarations', () => {
    expect([...declaredOverrides('override A: bool = true;\n  override B_2: i32 = -1;\n// override C\nconst D = 1;')]).toEqual(['A', 'B_2']);
  });
});
