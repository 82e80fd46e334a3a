import { describe, expect, it } from 'vitest';
import { isValidValue, mergeSettings } from '../renderer/settings-schema.ts';
import { DEFAULT_SETTINGS, type RenderSettings, type RenderSettingsPatch } from '../renderer/settings.ts';
import { notApplicable, numberBindingLimits, PANEL_SETTINGS, settingTooltip, TOOLTIPS, webGpuOnly, type PanelContext } from './panel-settings.ts';

/** The panel's own controls (not render settings), keyed as TOOLTIPS keys them. */
const OWN_CONTROLS = ['samplesPerFrame', 'autoScale', 'scale', 'accumulate', 'animate', 'convergeWhenStill', 'fov', 'mode'];

/** A Doom-like scene (walk map, torch, moving doors) or a Cornell-like one (none of them), with settings changed by `patch`. */
function context(scene: 'doom' | 'cornell', patch: RenderSettingsPatch = {}): PanelContext {
  const render = mergeSettings(DEFAULT_SETTINGS, patch) as RenderSettings;
  const doom = scene === 'doom';
  return { render, hasTorch: doom, canWalk: doom, moving: doom, tileGrid: doom };
}

/** The controls disabled in a context. */
const disabled = (c: PanelContext) => [...OWN_CONTROLS, ...PANEL_SETTINGS.map((e) => e.id)].filter((id) => notApplicable(id, c) !== undefined).sort();

describe('the panel', () => {
  // The exposure itself (scene default, stops or 'auto') is drawn by panel.ts's exposure block, not from its entry.
  it('shows the settings it showed before the schema, the spectral switch, the wireframe level and the automatic exposure', () => {
    expect(PANEL_SETTINGS.map((e) => e.id).sort()).toEqual(
      ['accel', 'clampK', 'debugLayout', 'debugView', 'denoise', 'denoiseView', 'exposureAdaptation', 'exposureCompensation', 'heatMax', 'historyCap', 'hybrid.giBounces', 'hybrid.giFilter', 'hybrid.giSamples', 'hybrid.giScale', 'hybrid.lightSamples', 'hybrid.reflectionBounces', 'hybrid.reflections', 'hybrid.taa', 'integrator', 'maxBounces', 'recipe', 'restir', 'restirCandidates', 'sampler', 'spectral', 'temporal', 'toneMapper', 'torch.color', 'torch.enabled', 'torch.intensity', 'torch.range', 'tileCulling', 'wireframeDepth', 'wireframeLevel'].sort(),
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

  it('gives every control a one-line tooltip, and the jargon ones their own words', () => {
    const ids = new Set([...OWN_CONTROLS, ...PANEL_SETTINGS.map((e) => e.id)]);
    // No tooltip for a control the panel does not have (a renamed setting would leave one behind).
    for (const key of Object.keys(TOOLTIPS)) expect(ids.has(key), key).toBe(true);
    for (const entry of PANEL_SETTINGS) {
      const tip = settingTooltip(entry);
      expect(tip, entry.id).not.toMatch(/\n/);
      expect(tip.length, entry.id).toBeGreaterThan(10);
      expect(tip.length, entry.id).toBeLessThan(200);
    }
    for (const jargon of ['clampK', 'historyCap', 'sampler', 'denoise', 'temporal', 'integrator', 'accel', 'hybrid.giScale', 'hybrid.taa', 'tileCulling']) {
      expect(TOOLTIPS[jargon], jargon).toBeDefined();
    }
    expect(TOOLTIPS.clampK).toMatch(/standard deviation/);
    expect(TOOLTIPS.denoise).toMatch(/à-trous/);
  });

  it('in a Doom map at the defaults, disables only the knobs of what is off: the hybrid recipe and the debug views', () => {
    expect(disabled(context('doom'))).toEqual(['debugLayout', 'heatMax', 'hybrid.giBounces', 'hybrid.giFilter', 'hybrid.giSamples', 'hybrid.giScale', 'hybrid.lightSamples', 'hybrid.reflectionBounces', 'hybrid.reflections', 'hybrid.taa', 'wireframeDepth', 'wireframeLevel']);
  });

  it('disables walk mode, the torch switch, animation and tile culling in a scene without a walk map, torch or movers', () => {
    const off = disabled(context('cornell'));
    for (const id of ['mode', 'torch.enabled', 'animate', 'tileCulling']) expect(off).toContain(id);
    // The torch's strength stays: setting it is how such a scene gets a torch.
    expect(off).not.toContain('torch.intensity');
    expect(notApplicable('mode', context('cornell'))).toMatch(/walk map/);
  });

  it('disables the real-time denoiser knobs in progressive mode, and the path tracer ones in the hybrid recipe', () => {
    const progressive = disabled(context('doom', { temporal: false, denoise: false }));
    for (const id of ['clampK', 'historyCap', 'denoiseView', 'integrator', 'convergeWhenStill']) expect(progressive).toContain(id);
    expect(progressive).not.toContain('temporal');
    // Spatial filter alone: the clamp and cap limit temporal history, which is off.
    const spatial = disabled(context('doom', { temporal: false }));
    expect(spatial).toEqual(expect.arrayContaining(['clampK', 'historyCap']));
    expect(spatial).not.toContain('denoiseView');
    const hybrid = disabled(context('doom', { recipe: 'hybrid' }));
    for (const id of ['temporal', 'denoise', 'clampK', 'historyCap', 'integrator', 'spectral', 'samplesPerFrame']) expect(hybrid).toContain(id);
    expect(hybrid.filter((id) => id.startsWith('hybrid.'))).toEqual([]);
    expect(disabled(context('doom', { recipe: 'hybrid', hybrid: { reflections: false } }))).toContain('hybrid.reflectionBounces');
  });

  it('enables the debug knobs of the view shown only', () => {
    expect(disabled(context('doom', { debugView: 'heat-nodes' }))).toEqual(expect.not.arrayContaining(['heatMax', 'debugLayout']));
    expect(disabled(context('doom', { debugView: 'heat-nodes' }))).toEqual(expect.arrayContaining(['wireframeDepth', 'wireframeLevel']));
    expect(disabled(context('doom', { debugView: 'wireframe' }))).toEqual(expect.arrayContaining(['heatMax']));
    expect(disabled(context('doom', { debugView: 'wireframe' }))).not.toContain('wireframeDepth');
  });

  it('says why in one line, for every control it disables', () => {
    const contexts = [context('cornell', { temporal: false, denoise: false }), context('cornell', { recipe: 'hybrid', hybrid: { reflections: false } })];
    for (const c of contexts) {
      for (const id of disabled(c)) {
        const reason = notApplicable(id, c)!;
        expect(reason, id).not.toMatch(/\n/);
        expect(reason, id).toMatch(/^[A-Z].*\.$/);
      }
    }
  });
});

describe('the panel on the WebGL2 backend', () => {
  it('greys out what needs WebGPU with the reason, and leaves the progressive settings', () => {
    const c: PanelContext = { render: DEFAULT_SETTINGS, hasTorch: false, canWalk: true, moving: false, tileGrid: false, webgl2: true };
    for (const id of ['recipe', 'temporal', 'denoise', 'spectral', 'debugView', 'restir', 'hybrid.giScale', 'restirCandidates']) expect(notApplicable(id, c), id).toMatch(/^WebGPU only: .+ \(this page renders with WebGL2\)\.$/);
    for (const id of ['maxBounces', 'toneMapper', 'exposureStops', 'samplesPerFrame', 'mode', 'lightSampling']) expect(webGpuOnly(id), id).toBeUndefined();
    expect(notApplicable('recipe', { ...c, webgl2: false })).toBeUndefined();
  });
});
