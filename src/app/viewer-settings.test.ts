import { describe, expect, it } from 'vitest';
import { formatSettingText, isValidValue, setAt, type SettingEntry } from '../renderer/settings-schema.ts';
import { DEFAULT_ENVIRONMENT_CHOICE } from './environment-choice.ts';
import { VIEWER_PANEL_BINDINGS, viewerBinding, type ViewerPanelKey } from './panel-settings.ts';
import { formatViewParams, LINKED_SETTINGS, LINKED_VIEWER_SETTINGS, parseViewParams, type ViewParams } from './view-params.ts';
import { SKY_LINK, VIEWER_DEFAULTS, VIEWER_ENTRIES, viewerEntry } from './viewer-settings.ts';

type Bounded = { min: number; max: number; above?: boolean };
const boundsOf = (entry: SettingEntry): Bounded | undefined => ('min' in entry.spec && 'max' in entry.spec ? (entry.spec as Bounded) : undefined);

/** A value just outside a limit: one whole number past it, or a millionth of it (of 1 at 0) for a real number. */
const past = (entry: SettingEntry, limit: number, direction: -1 | 1) => limit + direction * (entry.spec.type === 'integer' ? 1 : Math.max(Math.abs(limit), 1) * 1e-6);

/** The link text that carries `value` for a viewer setting: its own parameter, or the sky's (the others at their defaults). */
function linkFor(entry: SettingEntry, value: number): URLSearchParams {
  if (entry.path[0] !== 'sky') return new URLSearchParams({ [entry.spec.link!]: formatSettingText(entry.spec, value) });
  const sky: Record<string, number> = { ...VIEWER_DEFAULTS.sky, [entry.path[1]!]: value };
  return new URLSearchParams({ sky: formatSettingText(SKY_LINK, [sky.elevation, sky.azimuth, sky.turbidity]) });
}

/** The view a link parsed to holds `value` for the setting. */
const viewHolds = (view: ViewParams, entry: SettingEntry, value: number) => {
  const expected: Record<string, unknown> = {};
  setAt(expected, entry.path, value);
  expect(view).toMatchObject(expected);
};

const panelKeyOf = (entry: SettingEntry) => (Object.entries(VIEWER_PANEL_BINDINGS) as [ViewerPanelKey, string][]).find(([, id]) => id === entry.id)?.[0];

describe('the viewer settings', () => {
  it('declare what the page has, each once, with the link names saved links use', () => {
    expect(VIEWER_ENTRIES.map((e) => e.id)).toEqual(['samplesPerFrame', 'scale', 'accumulate', 'animate', 'convergeWhenStill', 'fovDegrees', 'sky.elevation', 'sky.azimuth', 'sky.turbidity', 'envIntensity']);
    expect(Object.fromEntries(LINKED_VIEWER_SETTINGS.map((e) => [e.id, e.spec.link]))).toEqual({
      samplesPerFrame: 'spf', scale: 'scale', accumulate: 'acc', animate: 'anim', convergeWhenStill: 'converge', fovDegrees: 'fov', envIntensity: 'env-intensity',
    });
    expect(SKY_LINK.link).toBe('sky');
    // No viewer parameter takes a render setting's name (nor the link's own: cam, mode, the scene's).
    const links = [...LINKED_VIEWER_SETTINGS.map((e) => e.spec.link!), SKY_LINK.link!, ...LINKED_SETTINGS.map((e) => e.spec.link!), 'cam', 'mode', 'scene', 'aperture', 'focus'];
    expect(new Set(links).size).toBe(links.length);
  });

  it('have defaults that are valid values, which the panel starts from', () => {
    for (const entry of VIEWER_ENTRIES) if (!entry.optional) expect(isValidValue(entry.spec, entry.spec.default), entry.id).toBe(true);
    expect(VIEWER_DEFAULTS).toEqual({ samplesPerFrame: 1, scale: 1, accumulate: true, animate: true, convergeWhenStill: true, sky: { elevation: 35, azimuth: 45, turbidity: 3 }, envIntensity: 1 });
    expect(DEFAULT_ENVIRONMENT_CHOICE).toMatchObject({ ...VIEWER_DEFAULTS.sky, skyIntensity: VIEWER_DEFAULTS.envIntensity });
  });

  it('give every one the panel shows a binding, and every binding a setting', () => {
    expect(VIEWER_ENTRIES.filter((e) => e.spec.panel).map((e) => e.id).sort()).toEqual(Object.values(VIEWER_PANEL_BINDINGS).sort());
  });

  it.each(VIEWER_ENTRIES.filter((e) => boundsOf(e)).map((e) => [e.id, e] as const))('%s: a link accepts each limit and refuses a value just outside it; the panel has the same limits', (_, entry) => {
    const { min, max, above } = boundsOf(entry)!;
    expect(above).toBeFalsy();
    for (const limit of [min, max]) {
      const { view, problems } = parseViewParams(linkFor(entry, limit));
      expect(problems, `${entry.id} = ${limit}`).toEqual([]);
      viewHolds(view, entry, limit);
      // Written back, the link says the same.
      viewHolds(parseViewParams(formatViewParams(view)).view, entry, limit);
    }
    for (const [limit, direction] of [[min, -1], [max, 1]] as const) {
      const value = past(entry, limit, direction);
      const { view, problems } = parseViewParams(linkFor(entry, value));
      expect(problems, `${entry.id} = ${value}`).toHaveLength(1);
      expect(view, `${entry.id} = ${value}`).toEqual({});
    }
    if (entry.spec.type === 'integer') expect(parseViewParams(linkFor(entry, min + 0.5)).problems).toHaveLength(1);

    // The panel: the same limits (typed values reach them), a slider within them.
    const binding = viewerBinding(panelKeyOf(entry)!);
    expect(binding.label).toBe(entry.spec.panel!.label);
    expect([binding.min, binding.max]).toEqual([min, max]);
    if (binding.slider) {
      expect(binding.slider[0]).toBeLessThan(binding.slider[1]);
      for (const end of binding.slider) expect(isValidValue(entry.spec, end), `${entry.id} slider ${end}`).toBe(true);
    }
  });

  it.each(VIEWER_ENTRIES.filter((e) => e.spec.type === 'boolean').map((e) => [e.spec.link!, e] as const))('%s: a link reads 0 and 1 (and the words links have used), refuses anything else', (name, entry) => {
    for (const [text, value] of [['0', false], ['1', true], ['off', false], ['on', true]] as const) viewHolds(parseViewParams(new URLSearchParams({ [name]: text })).view as ViewParams, entry, value as never);
    expect(formatViewParams(parseViewParams(new URLSearchParams({ [name]: 'on' })).view).get(name)).toBe('1');
    expect(parseViewParams(new URLSearchParams({ [name]: 'maybe' }))).toEqual({ view: {}, problems: [`${name}=maybe is not 1 or 0`] });
    expect(viewerBinding(panelKeyOf(entry)!)).toEqual({ label: entry.spec.panel!.label });
  });

  it('chose one set of limits where links and the panel had drifted', () => {
    // Samples per frame 1–64 (the panel stopped at 16: its slider still does); field of view 1–179° (links 150°, the panel 120°); the sun from −90° (the panel's slider from −10°).
    expect(viewerBinding('samplesPerFrame')).toEqual({ label: 'samples/frame', min: 1, max: 64, step: 1, slider: [1, 16] });
    expect(viewerBinding('fov')).toMatchObject({ min: 1, max: 179 });
    expect(viewerBinding('sunElevation')).toMatchObject({ min: -90, max: 90, slider: [-10, 90] });
    expect(parseViewParams(new URLSearchParams('spf=64&fov=179&sky=-90,0')).view).toEqual({ samplesPerFrame: 64, fovDegrees: 179, sky: { elevation: -90, azimuth: 0, turbidity: 3 } });
    expect(parseViewParams(new URLSearchParams('sky=91,0')).problems).toEqual([`sky=91,0 is not elevation,azimuth[,turbidity]: elevation from -90 to 90, azimuth from -360 to 360, turbidity from 1 to 10`]);
    expect(viewerEntry('fovDegrees').optional).toBe(true);
  });
});
