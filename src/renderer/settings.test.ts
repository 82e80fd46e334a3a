import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { SHADER_MODULES } from '../shaders/index.ts';
import { DEBUG_LAYOUTS, DEBUG_VIEWS, DEFAULT_SETTINGS, LIGHT_SAMPLING, SAMPLERS, SAMPLER_SETTINGS, TONE_MAPPERS, resolveSampler, validateSettings, type RenderSettings } from './settings.ts';

/** The u32 constants named PREFIX_* in a WGSL module, by name. */
function wgslConstants(module: string, prefix: string): Map<string, number> {
  const source = SHADER_MODULES.get(module)!;
  const re = new RegExp(`^const ${prefix}_([A-Z0-9_]+): u32 = (\\d+)u;`, 'gm');
  return new Map(Array.from(source.matchAll(re), (m) => [m[1]!, Number(m[2])]));
}

const wgslName = (name: string) => name.toUpperCase().replace(/-/g, '_');

describe('closed lists mirror their WGSL constants by position', () => {
  it.each([
    ['debug views', DEBUG_VIEWS, 'lib/debug-views', 'DEBUG_VIEW'],
    ['debug layouts', DEBUG_LAYOUTS, 'lib/debug-views', 'DEBUG_LAYOUT'],
    ['tone mappers', TONE_MAPPERS, 'lib/color', 'TONEMAP'],
    ['light sampling', LIGHT_SAMPLING, 'integrator/path', 'LIGHT_SAMPLING'],
    ['samplers', SAMPLERS, 'lib/random', 'SAMPLER'],
  ] as const)('%s', (_, names, module, prefix) => {
    const constants = wgslConstants(module, prefix);
    expect(constants.size).toBe(names.length);
    names.forEach((name, i) => expect(constants.get(wgslName(name)), `${prefix}_${wgslName(name)}`).toBe(i));
  });
});

describe('the sampler setting', () => {
  it("defaults to 'auto': Sobol for a progressive render, PCG for the real-time chain; a named sampler is used by both", () => {
    expect(DEFAULT_SETTINGS.sampler).toBe('auto');
    expect(resolveSampler('auto', 'progressive')).toBe('sobol');
    expect(resolveSampler('auto', 'real-time')).toBe('random');
    for (const s of SAMPLERS) for (const chain of ['progressive', 'real-time'] as const) expect(resolveSampler(s, chain)).toBe(s);
    expect([...SAMPLER_SETTINGS]).toEqual(['auto', ...SAMPLERS]);
  });
});

describe('validateSettings', () => {
  const valid = (changes: Partial<RenderSettings>) => validateSettings({ ...DEFAULT_SETTINGS, ...changes });

  it('accepts the defaults and every debug view, layout, depth and heat maximum in range', () => {
    expect(valid({})).toEqual(DEFAULT_SETTINGS);
    for (const debugView of DEBUG_VIEWS) for (const debugLayout of DEBUG_LAYOUTS) expect(() => valid({ debugView, debugLayout })).not.toThrow();
    for (const wireframeDepth of [0, 17, 64]) expect(() => valid({ wireframeDepth })).not.toThrow();
    for (const heatMax of ['auto', 1, 250.5] as const) expect(() => valid({ heatMax })).not.toThrow();
  });

  it.each([
    [{ debugView: 'heat' }, /unknown debug view 'heat'/],
    [{ debugLayout: 'split' }, /unknown debug layout 'split'/],
    [{ wireframeDepth: -1 }, /wireframe depth must be a whole number from 0 to 64, not -1/],
    [{ wireframeDepth: 2.5 }, /wireframe depth/],
    [{ wireframeDepth: 65 }, /wireframe depth/],
    [{ heatMax: 0 }, /heat map maximum must be a positive number or 'auto', not 0/],
    [{ heatMax: Number.NaN }, /heat map maximum/],
    [{ heatMax: 'max' }, /heat map maximum/],
  ])('%j is refused with a clear LanternError', (changes, message) => {
    expectLanternError(() => valid(changes as Partial<RenderSettings>), message);
  });
});
