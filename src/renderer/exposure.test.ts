import { describe, expect, it } from 'vitest';
import { adaptExposureStops, exposureChoice, log2AverageLuminance, MIDDLE_GREY, MIN_EXPOSURE_LUMINANCE, targetExposureStops } from './exposure.ts';
import { DEFAULT_SETTINGS, validateSettings } from './settings.ts';
import { isLook, lookSettings } from './looks.ts';
import { mergeSettings } from './settings-schema.ts';

describe('automatic exposure', () => {
  it('takes the geometric mean of luminance, an unlit pixel clamped rather than −∞', () => {
    // Grey pixels of luminance 1/4 and 4: the geometric mean is 1 (log2 0), the arithmetic one 2.125.
    expect(log2AverageLuminance([0.25, 0.25, 0.25, 4, 4, 4], 3)).toBeCloseTo(0, 12);
    // RGBA with a sample count: the scale applies before the log, alpha is ignored.
    expect(log2AverageLuminance([8, 8, 8, 99, 8, 8, 8, -1], 4, 1 / 8)).toBeCloseTo(0, 12);
    // Rec. 709 weights: pure green of 1 has luminance 0.7152.
    expect(log2AverageLuminance([0, 1, 0], 3)).toBeCloseTo(Math.log2(0.7152), 12);
    expect(log2AverageLuminance([0, 0, 0, 1, 1, 1], 3)).toBeCloseTo(Math.log2(MIN_EXPOSURE_LUMINANCE) / 2, 12);
    expect(log2AverageLuminance([], 3)).toBe(Math.log2(MIDDLE_GREY));
  });

  it('maps the average to middle grey, plus the compensation', () => {
    const log2Average = -5;
    const stops = targetExposureStops(log2Average, 0);
    expect(2 ** log2Average * 2 ** stops).toBeCloseTo(MIDDLE_GREY, 12);
    expect(targetExposureStops(log2Average, 1.5) - stops).toBeCloseTo(1.5, 12);
  });

  it('adapts by the exponential law: steps compose, the time constant closes 1 − 1/e of the gap', () => {
    const tau = 0.8;
    // One step of 0.6 s equals six of 0.1 s: the law depends on elapsed time, not on the frame rate.
    let stepped = -3;
    for (let i = 0; i < 6; i++) stepped = adaptExposureStops(stepped, 2, 0.1, tau);
    expect(stepped).toBeCloseTo(adaptExposureStops(-3, 2, 0.6, tau), 12);
    expect((adaptExposureStops(-3, 2, tau, tau) + 3) / 5).toBeCloseTo(1 - Math.exp(-1), 12);
    expect(adaptExposureStops(-3, 2, 0, tau)).toBe(-3);
    expect(adaptExposureStops(-3, 2, 1e6, tau)).toBe(2);
  });

  it('is the scene kind\'s choice until the setting overrides it', () => {
    const game = { autoExposure: true };
    const reference = {};
    const s = DEFAULT_SETTINGS;
    expect(s.exposureStops).toBeUndefined();
    expect(exposureChoice(game, 1.5, s)).toEqual({ kind: 'auto', compensationStops: 0, adaptationSeconds: s.exposureAdaptation });
    expect(exposureChoice(reference, 1.5, s)).toEqual({ kind: 'manual', stops: 1.5 });
    expect(exposureChoice(undefined, 0, s)).toEqual({ kind: 'manual', stops: 0 });
    // A number is manual, over the camera's exposure, on any scene; 'auto' is automatic on any scene.
    expect(exposureChoice(game, 1.5, { ...s, exposureStops: -1 })).toEqual({ kind: 'manual', stops: 0.5 });
    expect(exposureChoice(reference, 1.5, { ...s, exposureStops: 'auto', exposureCompensation: -2 })).toMatchObject({ kind: 'auto', compensationStops: -2 });
  });

  it('refuses an adaptation time of 0 and a compensation out of range', () => {
    expect(() => validateSettings({ ...DEFAULT_SETTINGS, exposureAdaptation: 0 })).toThrow(/exposure adaptation time must be a number above 0/);
    expect(() => validateSettings({ ...DEFAULT_SETTINGS, exposureCompensation: 20 })).toThrow(/exposure compensation must be a number from -16 to 16/);
  });
});

describe('looks', () => {
  it('doom: automatic exposure and the scene\'s torch, valid settings, a fresh copy each time', () => {
    expect(isLook('doom')).toBe(true);
    expect(isLook('noir')).toBe(false);
    const withTorch = { ...DEFAULT_SETTINGS, torch: { enabled: false, intensity: 5 } };
    const looked = validateSettings(mergeSettings(withTorch, { ...lookSettings('doom'), torch: { enabled: true } }));
    expect(exposureChoice({}, 0, looked).kind).toBe('auto');
    expect(looked.torch.enabled).toBe(true);
    const a = lookSettings('doom');
    (a as { exposureCompensation?: number }).exposureCompensation = 9;
    expect(lookSettings('doom').exposureCompensation).not.toBe(9);
  });
});
