import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { SHADER_MODULES } from '../shaders/index.ts';
import { DEFAULT_SETTINGS, DENOISE_VIEWS, validateSettings, type RenderSettings } from './settings.ts';

describe('denoiser settings', () => {
  it('DENOISE_VIEWS mirrors the DENOISE_VIEW_* constants of denoise-output.wgsl by position', () => {
    const source = SHADER_MODULES.get('passes/denoise-output')!;
    const constants = [...source.matchAll(/const DENOISE_VIEW_(\w+): u32 = (\d+)u;/g)].map(([, name, value]) => [name!.toLowerCase().replaceAll('_', '-'), Number(value)] as const);
    expect(constants.length).toBe(DENOISE_VIEWS.length);
    for (const [name, value] of constants) expect(DENOISE_VIEWS[value]).toBe(name);
  });

  it('accepts the defaults and the unlimited history, refuses nonsense with a LanternError', () => {
    const with_ = (changes: Partial<Record<keyof RenderSettings, unknown>>) => () => validateSettings({ ...DEFAULT_SETTINGS, ...changes } as RenderSettings);
    expect(with_({ historyCap: 'unlimited' })()).toMatchObject({ historyCap: 'unlimited' });
    expect(DEFAULT_SETTINGS).toMatchObject({ temporal: true, denoise: true, clampK: 1.25, denoiseView: 'output' });
    expectLanternError(with_({ historyCap: 0 }), /history cap/);
    expectLanternError(with_({ historyCap: 2.5 }), /history cap/);
    expectLanternError(with_({ historyCap: Number('forever') }), /history cap/);
    expectLanternError(with_({ clampK: -1 }), /clamp k/);
    expectLanternError(with_({ denoiseView: 'shadows' }), /unknown denoise view 'shadows'/);
    expectLanternError(with_({ temporal: 'yes' }), /temporal must be true or false/);
  });
});
