import { describe, expect, it } from 'vitest';
import { fromTrs } from '../../math/mat4.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import { metallicRoughness, type Mesh, type Scene } from '../../scene/types.ts';
import { SHADER_MODULES } from '../../shaders/index.ts';
import { TRIANGLE_ATTRIBUTE_TEXELS, TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW } from './scene-pack.ts';

/** One triangle in the xy plane with tangent +x (w = 1) and a second uv set. */
const mesh: Mesh = {
  name: 'tri',
  positions: new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]),
  indices: new Uint32Array([0, 1, 2]),
  uvs: new Float32Array([0, 0, 1, 0, 0, 1]),
  uvs1: new Float32Array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]),
  tangents: new Float32Array([1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1]),
  materialIds: new Uint32Array([0]),
};
const texture = { name: 'flat normal', width: 1, height: 1, rgba: new Uint8Array([128, 128, 255, 255]), encoding: 'linear' as const };

function scene(normalMapped: boolean, turn: [number, number, number, number], scale: [number, number, number]): Scene {
  return {
    name: 'attributes',
    meshes: [mesh],
    instances: [{ id: 0, mesh: 0, worldFromObject: fromTrs([0, 0, 0], turn, scale) }],
    materials: [metallicRoughness('m', normalMapped ? { normalTexture: { texture: 0 } } : {})],
    textures: [texture],
    camera: { position: [0, 0, 5], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 40 },
  };
}

describe('triangle attributes (tangents and the second uv set)', () => {
  it('carry world-space tangents, their handedness and the second uvs of each vertex', () => {
    // A quarter turn about z takes the tangent +x to +y.
    const s = Math.SQRT1_2;
    const { packed } = prepareScene(scene(true, [0, 0, s, s], [1, 1, 1]));
    const a = packed.triangleAttributes;
    expect(a.width).toBe(TRIANGLE_ATTRIBUTE_TEXELS * TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW);
    for (let c = 0; c < 3; c++) {
      const t = Array.from(a.data.subarray(c * 4, c * 4 + 4));
      expect(t[0]).toBeCloseTo(0, 6);
      expect(t[1]).toBeCloseTo(1, 6);
      expect(t[3]).toBe(1);
    }
    expect(Array.from(a.data.subarray(12, 18)).map((v) => +v.toFixed(5))).toEqual([0.1, 0.2, 0.3, 0.4, 0.5, 0.6]);
  });

  it('flip the handedness under a mirroring instance, whose corners v1 and v2 swap', () => {
    const { packed } = prepareScene(scene(true, [0, 0, 0, 1], [-1, 1, 1]));
    const a = packed.triangleAttributes.data;
    expect(a[0]).toBeCloseTo(-1, 6); // +x mirrored
    expect(a[3]).toBe(-1);
    // The second uvs follow the swapped corners: v0, then v2, then v1.
    expect(Array.from(a.subarray(12, 18)).map((v) => +v.toFixed(5))).toEqual([0.1, 0.2, 0.5, 0.6, 0.3, 0.4]);
  });

  it('are left out (1×1) where no material needs them', () => {
    expect(prepareScene(scene(false, [0, 0, 0, 1], [1, 1, 1])).packed.triangleAttributes.width).toBe(1);
  });

  it('have the layout the WGSL reads', () => {
    const types = SHADER_MODULES.get('scene/types')!;
    expect(types).toContain(`const TRIANGLE_ATTRIBUTE_TEXELS: u32 = ${TRIANGLE_ATTRIBUTE_TEXELS}u;`);
    expect(types).toContain(`const TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW: u32 = ${TRIANGLE_ATTRIBUTE_TRIANGLES_PER_ROW}u;`);
  });
});
