import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { uvSphere } from '../../bvh/test-scenes.ts';
import { IDENTITY } from '../../math/mat4.ts';
import { builtinScene } from '../../loaders/builtin/index.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import type { Scene } from '../../scene/types.ts';
import type { StructLayout } from '../wgsl/reflect.ts';
import { f32Literal, primitivesModule } from './primitives-module.ts';
import { sceneLayouts } from './scene-pack.ts';
import { StructArray } from './struct-array.ts';

/**
 * Reads the records of SCENE_PRIMITIVES back out of a generated module into the bytes of `layout`:
 * the literals in order, each stored as its field's type says (an independent reader of the text).
 */
function parsePrimitives(code: string, layout: StructLayout): { count: number; bytes: ArrayBuffer } {
  const header = /const SCENE_PRIMITIVES = array<(\w+), (\d+)>\(\n([\s\S]*?)\n\);/.exec(code);
  if (!header) throw new Error('no SCENE_PRIMITIVES array');
  expect(header[1]).toBe(layout.name);
  const count = Number(header[2]);
  const records = header[3]!.split('\n');
  expect(records).toHaveLength(count);
  const out = new StructArray(layout, count);
  const fields = [...layout.fields.values()].sort((a, b) => a.offset - b.offset);
  records.forEach((line, i) => {
    // Drop the constructor names (vec3f, TriangleHot: they hold digits), keep the literals.
    const literals = line.replace(/[A-Za-z_]\w*\(/g, '(').match(/-?[0-9][0-9.e+-]*[ui]?/g) ?? [];
    let k = 0;
    for (const f of fields) {
      const n = f.size / 4;
      for (let c = 0; c < n; c++) {
        const lit = literals[k++]!;
        const word = out.base(i) + f.offset / 4 + c;
        if (f.type.endsWith('u') || f.type === 'u32') {
          expect(lit).toMatch(/^\d+u$/);
          out.u32[word] = Number(lit.slice(0, -1));
        } else {
          expect(lit).toMatch(/^-?\d+(\.\d+)?(e[+-]?\d+)?$/);
          out.f32[word] = Number(lit);
        }
      }
    }
    expect(k).toBe(literals.length);
  });
  return { count, bytes: out.bytes };
}

const words = (b: ArrayBuffer, n: number) => Array.from(new Uint32Array(b, 0, n));

describe('the generated primitives module', () => {
  it.each([
    ['cornell', () => builtinScene('cornell')],
    ['furnace', () => builtinScene('furnace')],
    [
      'a sphere of 48 triangles',
      (): Scene => {
        const positions = uvSphere(4, 6, 1.7);
        const n = positions.length / 9;
        return {
          name: 'sphere',
          meshes: [{ name: 's', positions, indices: Uint32Array.from({ length: n * 3 }, (_, i) => i), materialIds: new Uint32Array(n) }],
          instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }],
          materials: [{ kind: 'diffuse', name: 'grey', albedo: [0.5, 0.5, 0.5], emission: [0, 0, 0] }],
          camera: { position: [0, 0, -5], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 45 },
        };
      },
    ],
  ])('round-trips the packed triangles_hot of %s bit for bit', (_, make) => {
    const prepared = prepareScene(make());
    const layout = sceneLayouts().hot;
    const n = prepared.packed.counts.triangles;
    const code = primitivesModule(layout, prepared.packed.triangles_hot, n, prepared.scene.name);
    const back = parsePrimitives(code, layout);
    expect(back.count).toBe(n);
    expect(words(back.bytes, n * layout.strideWords)).toEqual(words(prepared.packed.triangles_hot, n * layout.strideWords));
    expect(code).toContain(`const SCENE_PRIMITIVE_COUNT: u32 = ${n}u;`);
    // One closest-hit call and one any-hit test per primitive, in leaf order.
    expect(code.match(/closest_candidate\(ray, SCENE_PRIMITIVES\[\d+\], \d+u, hit\);/g)).toHaveLength(n);
    expect(code.match(/any_candidate\(ray, SCENE_PRIMITIVES\[\d+\], \d+u\)/g)).toHaveLength(n);
    expect(code).toContain(`closest_candidate(ray, SCENE_PRIMITIVES[${n - 1}], ${n - 1}u, hit);`);
  });

  it('writes awkward f32 values exactly: −0, subnormals, the largest f32, values with no short decimal', () => {
    const layout = sceneLayouts().hot;
    const values = [-0, 1e-45, 3.4028234663852886e38, -3.4028234663852886e38, 0.1, 1 / 3, 1e7, 123456789, -2.5e-39, 65504];
    const records = new StructArray(layout, 2);
    const v0 = records.vec3('v0'), e1 = records.vec3('e1'), e2 = records.vec3('e2'), flags = records.u32Field('flags');
    const at = (k: number) => values[k % values.length]!;
    for (let i = 0; i < 2; i++) {
      v0(i, at(9 * i), at(9 * i + 1), at(9 * i + 2));
      e1(i, at(9 * i + 3), at(9 * i + 4), at(9 * i + 5));
      e2(i, at(9 * i + 6), at(9 * i + 7), at(9 * i + 8));
      flags(i, i === 0 ? 0xffffffff : 1);
    }
    const back = parsePrimitives(primitivesModule(layout, records.bytes, 2, 'awkward'), layout);
    expect(words(back.bytes, 2 * layout.strideWords)).toEqual(words(records.bytes, 2 * layout.strideWords));
  });

  it('f32Literal is a WGSL float literal', () => {
    expect(f32Literal(1)).toBe('1.0');
    expect(f32Literal(-0)).toBe('-0.0');
    expect(f32Literal(Math.fround(0.1))).toBe('0.10000000149011612');
    expect(f32Literal(1e21)).toBe('1e+21');
  });

  it('refuses non-finite values and empty scenes', () => {
    const layout = sceneLayouts().hot;
    const records = new StructArray(layout, 1);
    records.vec3('v0')(0, NaN, 0, 0);
    expectLanternError(() => primitivesModule(layout, records.bytes, 1, 'nan'), /non-finite/);
    expectLanternError(() => primitivesModule(layout, records.bytes, 0, 'empty'), /without primitives/);
  });
});
