/**
 * Every light of a scene in one alias table (shaders/scene/lights.wgsl): emissive triangles,
 * punctual lights, the environment map and the sun, each picked with probability proportional to
 * its power. Powers of lights at infinity are estimated as the flux they send through a disk of the
 * scene's bounding radius (irradiance × πR²), which puts them on the same scale as the emitters
 * inside. Pure CPU.
 */
import { makeStructuredView } from 'webgpu-utils';
import { buildAliasTable } from '../../math/alias-table.ts';
import { normalize, scale } from '../../math/vec3.ts';
import type { PunctualLight } from '../../scene/types.ts';
import { punctualPower } from '../../scene/punctual-power.ts';
import type { ShaderLayouts, StructLayout } from '../wgsl/reflect.ts';
import { StructArray } from './struct-array.ts';

export const LIGHT_KIND_SHIFT = 30;
export const LIGHT_KIND = { triangle: 0, punctual: 1, environment: 2, sun: 3 } as const;
export const PUNCTUAL_KINDS: readonly PunctualLight['kind'][] = ['point', 'spot', 'directional'];
/** The size of the WGSL uniform array (MAX_PUNCTUAL_LIGHTS in shaders/scene/types.wgsl). */
export const MAX_PUNCTUAL_LIGHTS = 64;

export const lightCode = (kind: keyof typeof LIGHT_KIND, index: number): number => ((LIGHT_KIND[kind] << LIGHT_KIND_SHIFT) | index) >>> 0;

export interface LightInputs {
  /** Leaf-order indices and powers of emissive triangles. */
  readonly triangles: readonly number[];
  readonly trianglePowers: readonly number[];
  /** The instance (shaders/scene/types.wgsl Instance) of each emissive triangle; all 0 (the static world) when absent. */
  readonly triangleInstances?: readonly number[];
  readonly punctual: readonly PunctualLight[];
  /** Estimated powers of the environment map and of the sun (0: absent). */
  readonly environmentPower: number;
  readonly sunPower: number;
  /** Radius of the scene's bounding sphere. */
  readonly sceneRadius: number;
}

export interface PackedLights {
  readonly lightSlots: ArrayBuffer;
  readonly punctualLights: ArrayBuffer;
  readonly slotCount: number;
  readonly totalPower: number;
  readonly environmentSelectPmf: number;
  readonly sunSelectPmf: number;
  readonly punctualCount: number;
  readonly warnings: readonly string[];
}

export function packLights(inputs: LightInputs, layouts: { lightSlot: StructLayout }, defs: ShaderLayouts): PackedLights {
  const warnings: string[] = [];
  let punctual = inputs.punctual.map((light) => ({ light, power: punctualPower(light, inputs.sceneRadius) })).filter((p) => p.power > 0);
  if (punctual.length > MAX_PUNCTUAL_LIGHTS) {
    warnings.push(`the scene has ${punctual.length} punctual lights; the ${MAX_PUNCTUAL_LIGHTS} brightest are kept`);
    punctual = punctual.sort((a, b) => b.power - a.power).slice(0, MAX_PUNCTUAL_LIGHTS);
  }
  const codes: number[] = [];
  const powers: number[] = [];
  const instances: number[] = [];
  inputs.triangles.forEach((t, i) => {
    codes.push(lightCode('triangle', t));
    powers.push(inputs.trianglePowers[i]!);
    instances.push(inputs.triangleInstances?.[i] ?? 0);
  });
  punctual.forEach((p, i) => {
    codes.push(lightCode('punctual', i));
    powers.push(p.power);
  });
  if (inputs.environmentPower > 0) {
    codes.push(lightCode('environment', 0));
    powers.push(inputs.environmentPower);
  }
  if (inputs.sunPower > 0) {
    codes.push(lightCode('sun', 0));
    powers.push(inputs.sunPower);
  }

  const slots = new StructArray(layouts.lightSlot, codes.length);
  let total = 0;
  if (codes.length > 0) {
    const table = buildAliasTable(powers);
    total = table.total;
    const light = slots.u32Field('light'), alias = slots.u32Field('alias_light'), keep = slots.f32Field('keep');
    const instance = slots.u32Field('instance'), aliasInstance = slots.u32Field('alias_instance');
    for (let i = 0; i < codes.length; i++) {
      light(i, codes[i]!);
      alias(i, codes[table.alias[i]!]!);
      keep(i, table.keep[i]!);
      instance(i, instances[i] ?? 0);
      aliasInstance(i, instances[table.alias[i]!] ?? 0);
    }
  }

  const view = makeStructuredView(defs.uniforms.punctual_lights!);
  view.set({
    count: punctual.length,
    lights: punctual.map(({ light, power }) => lightRecord(light, total > 0 ? power / total : 0)),
  });

  return {
    lightSlots: slots.bytes,
    punctualLights: view.arrayBuffer,
    slotCount: codes.length,
    totalPower: total,
    environmentSelectPmf: total > 0 ? inputs.environmentPower / total : 0,
    sunSelectPmf: total > 0 ? inputs.sunPower / total : 0,
    punctualCount: punctual.length,
    warnings,
  };
}

/** The WGSL PunctualLight record of a light (shaders/scene/types.wgsl). */
function lightRecord(light: PunctualLight, selectPmf: number) {
  const kind = PUNCTUAL_KINDS.indexOf(light.kind);
  switch (light.kind) {
    case 'directional':
      return { kind, select_pmf: selectPmf, position: scale(normalize(light.direction), -1), intensity: scale(light.color, light.irradiance), range: 3e38 };
    case 'point':
      return { kind, select_pmf: selectPmf, position: light.position, intensity: scale(light.color, light.intensity), range: finiteRange(light.range) };
    case 'spot': {
      const cosOuter = Math.cos(light.outerConeAngle), cosInner = Math.cos(light.innerConeAngle);
      return {
        kind,
        select_pmf: selectPmf,
        position: light.position,
        intensity: scale(light.color, light.intensity),
        range: finiteRange(light.range),
        direction: normalize(light.direction),
        cos_outer: cosOuter,
        cone_scale: 1 / Math.max(cosInner - cosOuter, 1e-4),
      };
    }
  }
}

const finiteRange = (r: number): number => (Number.isFinite(r) && r > 0 ? r : 3e38);

