/**
 * Every GPU struct layout the host packs by reflection is checked against the GPU itself: the host
 * fills an array of structs with distinct values at reflected offsets, a generated kernel copies
 * every field out in declaration order, and the host compares. A vec3 alignment mistake in the
 * reflection (or a field the host writes at the wrong place) shows up as a mismatch.
 */
import { describe, expect, it } from 'vitest';
import { reflectModule } from '../../src/gpu/wgsl/reflect.ts';
import type { StructDefinition, TypeDefinition } from 'webgpu-utils';
import { testGpu } from './gpu-context.ts';
import { outputBuffer, runOnce, storageBuffer, testKernel } from './compute.ts';

interface Leaf {
  path: string;
  offset: number;
  components: number;
  kind: 'f32' | 'u32' | 'i32';
}

const SCALARS: Record<string, { components: number; kind: Leaf['kind'] }> = {
  f32: { components: 1, kind: 'f32' }, u32: { components: 1, kind: 'u32' }, i32: { components: 1, kind: 'i32' },
  vec2f: { components: 2, kind: 'f32' }, vec3f: { components: 3, kind: 'f32' }, vec4f: { components: 4, kind: 'f32' },
  vec2u: { components: 2, kind: 'u32' }, vec3u: { components: 3, kind: 'u32' }, vec4u: { components: 4, kind: 'u32' },
  'vec2<f32>': { components: 2, kind: 'f32' }, 'vec3<f32>': { components: 3, kind: 'f32' }, 'vec4<f32>': { components: 4, kind: 'f32' },
  'vec2<u32>': { components: 2, kind: 'u32' }, 'vec3<u32>': { components: 3, kind: 'u32' }, 'vec4<u32>': { components: 4, kind: 'u32' },
};

function leaves(def: StructDefinition, prefix = '', base = 0): Leaf[] {
  const out: Leaf[] = [];
  for (const [name, field] of Object.entries(def.fields)) {
    const type = field.type as TypeDefinition & { type?: string; fields?: unknown };
    if ('fields' in type && type.fields) {
      out.push(...leaves(type as StructDefinition, `${prefix}${name}.`, base + field.offset));
      continue;
    }
    const scalar = SCALARS[type.type ?? ''];
    if (!scalar) throw new Error(`unhandled field type ${type.type} in ${prefix}${name}`);
    out.push({ path: `${prefix}${name}`, offset: base + field.offset, ...scalar });
  }
  return out;
}

/** Structs to check: (module that declares them, struct name). */
const STRUCTS: [string, string][] = [
  ['scene/bindings', 'BvhNode'],
  ['scene/bindings', 'TriangleHot'],
  ['scene/bindings', 'TriangleShading'],
  ['scene/bindings', 'Material'],
  ['scene/bindings', 'LightSlot'],
  ['scene/bindings', 'SceneInfo'],
  ['scene/bindings', 'EnvironmentInfo'],
  ['scene/bindings', 'Ray'],
  ['scene/bindings', 'HitRecord'],
  ['view/bindings', 'View'],
  ['passes/path-trace', 'PathTraceParams'],
  ['passes/tonemap', 'TonemapParams'],
  ['passes/exposure', 'ExposureParams'],
  ['passes/exposure', 'ExposureState'],
  ['passes/primary-rays', 'PrimaryRaysParams'],
  ['passes/selection-outline', 'SelectionParams'],
  ['scene/bindings', 'TextureRef'],
  ['scene/bindings', 'PunctualLight'],
];

describe('GPU struct layouts match reflection', () => {
  it.each(STRUCTS)('%s %s', async (module, struct) => {
    const { device } = await testGpu();
    const def = reflectModule(module).defs.structs[struct]!;
    expect(def).toBeDefined();
    const fields = leaves(def);
    const words = fields.reduce((n, f) => n + f.components, 0);
    const count = 3;

    // Distinct bit patterns per element and component, written at the reflected offsets.
    const input = new ArrayBuffer(def.size * count);
    const view = new DataView(input);
    const expected: number[] = [];
    for (let e = 0; e < count; e++) {
      fields.forEach((f, fi) => {
        for (let c = 0; c < f.components; c++) {
          const at = e * def.size + f.offset + c * 4;
          if (f.kind === 'f32') {
            const v = Math.fround(e * 1000 + fi * 10 + c + 0.25);
            view.setFloat32(at, v, true);
            expected.push(new Uint32Array(new Float32Array([v]).buffer)[0]!);
          } else {
            const v = (e * 1000 + fi * 10 + c + 7) >>> 0;
            view.setUint32(at, v, true);
            expected.push(v);
          }
        }
      });
    }

    const copies = fields.flatMap((f) => {
      const comps = f.components === 1 ? [''] : ['.x', '.y', '.z', '.w'].slice(0, f.components);
      return comps.map((c) => `  layout_output[o] = bitcast<u32>(layout_input[e].${f.path}${c}); o += 1u;`);
    });
    const code = [
      `#import ${module}`,
      `@group(3) @binding(0) var<storage, read> layout_input: array<${struct}>;`,
      `@group(3) @binding(1) var<storage, read_write> layout_output: array<u32>;`,
      `@compute @workgroup_size(1) fn copy_fields(@builtin(global_invocation_id) id: vec3u) {`,
      `  let e = id.x;`,
      `  var o = e * ${words}u;`,
      ...copies,
      `}`,
    ].join('\n');
    const kernel = await testKernel(device, `test/layout-${struct}`, code, 'copy_fields');
    const out = outputBuffer(device, 'fields', words * count * 4);
    const inBuffer = storageBuffer(device, 'structs', input);
    const got = new Uint32Array(await runOnce(device, kernel, { 3: kernel.bindGroup(3, { layout_input: inBuffer, layout_output: out }) }, [count], out));
    expect([...got]).toEqual(expected);
    inBuffer.destroy();
    out.destroy();
  });
});
