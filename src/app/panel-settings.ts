/**
 * Which render settings the panel shows and with what Tweakpane limits, from their schema entries.
 * Pure (no Tweakpane, no DOM), so that a unit test can hold the panel's ranges to the schema's.
 */
import type { SettingEntry } from '../renderer/settings-schema.ts';
import { SETTING_ENTRIES } from '../renderer/settings.ts';

/** The settings the panel shows. */
export const PANEL_SETTINGS: readonly SettingEntry[] = SETTING_ENTRIES.filter((e) => e.spec.panel !== undefined);

/** A bound setting's key in the panel's own object: for 'integer-or-unlimited', the key of its checkbox. */
export const unlimitedKey = (id: string) => `${id}#unlimited`;

/**
 * The Tweakpane parameters of a numeric setting: the schema's limits constrain what is accepted (typed
 * values too); `slider` is the span the slider covers, narrower where the valid range is too wide to drag.
 */
export function numberBindingLimits(entry: SettingEntry): { min?: number; max?: number; step?: number; slider?: readonly [number, number] } {
  const spec = entry.spec;
  if (spec.type === 'boolean' || spec.type === 'choice' || spec.type === 'color' || spec.type === 'numbers' || spec.type === 'text') return {};
  const hint = spec.panel;
  return {
    // An exclusive lower bound cannot be a Tweakpane limit: such values are refused when applied instead.
    ...(Number.isFinite(spec.min) && !spec.above ? { min: spec.min } : {}),
    // 'auto' is shown as the exclusive lower bound (0 for the heat maximum), so that bound must be enterable.
    ...(spec.type === 'number-or-auto' && spec.above ? { min: spec.min } : {}),
    ...(Number.isFinite(spec.max) ? { max: spec.max } : {}),
    ...(hint?.step !== undefined ? { step: hint.step } : {}),
    ...(hint?.slider ? { slider: hint.slider } : {}),
  };
}
