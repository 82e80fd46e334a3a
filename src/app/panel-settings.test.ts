import { describe, expect, it } from 'vitest';
import { isValidValue } from '../renderer/settings-schema.ts';
import { numberBindingLimits, PANEL_SETTINGS } from './panel-settings.ts';

describe('the panel', () => {
  // The exposure itself (scene default, stops or 'auto') is drawn by panel.ts's exposure block, not from its entry.
  it('shows the settings it showed before the schema, the spectral switch, the wireframe level and the automatic exposure', () => {
    expect(PANEL_SETTINGS.map((e) => e.id).sort()).toEqual(
      ['accel', 'clampK', 'debugLayout', 'debugView', 'denoise', 'denoiseView', 'exposureAdaptation', 'exposureCompensation', 'heatMax', 'historyCap', 'hybrid.giBounces', 'hybrid.giFilter', 'hybrid.giSamples', 'hybrid.giScale', 'hybrid.lightSamples', 'hybrid.reflectionBounces', 'hybrid.reflections', 'hybrid.taa', 'integrator', 'maxBounces', 'recipe', 'sampler', 'spectral', 'temporal', 'toneMapper', 'torch.color', 'torch.enabled', 'torch.intensity', 'torch.range', 'tileCulling', 'wireframeDepth', 'wireframeLevel'].sort(),
    );
  });

  it.each(PANEL_SETTINGS.filter((e) => ['integer', 'number', 'number-or-auto', 'integer-or-unlimited'].includes(e.spec.type)).map((e) => [e.id, e] as const))(
    '%s: the limits are the schema ones, the slider lies within them',
    (_, entry) => {
      const spec = entry.spec;
      if (spec.type !== 'integer' && spec.type !== 'number' && spec.type !== 'number-or-auto' && spec.type !== 'integer-or-unlimited') throw new Error('numeric settings only');
      const { min, max, slider } = numberBindingLimits(entry);
      // What the panel lets through is what the schema accepts: the same bounds, or none where the schema has none.
      expect(max).toBe(Number.isFinite(spec.max) ? spec.max : undefined);
      expect(min).toBe(spec.above && spec.type !== 'number-or-auto' ? undefined : spec.min);
      if (min !== undefined && spec.type !== 'number-or-auto') expect(isValidValue(spec, min)).toBe(true);
      if (max !== undefined) expect(isValidValue(spec, max)).toBe(true);
      if (slider) {
        expect(slider[0]).toBeLessThan(slider[1]);
        expect(isValidValue(spec, slider[0])).toBe(true);
        expect(isValidValue(spec, slider[1])).toBe(true);
      }
    },
  );

  it('slides over bounces 0–32 while accepting typed values up to 1024', () => {
    expect(numberBindingLimits(PANEL_SETTINGS.find((e) => e.id === 'maxBounces')!)).toEqual({ min: 0, max: 1024, step: 1, slider: [0, 32] });
  });
});
