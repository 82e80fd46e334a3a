/**
 * Looks: one-click sets of display settings (the panel's buttons, the link's `look=`). A look changes
 * only how the image is exposed and shown, and puts the torch back to the scene's own; links and
 * flags given beside it win.
 */
import type { RenderSettingsPatch } from './settings.ts';

export const LOOKS = ['doom'] as const;
export type Look = (typeof LOOKS)[number];

/**
 * 'doom': the game's brightness. Doom draws a wall at its texture's colour scaled by its sector's
 * light, dark rooms readable and nothing brighter than the palette: the eye adapts (automatic
 * exposure), half a stop of compensation lifts the mid-tones toward where the game draws them, and
 * ACES's per-channel shoulder keeps saturated lamps and lava from clipping (Reinhard's, on luminance,
 * pushes their strong channel past 1). Measured on E1M1 over six views (docs/perf.md, "Exposure and
 * torch"): 14 % of pixels below 32/255 and 1.1 % clipped, against 47 % and 0.8 % at the fixed
 * exposure; with +1 stop and Reinhard 8 % and 9 %.
 */
const LOOK_SETTINGS: Record<Look, RenderSettingsPatch> = {
  doom: { exposureStops: 'auto', exposureCompensation: 0.5, toneMapper: 'aces', torch: { enabled: true } },
};

/** A look's settings, a fresh copy (callers may add to it). */
export function lookSettings(look: Look): RenderSettingsPatch {
  return structuredClone(LOOK_SETTINGS[look]);
}

export const isLook = (name: string): name is Look => (LOOKS as readonly string[]).includes(name);
