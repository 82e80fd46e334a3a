import { describe, expect, it } from 'vitest';
import { liveEntryResources } from '../src/gpu/wgsl/reflect.ts';
import { parseGlslInterface, translatedProgram } from '../src/webgl2/glsl.ts';
import { translateSpec } from '../src/webgl2/translate.ts';
import { webGl2ProgramSpecs } from '../src/webgl2/programs.ts';
import { translateAll, translateProgram } from './glsl-translation.ts';

describe('WGSL -> GLSL ES 3.00 for the WebGL2 backend', () => {
  const specs = webGl2ProgramSpecs();

  it('translates every program the backend uses, the same text every time', () => {
    expect(specs.length).toBeGreaterThan(0);
    expect(new Set(specs.map((s) => s.key)).size).toBe(specs.length);
    for (const spec of specs) {
      const a = translateProgram(spec, translateSpec);
      const b = translateProgram(spec, translateSpec);
      expect(b).toEqual(a);
      for (const text of [a.vertex, a.fragment]) {
        expect(text.startsWith('#version 300 es\n')).toBe(true);
        // WebGL2 needs default precisions for floats and ints in the fragment stage.
        expect(text).toMatch(/precision highp float;/);
        expect(text).toMatch(/precision highp int;/);
      }
    }
  });

  it('declares a uniform block or a sampler for every WGSL binding each entry point uses, and nothing else', () => {
    for (const spec of specs) {
      const program = translateProgram(spec, translateSpec);
      const linked = { entry: spec.module, code: spec.wgsl, modules: [spec.module], lineMap: [] };
      for (const [stage, entry] of [['vertex', spec.vertexEntry], ['fragment', spec.fragmentEntry]] as const) {
        const used = liveEntryResources(linked, entry).filter((r) => !r.layout.sampler);
        const declared = [...program.blocks.filter((b) => b.stage === stage).map((b) => ({ group: b.group, binding: b.binding, kind: 'buffer' })), ...program.samplers.filter((s) => s.stage === stage).map((s) => ({ group: s.group, binding: s.binding, kind: 'texture' }))];
        const expected = used.map((r) => ({ group: r.group, binding: r.binding, kind: r.layout.buffer ? 'buffer' : 'texture' }));
        const order = (a: { group: number; binding: number }, b: { group: number; binding: number }) => a.group - b.group || a.binding - b.binding;
        expect(declared.sort(order), `${spec.key} ${stage}`).toEqual(expected.sort(order));
        for (const r of used.filter((u) => u.layout.buffer)) expect(r.layout.buffer!.type, `${spec.key}: ${r.name} is not a uniform (WebGL2 has no storage buffers)`).toBe('uniform');
      }
    }
  });

  it('reads the tone map pass: one std140 block of TonemapFragmentParams and the accumulation as a float sampler', () => {
    const tonemap = translateProgram(specs.find((s) => s.key === 'tonemap')!, translateSpec);
    expect(tonemap.blocks).toEqual([{ group: 0, binding: 0, stage: 'fragment', block: 'TonemapFragmentParams_block_0Fragment', struct: 'TonemapFragmentParams', instance: '_group_0_binding_0_fs' }]);
    expect(tonemap.samplers).toEqual([{ group: 0, binding: 1, stage: 'fragment', name: '_group_0_binding_1_fs', type: 'sampler2D' }]);
  });

  it('refuses a uniform declaration it cannot bind', () => {
    expect(() => parseGlslInterface('#version 300 es\nuniform vec4 stray;\n', '')).toThrow(/does not recognise: uniform vec4 stray;/);
  });

  it('makes the JSON the page build carries, which the host reads back by key', async () => {
    const json = await translateAll(process.cwd());
    expect(await translateAll(process.cwd())).toBe(json);
    for (const spec of specs) expect(translatedProgram(spec.key, json)).toEqual(translateProgram(spec, translateSpec));
    expect(() => translatedProgram('nothing', json)).toThrow(/no translated program 'nothing' \(the build made: tonemap, path-trace:shallowStack, path-trace:environment\+analyticPrimitives\+shallowStack/);
  });
});
