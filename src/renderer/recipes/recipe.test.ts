import { describe, expect, it } from 'vitest';
import { DEFAULT_SETTINGS, type RenderSettings } from '../settings.ts';
import { newlyCompiled, recipeCompiles, recipeFor, RECIPES, type Recipe } from './recipe.ts';

const SWITCHES = ['temporal', 'denoise', 'restir'] as const;

/** Every combination of what chooses a recipe: the named recipe, the chain's switches, a debug view and its layout, frames asked for. */
function* combinations(): Generator<{ settings: RenderSettings; frames: boolean }> {
  for (const recipe of ['path', 'hybrid'] as const)
    for (let bits = 0; bits < 1 << SWITCHES.length; bits++)
      for (const [debugView, debugLayout] of [['none', 'replace'], ['heat-nodes', 'replace'], ['heat-nodes', 'side-by-side'], ['normals', 'overlay']] as const)
        for (const frames of [false, true]) {
          const switches = Object.fromEntries(SWITCHES.map((k, i) => [k, (bits & (1 << i)) !== 0]));
          yield { settings: { ...DEFAULT_SETTINGS, ...switches, recipe, debugView, debugLayout }, frames };
        }
}

describe('recipeFor: which recipe a frame runs', () => {
  it('draws a debug view that replaces the image without tracing, whatever else is asked', () => {
    for (const { settings, frames } of combinations()) {
      const replaces = settings.debugView !== 'none' && settings.debugLayout === 'replace';
      expect(recipeFor(settings, { frames }) === 'debug', JSON.stringify(settings)).toBe(replaces);
    }
  });

  it('runs the hybrid recipe when it is named, and the path recipes otherwise', () => {
    for (const { settings, frames } of combinations()) {
      const recipe = recipeFor(settings, { frames });
      if (recipe !== 'debug') expect(recipe === 'hybrid').toBe(settings.recipe === 'hybrid');
    }
  });

  it('runs the real-time chain when any of its switches is on or frames are asked for, and accumulates otherwise', () => {
    const plain = { ...DEFAULT_SETTINGS, temporal: false, denoise: false, restir: false };
    expect(recipeFor(plain)).toBe('progressive');
    expect(recipeFor(plain, { frames: true })).toBe('real-time');
    // ReSTIR's reservoirs live only in frames: asking for it alone asks for frames (the CLI's --restir and the viewer's alike).
    for (const k of SWITCHES) expect(recipeFor({ ...plain, [k]: true }), k).toBe('real-time');
    // Every recipe is reachable.
    const seen = new Set<Recipe>([...combinations()].map(({ settings, frames }) => recipeFor(settings, { frames })));
    expect([...seen].sort()).toEqual([...RECIPES].sort());
  });
});

describe('recipeCompiles: what a recipe compiles', () => {
  it('compiles each recipe\'s own passes and no other recipe\'s', () => {
    for (const { settings, frames } of combinations()) {
      for (const integrator of ['megakernel', 'wavefront'] as const) {
        const s = { ...settings, integrator, spectral: true };
        const recipe = recipeFor(s, { frames });
        const c = recipeCompiles(s, { frames });
        const label = `${recipe} ${JSON.stringify(s)}`;
        expect(c.realTime, label).toBe(recipe === 'real-time');
        expect(c.hybrid, label).toBe(recipe === 'hybrid');
        // The integrator and ReSTIR are options of the real-time chain alone.
        expect(c.wavefront, label).toBe(recipe === 'real-time' && integrator === 'wavefront');
        expect(c.restir, label).toBe(recipe === 'real-time' && s.restir);
        // The debug views, when one is shown alone or with the image.
        expect(c.debugViews, label).toBe(s.debugView !== 'none');
        // Spectral path tracers wherever paths are traced (the viewer converges a still view progressively beside any frame recipe).
        expect(c.spectral, label).toBe(recipe !== 'debug');
        expect(recipeCompiles({ ...s, spectral: false }, { frames }).spectral).toBe(false);
      }
    }
  });

  it('names what a change of settings compiles first, and nothing for a change that compiles nothing new', () => {
    const progressive = { ...DEFAULT_SETTINGS, temporal: false, denoise: false };
    expect(newlyCompiled(progressive, { ...progressive, restir: true })).toBe('the real-time chain');
    expect(newlyCompiled(progressive, { ...progressive, recipe: 'hybrid' })).toBe('the hybrid recipe');
    expect(newlyCompiled(progressive, { ...progressive, debugView: 'normals', debugLayout: 'overlay' })).toBe('the debug views');
    expect(newlyCompiled(progressive, { ...progressive, spectral: true })).toBe('spectral rendering');
    expect(newlyCompiled(DEFAULT_SETTINGS, { ...DEFAULT_SETTINGS, denoise: false })).toBeUndefined();
    // Back to the progressive estimate: its kernels are always there.
    expect(newlyCompiled(DEFAULT_SETTINGS, progressive)).toBeUndefined();
  });
});
