/**
 * The reflection a bundle carries (precompute.ts, at build time) against live reflection of the
 * same code, module by module: every struct and uniform layout, every entry point and the bindings
 * of each. The data goes through JSON and back as in a bundle (reflect.ts decodePrecomputed), so a
 * change to the reflection code, the data's format or a shader that the data no longer matches
 * fails here rather than in a pipeline layout.
 */
import { makeStructuredView } from 'webgpu-utils';
import { beforeAll, describe, expect, it } from 'vitest';
import { SHADER_MODULES } from '../../shaders/index.ts';
import { linkWgsl } from './linker.ts';
import { precomputeReflection } from './precompute.ts';
import { codeHash, decodePrecomputed, entryPointBindings, liveEntryPointNames, liveEntryResources, precomputedShader, reflectLinked, type PrecomputedReflection } from './reflect.ts';

/** GPUShaderStage.COMPUTE | VERTEX | FRAGMENT: the visibility is the caller's, passed through either way. */
const ALL_STAGES = 7;

/** Modules that link only with a module generated at run time (gpu/specialisation.ts). */
const NOT_PRECOMPUTED = ['scene/traversal-unrolled'];

describe('precomputed reflection', () => {
  let skipped: readonly string[];
  let decoded: PrecomputedReflection;
  beforeAll(() => {
    const made = precomputeReflection();
    skipped = made.skipped;
    decoded = decodePrecomputed(JSON.stringify(made.data));
  }, 120_000);

  it('leaves out only the modules that link with generated code', () => {
    expect(skipped.map((s) => s.split(':')[0])).toEqual(NOT_PRECOMPUTED);
    expect(Object.keys(decoded.modules).sort()).toEqual([...SHADER_MODULES.keys()].filter((m) => !NOT_PRECOMPUTED.includes(m)).sort());
  });

  it('equals live reflection for every module: layouts, entry points and their bindings', { timeout: 180_000 }, () => {
    let entryPoints = 0;
    for (const module of Object.keys(decoded.modules)) {
      // Two links of the same code: precomputedShader files its entry points under the one it is given.
      const pre = precomputedShader(linkWgsl(module), decoded);
      const live = reflectLinked(linkWgsl(module));
      expect(pre?.source, module).toBe('precomputed');
      expect(pre!.defs.structs, module).toEqual(live.defs.structs);
      expect(pre!.defs.uniforms, module).toEqual(live.defs.uniforms);
      const names = liveEntryPointNames(live.linked);
      expect(Object.keys(decoded.modules[module]!.entryPoints).sort(), module).toEqual([...names].sort());
      for (const entry of names) {
        expect(entryPointBindings(pre!, [entry], ALL_STAGES), `${module}:${entry}`).toEqual(entryPointBindings(live, [entry], ALL_STAGES));
      }
      // Vertex + fragment pairs, as the raster passes ask: resources shared by both are bound once.
      if (names.length > 1) expect(entryPointBindings(pre!, names, ALL_STAGES), module).toEqual(entryPointBindings(live, names, ALL_STAGES));
      entryPoints += names.length;
    }
    expect(entryPoints).toBeGreaterThan(40);
  });

  it('is shared between modules and frozen, and webgpu-utils builds views over it', () => {
    const bindings = precomputedShader(linkWgsl('scene/bindings'), decoded)!;
    const path = precomputedShader(linkWgsl('passes/path-trace'), decoded)!;
    expect(path.defs.structs['SceneInfo']).toBe(bindings.defs.structs['SceneInfo']);
    expect(Object.isFrozen(path.defs.structs['SceneInfo']!.fields)).toBe(true);
    const view = makeStructuredView(path.defs.uniforms['params']!);
    expect(view.arrayBuffer.byteLength).toBe(path.defs.uniforms['params']!.size);
  });

  it('is not used for other code: the hash differs, and the code is reflected live', () => {
    const linked = linkWgsl('passes/tonemap');
    const edited = { ...linked, code: `${linked.code}\n// edited` };
    expect(precomputedShader(edited, decoded)).toBeUndefined();
    expect(codeHash(edited.code)).not.toBe(codeHash(linked.code));
    expect(decoded.modules['passes/tonemap']!.code).toBe(codeHash(linked.code));
  });

  it('caches bindings that override constants cannot change: a resource used under an override is always used', () => {
    // Bindings are a function of the code alone (entryPointBindings takes no constants): wgsl_reflect
    // follows calls whatever the branch, so the variant a pipeline compiles binds the same resources.
    const code = [
      'override USE_EXTRA: bool = false;',
      '@group(0) @binding(0) var<storage, read_write> out: array<u32>;',
      '@group(0) @binding(1) var<storage, read> extra: array<u32>;',
      'fn read_extra() -> u32 { return extra[0]; }',
      '@compute @workgroup_size(1) fn main() { var v = 1u; if (USE_EXTRA) { v = read_extra(); } out[0] = v; }',
    ].join('\n');
    const linked = linkWgsl('override-test', new Map([['override-test', code]]));
    expect(liveEntryResources(linked, 'main').map((r) => r.name).sort()).toEqual(['extra', 'out']);
  });
});
