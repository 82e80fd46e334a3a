/**
 * Looks: one-click sets of display settings (the panel's buttons, the link's `look=`). A look changes
 * only how the image is exposed and shown, and puts the torch back to the scene's own; links and
 * flags given beside it win.
 */
import type { RenderSettingsPatch } from './settings.ts';

export const LOOKS = ['doom'] as const;
export type Look = (typeof LOOKS)[number];

/**
 * 'doom': the game's brightness. Doom draws a wall at its texture's colour scaled by the sector's
 * light and nothing brighter than the palette allows: the eye adapts (automatic exposure), the
 * compensation lifts the mid-tones to where the game draws them, and Reinhard's curve rolls lamps
 * off instead of clipping them (measured on E1M1: docs/perf.md, "Exposure and torch").
 */
const LOOK_SETTINGS: Record<Look, RenderSettingsPatch> = {
  doom: { exposureStops: 'auto', exposureCompensation: 1, toneMapper: 'reinhard', torch: { enabled: true } },
};

/** A look's settings, a fresh copy (callers may add to it). */
export function lookSettings(look: Look): RenderSettingsPatch {
  return structuredClone(LOOK_SETTINGS[look]);
}

export const isLook = (name: string): name is Look => (LOOKS as readonly string[]).includes(name);
