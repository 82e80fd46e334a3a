import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { malformedTexts, outOfRangeValues, validValues } from './setting-samples.ts';
import {
  defaultsOf, describeValues, flattenSchema, formatSettingText, mergeSettings, number, numbers, optional, parseSettingText, setAt, SETTING_TYPES, text, validateAgainst,
  type SettingGroup, type SettingsOf,
} from './settings-schema.ts';
import { DEFAULT_SETTINGS, ESTIMATE_SETTINGS, SETTING_ENTRIES, validateSettings, type RenderSettings } from './settings.ts';

/** The defaults with one setting replaced (nested settings inside their group). */
function withValue(path: readonly string[], value: unknown): RenderSettings {
  const patch: Record<string, unknown> = {};
  setAt(patch, path, value);
  return mergeSettings(DEFAULT_SETTINGS, patch);
}

describe('the settings schema', () => {
  it('declares each CLI flag and link parameter once, and every type it uses', () => {
    const flags = SETTING_ENTRIES.flatMap((e) => (e.spec.cli ? [e.spec.cli.flag, ...(e.spec.cli.short ? [e.spec.cli.short] : [])] : []));
    const links = SETTING_ENTRIES.flatMap((e) => (e.spec.link ? [e.spec.link] : []));
    expect(new Set(flags).size).toBe(flags.length);
    expect(new Set(links).size).toBe(links.length);
    for (const e of SETTING_ENTRIES) expect(SETTING_TYPES).toContain(e.spec.type);
  });

  it('keeps the names scripts and saved links depend on', () => {
    const byId = new Map(SETTING_ENTRIES.map((e) => [e.id, e.spec]));
    const names = Object.fromEntries([...byId].map(([id, s]) => [id, [s.cli?.flag, s.link]]));
    expect(names).toMatchObject({
      maxBounces: ['--bounces', 'bounces'], toneMapper: ['--tonemap', 'tonemap'], exposureStops: ['--exposure', 'exposure'],
      'torch.enabled': ['--torch', 'torch'], 'torch.color': ['--torch-color', 'torch-color'], 'torch.intensity': ['--torch-intensity', 'torch-intensity'],
      'torch.range': ['--torch-range', 'torch-range'], debugView: ['--debug', 'debug'], debugLayout: ['--debug-layout', 'layout'],
      wireframeDepth: ['--wireframe-depth', 'depth'], heatMax: ['--heat-max', 'heat-max'], temporal: ['--temporal', 'temporal'],
      denoise: ['--denoise', 'denoise'], clampK: ['--clamp-k', 'clamp-k'], historyCap: ['--history-cap', 'history-cap'], denoiseView: ['--denoise-view', 'denoise-view'],
      seed: ['--seed', undefined], lightSampling: ['--light-sampling', undefined], sampler: ['--sampler', 'sampler'],
    });
  });

  it('derives defaults that validate, and the settings that restart accumulation', () => {
    expect(validateSettings(DEFAULT_SETTINGS)).toBe(DEFAULT_SETTINGS);
    expect(DEFAULT_SETTINGS).toMatchObject({ maxBounces: 8, lightSampling: 'mis', toneMapper: 'aces', torch: { enabled: true }, historyCap: 32 });
    // Optional settings have no default: absent means "the scene's own".
    expect(DEFAULT_SETTINGS.torch).toEqual({ enabled: true });
    expect(Object.isFrozen(DEFAULT_SETTINGS) && Object.isFrozen(DEFAULT_SETTINGS.torch)).toBe(true);
    expect([...ESTIMATE_SETTINGS].sort()).toEqual(['accel', 'hybrid', 'integrator', 'lightSampling', 'maxBounces', 'recipe', 'sampler', 'seed', 'spectral', 'tileCulling', 'torch']);
  });

  it('merges a nested patch into its group and leaves the rest alone', () => {
    const merged = mergeSettings(DEFAULT_SETTINGS, { torch: { intensity: 5 }, maxBounces: 3 });
    expect(merged.torch).toEqual({ enabled: true, intensity: 5 });
    expect(merged.maxBounces).toBe(3);
    expect(DEFAULT_SETTINGS.torch).toEqual({ enabled: true });
    expect(mergeSettings(merged, { torch: { color: [0.5, 0.5, 0.5] } }).torch).toEqual({ enabled: true, intensity: 5, color: [0.5, 0.5, 0.5] });
  });

  describe.each(SETTING_ENTRIES.map((e) => [e.id, e] as const))('%s', (_, entry) => {
    const { spec, path } = entry;
    it('accepts its valid values, and their text form reads back as the same value', () => {
      const values = validValues(spec);
      expect(values.length).toBeGreaterThan(0);
      for (const value of values) {
        expect(() => validateSettings(withValue(path, value)), String(value)).not.toThrow();
        expect(parseSettingText(spec, formatSettingText(spec, value))).toEqual({ ok: true, value });
      }
    });

    it('refuses values out of range and malformed text, naming what it accepts', () => {
      for (const value of outOfRangeValues(spec)) {
        expectLanternError(() => validateSettings(withValue(path, value)), new RegExp(`^${escape(spec.name)} must be ${escape(describeValues(spec))}, not `));
        expect(parseSettingText(spec, formatSettingText(spec, value))).toEqual({ ok: false, problem: `must be ${describeValues(spec)}` });
      }
      for (const text of malformedTexts(spec)) expect(parseSettingText(spec, text).ok, `'${text}'`).toBe(false);
    });
  });
});

const escape = (s: string) => s.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');

describe('describeValues', () => {
  it('phrases each kind of range as the messages use it', () => {
    const phrase = (id: string) => describeValues(SETTING_ENTRIES.find((e) => e.id === id)!.spec);
    expect(phrase('maxBounces')).toBe('a whole number from 0 to 1024');
    expect(phrase('heatMax')).toBe("a positive number or 'auto'");
    expect(phrase('torch.intensity')).toBe('a non-negative number');
    expect(phrase('historyCap')).toBe("a whole number from 1 to 65536, or 'unlimited'");
    expect(phrase('torch.color')).toBe('three comma-separated numbers, each number from 0 to 1');
    expect(phrase('torch.enabled')).toBe('on or off');
    expect(phrase('toneMapper')).toBe('one of linear, reinhard, aces');
  });
});

describe('the types the coming environment settings need', () => {
  // Shaped as `--sky elevation,azimuth[,turbidity]` and `--env file.hdr` with intensity and rotation will be.
  const EXAMPLE = {
    sky: optional(numbers({
      name: 'sky', description: 'an analytic sky', restarts: true, required: 2, default: [45, 0, 3],
      components: [{ name: 'elevation', min: -90, max: 90 }, { name: 'azimuth', min: -360, max: 360 }, { name: 'turbidity', min: 1, max: 10 }],
    })),
    env: {
      file: optional(text({ name: 'environment map', description: 'an HDR environment', accepts: 'an .hdr file', pattern: /\.hdr$/i, default: '', restarts: true })),
      intensity: number({ name: 'environment intensity', description: 'scale of the environment', min: 0, max: Infinity, default: 1, restarts: true }),
    },
  } as const satisfies SettingGroup;
  type Example = SettingsOf<typeof EXAMPLE>;
  const entries = flattenSchema(EXAMPLE);
  const defaults: Example = defaultsOf(EXAMPLE);

  it('derive a type, defaults and messages', () => {
    expect(entries.map((e) => e.id)).toEqual(['sky', 'env.file', 'env.intensity']);
    expect(defaults).toEqual({ env: { intensity: 1 } });
    const sky = entries[0]!.spec;
    expect(describeValues(sky)).toBe('elevation,azimuth[,turbidity]: elevation from -90 to 90, azimuth from -360 to 360, turbidity from 1 to 10');
    expect(parseSettingText(sky, '30,120')).toEqual({ ok: true, value: [30, 120] });
    expect(parseSettingText(sky, '30,120,2.5')).toEqual({ ok: true, value: [30, 120, 2.5] });
    expect(parseSettingText(sky, '95,120').ok).toBe(false);
    expect(parseSettingText(entries[1]!.spec, 'studio.HDR')).toEqual({ ok: true, value: 'studio.HDR' });
    expect(parseSettingText(entries[1]!.spec, 'studio.exr')).toEqual({ ok: false, problem: 'must be an .hdr file' });
    expectLanternError(() => validateAgainst(entries, mergeSettings(defaults, { sky: [0, 400] })), /^sky must be elevation,azimuth\[,turbidity\]: .* not 0, 400/);
  });

  it.each(entries.map((e) => [e.id, e] as const))('%s: samples round-trip and out-of-range ones are refused', (_, entry) => {
    const at = (value: unknown) => {
      const patch: Record<string, unknown> = {};
      setAt(patch, entry.path, value);
      return mergeSettings(defaults, patch);
    };
    const valid = validValues(entry.spec);
    expect(valid.length).toBeGreaterThan(0);
    for (const value of valid) {
      expect(() => validateAgainst(entries, at(value))).not.toThrow();
      expect(parseSettingText(entry.spec, formatSettingText(entry.spec, value))).toEqual({ ok: true, value });
    }
    for (const value of outOfRangeValues(entry.spec)) {
      expectLanternError(() => validateAgainst(entries, at(value)), /must be/);
      expect(parseSettingText(entry.spec, formatSettingText(entry.spec, value)).ok).toBe(false);
    }
    for (const t of malformedTexts(entry.spec)) expect(parseSettingText(entry.spec, t).ok, `'${t}'`).toBe(false);
  });
});
