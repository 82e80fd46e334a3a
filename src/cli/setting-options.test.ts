import { Command, InvalidArgumentError } from 'commander';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { malformedTexts, outOfRangeValues, validValues } from '../renderer/setting-samples.ts';
import { describeValues, formatSettingText, mergeSettings, setAt } from '../renderer/settings-schema.ts';
import { DEFAULT_SETTINGS, SETTING_ENTRIES, validateSettings } from '../renderer/settings.ts';
import { PANEL_SETTINGS, settingTooltip } from '../app/panel-settings.ts';
import { registerRender } from './commands/render.ts';
import type { CliContext } from './context.ts';
import { CLI_SETTINGS, parseCliSetting, settingMode, settingOption, settingsFromOptions, withSettingOptions } from './setting-options.ts';

/** Parses a command line the way `lantern render` does, and returns the settings it asks for. */
function settingsOf(args: string[]) {
  const command = withSettingOptions(new Command().exitOverride().configureOutput({ writeErr: () => {} }));
  command.parse(args, { from: 'user' });
  return settingsFromOptions(command.opts());
}

const escape = (s: string) => s.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');

describe('render settings on the command line', () => {
  it('offers every setting that has a flag, and only those', () => {
    expect(CLI_SETTINGS.map((e) => e.id)).toEqual(SETTING_ENTRIES.filter((e) => e.spec.cli).map((e) => e.id));
    expect(CLI_SETTINGS.length).toBeGreaterThan(10);
  });

  describe.each(CLI_SETTINGS.map((e) => [e.spec.cli!.flag, e] as const))('%s', (flag, entry) => {
    const { spec } = entry;
    const offered = (v: unknown) => spec.type !== 'choice' || !spec.cli?.values || spec.cli.values.includes(String(v));

    it('reads each valid value back as itself, through commander into the nested settings', () => {
      for (const value of validValues(spec).filter(offered)) {
        const text = formatSettingText(spec, value);
        expect(parseCliSetting(entry, text)).toEqual(value);
        if (spec.cli?.switch) continue;
        const patch: Record<string, unknown> = {};
        setAt(patch, entry.path, value);
        expect(settingsOf([flag, text])).toMatchObject(patch);
      }
    });

    it('refuses out-of-range values as validation does, with the same words', () => {
      for (const value of outOfRangeValues(spec)) {
        const text = formatSettingText(spec, value);
        const phrase = escape(describeValues(spec));
        expect(() => parseCliSetting(entry, text)).toThrow(InvalidArgumentError);
        expect(() => parseCliSetting(entry, text)).toThrow(new RegExp(`^${escape(flag)} must be ${phrase}, not '`));
        const patch: Record<string, unknown> = {};
        setAt(patch, entry.path, value);
        expectLanternError(() => validateSettings(mergeSettings(DEFAULT_SETTINGS, patch)), new RegExp(`must be ${phrase}, not `));
      }
      for (const text of malformedTexts(spec)) expect(() => parseCliSetting(entry, text), `'${text}'`).toThrow(InvalidArgumentError);
    });
  });

  it('leaves out what is not given, except switches, which are off unless given', () => {
    expect(settingsOf([])).toEqual({ temporal: false, denoise: false, spectral: false, tileCulling: false, restir: false });
    expect(settingsOf(['--temporal', '-b', '3', '--torch-intensity', '5', '--torch', 'off'])).toEqual({ temporal: true, denoise: false, spectral: false, tileCulling: false, restir: false, maxBounces: 3, torch: { intensity: 5, enabled: false } });
  });

  it('a torch option keeps the torch on (nested settings merge into their group)', () => {
    const s = mergeSettings(DEFAULT_SETTINGS, settingsOf(['--torch-range', '900', '--torch-color', '1,0.5,0']));
    expect(s.torch).toEqual({ enabled: true, range: 900, color: [1, 0.5, 0] });
    expect(validateSettings(s)).toBe(s);
  });

  it("--debug offers no 'none': leaving it out is how to ask for none", () => {
    const debug = CLI_SETTINGS.find((e) => e.id === 'debugView')!;
    expect(() => parseCliSetting(debug, 'none')).toThrow(/--debug must be one of heat-nodes, /);
    expect(settingsOf([])).not.toHaveProperty('debugView');
  });
});

describe('the mode a setting applies to', () => {
  it('is the schema field, never a prefix of the description', () => {
    for (const entry of SETTING_ENTRIES) {
      expect(settingMode(entry), entry.id).toBe(entry.spec.mode);
      expect(entry.spec.description, entry.id).not.toMatch(/^(frame mode|hybrid):/);
    }
    expect(SETTING_ENTRIES.filter((e) => e.spec.mode === 'frame').map((e) => e.id)).toEqual(['integrator', 'temporal', 'denoise', 'clampK', 'historyCap', 'restir', 'restirCandidates', 'denoiseView']);
    expect(SETTING_ENTRIES.filter((e) => e.spec.mode === 'hybrid').map((e) => e.id)).toEqual(SETTING_ENTRIES.filter((e) => e.path[0] === 'hybrid').map((e) => e.id));
  });

  it('opens the help text as it always has', () => {
    const help = (id: string) => settingOption(SETTING_ENTRIES.find((e) => e.id === id)!).description;
    expect(help('clampK')).toBe('frame mode: history clamp to mean ± k·σ of the 3×3 neighbourhood (0: off) (default: 1.25)');
    expect(help('temporal')).toBe('frame mode: accumulate over frames with reprojection (temporal denoising)');
    expect(help('hybrid.giScale')).toBe('hybrid: GI texels per pixel along each axis (0.5: one GI path per four pixels), upsampled by a joint bilateral filter (default: 0.5)');
    expect(help('hybrid.taa')).toBe('hybrid: temporal anti-aliasing (history reprojected and clamped to the 3×3 neighbourhood) (default: 1)');
    expect(help('maxBounces')).toBe('maximum bounces per path (0: emitters only, 1: direct light, ...) (default: 8)');
    // `lantern render --help` prints them so.
    const program = new Command();
    registerRender(program, {} as CliContext);
    const text = program.commands.find((c) => c.name() === 'render')!.helpInformation();
    expect(text).toMatch(/--clamp-k <k> +frame mode: history clamp to mean ± k·σ of the 3×3 neighbourhood \(0: off\) \(default: 1\.25\)/);
    expect(text).toMatch(/--gi-scale <0\.25\.\.1> +hybrid: GI texels per pixel along each axis/);
  });

  it("keeps the panel's tooltips that come from a description, mode and all", () => {
    expect(settingTooltip(PANEL_SETTINGS.find((e) => e.id === 'restir')!)).toMatch(/^Frame mode: direct light at the first bounce by ReSTIR DI/);
  });
});
