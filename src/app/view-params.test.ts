import { describe, expect, it } from 'vitest';
import { malformedTexts, outOfRangeValues, validValues } from '../renderer/setting-samples.ts';
import { describeValues, formatSettingText, setAt } from '../renderer/settings-schema.ts';
import { lookSettings } from '../renderer/looks.ts';
import { formatViewParams, LINKED_SETTINGS, linkedRenderSettings, parseViewParams, type ViewParams } from './view-params.ts';

describe('view parameters', () => {
  it('round-trip a full view', () => {
    const view: ViewParams = {
      scene: { kind: 'files', format: 'doom-wad', urls: ['files/0/freedoom1.wad', 'files/1/my.wad'], part: 'E1M2' },
      pose: { position: [1024.5, 41, -3200.25], yaw: 1.5708, pitch: -0.1 },
      fovDegrees: 73.74,
      apertureRadius: 0.00625,
      focusDistance: 1234.5,
      mode: 'walk',
      samplesPerFrame: 4,
      maxBounces: 3,
      scale: 0.5,
      accumulate: false,
      animate: false,
      convergeWhenStill: false,
      toneMapper: 'reinhard',
      exposureStops: -1.5,
      debugView: 'wireframe',
      debugLayout: 'overlay',
      wireframeDepth: 3,
      heatMax: 'auto',
      temporal: true,
      denoise: false,
      clampK: 1.5,
      historyCap: 'unlimited',
      denoiseView: 'variance',
      torch: { enabled: true, color: [1, 0.8, 0.6], intensity: 2000, range: 900 },
      sky: { elevation: 12.5, azimuth: -40, turbidity: 4.5 },
      envIntensity: 0.25,
    };
    const { view: back, problems } = parseViewParams(new URLSearchParams(formatViewParams(view).toString()));
    expect(problems).toEqual([]);
    expect(back).toEqual(view);
    // What reaches the renderer: the render settings it names, under their own names, and nothing else.
    expect(linkedRenderSettings(back)).toEqual({ maxBounces: 3, toneMapper: 'reinhard', exposureStops: -1.5, debugView: 'wireframe', debugLayout: 'overlay', wireframeDepth: 3, heatMax: 'auto', temporal: true, denoise: false, clampK: 1.5, historyCap: 'unlimited', denoiseView: 'variance' });
    expect(linkedRenderSettings({ exposureStops: 2 })).toEqual({ exposureStops: 2 });
  });

  it('reads a look as the settings it sets, under those the link names, and refuses an unknown one', () => {
    const { view, problems } = parseViewParams(new URLSearchParams('look=doom&exposure-compensation=-0.5&torch-intensity=100'));
    expect(problems).toEqual([]);
    expect(view).toMatchObject({ exposureStops: 'auto', exposureCompensation: -0.5, toneMapper: lookSettings('doom').toneMapper, torch: { enabled: true, intensity: 100 } });
    // Written back, a link names the settings themselves.
    expect(parseViewParams(formatViewParams(view)).view).toEqual(view);
    // The link's own value did not leak into the look.
    expect(lookSettings('doom').torch).toEqual({ enabled: true });
    expect(parseViewParams(new URLSearchParams('look=noir')).problems).toEqual(['look=noir is not one of doom']);
    expect(parseViewParams(new URLSearchParams('exposure=auto')).view).toEqual({ exposureStops: 'auto' });
  });

  it('reads the scene forms and ignores what is absent', () => {
    expect(parseViewParams(new URLSearchParams('scene=furnace')).view).toEqual({ scene: { kind: 'builtin', name: 'furnace' } });
    expect(parseViewParams(new URLSearchParams('ply=files/0/dragon.ply.gz')).view.scene).toEqual({ kind: 'files', format: 'ply', urls: ['files/0/dragon.ply.gz'] });
    expect(parseViewParams(new URLSearchParams('wad=a.wad&map=e1m1')).view.scene).toEqual({ kind: 'files', format: 'doom-wad', urls: ['a.wad'], part: 'E1M1' });
    expect(parseViewParams(new URLSearchParams('')).view).toEqual({});
  });

  it("reads and writes Doom's skill level with the files, ignoring one outside 1–5", () => {
    const scene = { kind: 'files', format: 'doom-wad', urls: ['a.wad'], part: 'E1M1', skill: 4 } as const;
    expect(parseViewParams(new URLSearchParams('wad=a.wad&map=e1m1&skill=4')).view.scene).toEqual(scene);
    expect(parseViewParams(formatViewParams({ scene })).view.scene).toEqual(scene);
    for (const bad of ['0', '6', '2.5', 'x']) expect(parseViewParams(new URLSearchParams(`wad=a.wad&skill=${bad}`)).view.scene).toEqual({ kind: 'files', format: 'doom-wad', urls: ['a.wad'] });
  });

  it('names every parameter it refuses and keeps the rest', () => {
    const { view, problems } = parseViewParams(new URLSearchParams('cam=1,2,3&spf=0&bounces=2.5&scale=9&tonemap=filmic&mode=swim&torch-color=2,0,0&exposure=1&debug=rainbow&depth=-1&heat-max=40'));
    expect(view).toEqual({ exposureStops: 1, heatMax: 40 });
    expect(problems).toHaveLength(9);
    expect(problems.join('\n')).toMatch(/cam=1,2,3 is not 5 numbers/);
    expect(problems.join('\n')).toMatch(/spf=0 is not a whole number from 1 to 64/);
    expect(problems.join('\n')).toMatch(/scale=9 is not a number from 0.01 to 2/);
  });

  it('reads a lens: aperture 0 is a pinhole, a focus distance must be positive', () => {
    expect(parseViewParams(new URLSearchParams('aperture=0&focus=3.5')).view).toEqual({ apertureRadius: 0, focusDistance: 3.5 });
    const { view, problems } = parseViewParams(new URLSearchParams('aperture=-1&focus=0'));
    expect(view).toEqual({});
    expect(problems).toEqual(['aperture=-1 is not ≥ 0', 'focus=0 is not > 0']);
    expect(parseViewParams(new URLSearchParams('focus=far')).problems).toEqual(['focus=far is not 1 number']);
  });
});

describe('render settings in links, from the schema', () => {
  const viewWith = (path: readonly string[], value: unknown): ViewParams => {
    const view: Record<string, unknown> = {};
    setAt(view, path, value);
    return view as ViewParams;
  };

  it.each(LINKED_SETTINGS.map((e) => [e.spec.link!, e] as const))('%s: every valid value round-trips; out of range and malformed ones are ignored with a note', (name, entry) => {
    for (const value of validValues(entry.spec)) {
      const params = formatViewParams(viewWith(entry.path, value));
      expect(params.get(name)).toBe(formatSettingText(entry.spec, value));
      expect(parseViewParams(new URLSearchParams(params.toString()))).toEqual({ view: viewWith(entry.path, value), problems: [] });
    }
    const refused = [...outOfRangeValues(entry.spec).map((v) => formatSettingText(entry.spec, v)), ...malformedTexts(entry.spec)];
    for (const text of refused) {
      // A valid parameter beside the refused one is kept.
      const [other, kept] = name === 'exposure' ? (['bounces', { maxBounces: 3 }] as const) : (['exposure', { exposureStops: 3 }] as const);
      const { view, problems } = parseViewParams(new URLSearchParams({ [name]: text, [other]: '3' }));
      expect(view, `${name}=${text}`).toEqual(kept);
      expect(problems).toEqual([`${name}=${text} is not ${describeValues(entry.spec)}`]);
    }
  });

  it('accepts in links the ranges the CLI accepts (links used to stop at 64 bounces and ±20 stops)', () => {
    expect(parseViewParams(new URLSearchParams('bounces=1024&exposure=-64')).view).toEqual({ maxBounces: 1024, exposureStops: -64 });
    expect(parseViewParams(new URLSearchParams('bounces=1025')).problems).toEqual(['bounces=1025 is not a whole number from 0 to 1024']);
  });

  it('reads the boolean words links have always used', () => {
    expect(parseViewParams(new URLSearchParams('torch=off&temporal=0&denoise=1')).view).toEqual({ torch: { enabled: false }, temporal: false, denoise: true });
    expect(parseViewParams(new URLSearchParams('torch=on&temporal=true')).view).toEqual({ torch: { enabled: true }, temporal: true });
  });

  it('read a sky with the CLI default turbidity, and refuse one outside the sky model', () => {
    expect(parseViewParams(new URLSearchParams('sky=30,120&env-intensity=2')).view).toMatchObject({ sky: { elevation: 30, azimuth: 120, turbidity: 3 }, envIntensity: 2 });
    for (const bad of ['sky=95,0', 'sky=30', 'sky=30,0,11', 'sky=30,0,0.5', 'sky=a,b', 'env-intensity=-1']) {
      const { view, problems } = parseViewParams(new URLSearchParams(bad));
      expect(view.sky, bad).toBeUndefined();
      expect(view.envIntensity, bad).toBeUndefined();
      expect(problems, bad).toHaveLength(1);
    }
  });
});
