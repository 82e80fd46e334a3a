/**
 * The machinery of the settings schema: a setting is declared once (its type, default, one valid
 * range, description, the mode it applies to, CLI flag, link parameter, panel hint) in a table, and
 * everything else is derived from that declaration here: the TypeScript type, the defaults,
 * validation, and the text form that the CLI and the links share. The tables: RENDER_SETTINGS of
 * settings.ts (the renderer's), VIEWER_SETTINGS of app/viewer-settings.ts (the page's own). Pure: no
 * DOM, no node:*, no commander; the front ends (cli/setting-options.ts, app/view-params.ts,
 * app/panel.ts) adapt it.
 */
import { LanternError } from '../errors.ts';

/** The value types a setting can have; each one is handled by an exhaustive switch below. */
export const SETTING_TYPES = ['integer', 'number', 'boolean', 'choice', 'color', 'number-or-auto', 'integer-or-unlimited', 'numbers', 'text'] as const;
export type SettingType = (typeof SETTING_TYPES)[number];

/** The folders of the viewer's panel that settings go into, in the panel's order ('camera': Camera and torch). */
export const PANEL_FOLDERS = ['render', 'camera', 'environment', 'exposure', 'denoise', 'hybrid', 'debug'] as const;
export type PanelFolder = (typeof PANEL_FOLDERS)[number];

/**
 * The modes a setting may apply to alone: 'frame', the real-time frame (`render --frames`, `--path`,
 * a real-time switch, or the hybrid recipe); 'hybrid', the hybrid recipe. A setting without one
 * applies in every mode.
 */
export const SETTING_MODES = ['frame', 'hybrid'] as const;
export type SettingMode = (typeof SETTING_MODES)[number];

/** How the help and the tooltips name a mode before a setting's description ('frame mode: …'). */
const MODE_WORDS: Readonly<Record<SettingMode, string>> = { frame: 'frame mode', hybrid: 'hybrid' };

export interface CliHint {
  /** The long flag, e.g. '--bounces'. Scripts depend on it: never rename one. */
  readonly flag: string;
  readonly short?: string;
  /** What the help shows as the argument, e.g. '<n>' (default: one derived from the type). */
  readonly argument?: string;
  /** Booleans only: a flag without a value, true when given and false when not. */
  readonly switch?: boolean;
  /** Choices only: the values the CLI offers, when it offers fewer than the setting has. */
  readonly values?: readonly string[];
}

export interface PanelHint {
  readonly folder: PanelFolder;
  readonly label: string;
  readonly step?: number;
  /**
   * The span the slider covers where it is narrower than the valid range (typed values anywhere in
   * the valid range are still accepted: a slider over 0–1024 bounces would be useless at 0–8).
   */
  readonly slider?: readonly [number, number];
  /** 'integer-or-unlimited' only: the label of the checkbox that chooses 'unlimited'. */
  readonly unlimitedLabel?: string;
}

interface Common {
  /** How messages name the setting: 'bounces', 'torch intensity'. */
  readonly name: string;
  /**
   * One line: the CLI's help text and the documentation. It leaves out the mode: settingDescription
   * puts `mode` before it ('frame mode: …').
   */
  readonly description: string;
  /** The mode the setting applies to alone (absent: every mode); `lantern render` refuses it outside that mode. */
  readonly mode?: SettingMode;
  readonly cli?: CliHint;
  /** The URL parameter of the viewer's links. Saved links depend on it: never rename one. */
  readonly link?: string;
  /** True where changing the setting changes the estimate itself (accumulation restarts). */
  readonly restarts: boolean;
  readonly panel?: PanelHint;
}

/** Inclusive bounds; `above` makes the lower one exclusive (for 'a positive number'). */
interface Bounds {
  readonly min: number;
  readonly max: number;
  readonly above?: boolean;
}

/** One component of a 'numbers' setting: its name in messages and its own bounds. */
export interface Component extends Bounds {
  readonly name: string;
}

export type SettingSpec =
  | (Common & Bounds & { readonly type: 'integer' | 'number' | 'number-or-auto' | 'integer-or-unlimited' | 'color'; readonly default?: unknown })
  | (Common & { readonly type: 'boolean'; readonly words: readonly [off: string, on: string]; readonly default?: unknown })
  | (Common & { readonly type: 'choice'; readonly values: readonly string[]; readonly default?: unknown })
  /** Comma-separated numbers, each with its own range; the first `required` must be given, the rest may be left off. */
  | (Common & { readonly type: 'numbers'; readonly components: readonly Component[]; readonly required: number; readonly default?: unknown })
  /** A non-empty string (a file name, a URL); `accepts` says what in messages, `pattern` checks it. */
  | (Common & { readonly type: 'text'; readonly accepts: string; readonly pattern?: RegExp; readonly default?: unknown });

/**
 * One declared setting. T is its value's type and O whether it may be absent (an optional setting
 * has no default: its absence means "not overridden", as the torch's colour does).
 */
export interface Setting<T, O extends boolean = false> {
  readonly spec: SettingSpec;
  readonly optional: O;
  /** Never set: carries T for the type derivation. */
  readonly valueType?: T;
}

export interface SettingGroup {
  readonly [key: string]: Setting<unknown, boolean> | SettingGroup;
}

type ValueOf<X> = X extends Setting<infer T, boolean> ? T : X extends SettingGroup ? SettingsOf<X> : never;
type Flatten<T> = { [K in keyof T]: T[K] };

/** The settings object a schema describes: optional settings become optional properties. */
export type SettingsOf<G extends SettingGroup> = Flatten<
  { readonly [K in keyof G as G[K] extends Setting<unknown, true> ? never : K]: ValueOf<G[K]> } & {
    readonly [K in keyof G as G[K] extends Setting<unknown, true> ? K : never]?: ValueOf<G[K]>;
  }
>;

/** A change to some settings: any subset, nested groups included. */
export type SettingsPatch<S> = { readonly [K in keyof S]?: S[K] extends readonly unknown[] ? S[K] : S[K] extends object ? SettingsPatch<S[K]> : S[K] };

type NoDefault<T> = Omit<T, 'default' | 'type'>;

// The builders: each fixes the value type that SettingsOf reads.
export const integer = (s: NoDefault<Common & Bounds> & { default: number }): Setting<number> => ({ spec: { ...s, type: 'integer' }, optional: false });
export const number = (s: NoDefault<Common & Bounds> & { default: number }): Setting<number> => ({ spec: { ...s, type: 'number' }, optional: false });
export const numberOrAuto = (s: NoDefault<Common & Bounds> & { default: number | 'auto' }): Setting<number | 'auto'> => ({ spec: { ...s, type: 'number-or-auto' }, optional: false });
export const integerOrUnlimited = (s: NoDefault<Common & Bounds> & { default: number | 'unlimited' }): Setting<number | 'unlimited'> => ({
  spec: { ...s, type: 'integer-or-unlimited' },
  optional: false,
});
export const boolean = (s: NoDefault<Common> & { words: readonly [string, string]; default: boolean }): Setting<boolean> => ({ spec: { ...s, type: 'boolean' }, optional: false });
export const choice = <const V extends readonly string[]>(values: V, s: NoDefault<Common> & { default: V[number] }): Setting<V[number]> => ({
  spec: { ...s, type: 'choice', values },
  optional: false,
});
/** A linear RGB triple, each component within the bounds. */
export const color = (s: NoDefault<Common & Bounds> & { default: readonly [number, number, number] }): Setting<readonly [number, number, number]> => ({
  spec: { ...s, type: 'color' },
  optional: false,
});
/**
 * Comma-separated numbers with their own ranges, e.g. a sky's elevation,azimuth[,turbidity]:
 * components after the first `required` may be left off (the consumer gives them their defaults).
 */
export const numbers = (s: NoDefault<Common> & { components: readonly Component[]; required: number; default: readonly number[] }): Setting<readonly number[]> => ({
  spec: { ...s, type: 'numbers' },
  optional: false,
});
/** A non-empty string such as a file name or URL (what it names is the consumer's to check). */
export const text = (s: NoDefault<Common> & { accepts: string; pattern?: RegExp; default: string }): Setting<string> => ({ spec: { ...s, type: 'text' }, optional: false });
/** The same setting without a default: absent means "not overridden". */
export const optional = <T>(setting: Setting<T>): Setting<T, true> => {
  const { default: _, ...spec } = setting.spec;
  return { spec: spec as SettingSpec, optional: true };
};

/** A leaf of the schema with where it sits: path ['torch', 'intensity'], id 'torch.intensity'. */
export interface SettingEntry {
  readonly path: readonly string[];
  readonly id: string;
  readonly spec: SettingSpec;
  readonly optional: boolean;
}

const isSetting = (x: Setting<unknown, boolean> | SettingGroup): x is Setting<unknown, boolean> => 'spec' in x && typeof x.spec === 'object' && x.spec !== null && 'type' in x.spec;

/** Every setting of the schema in declaration order (the order of the help, links and panel). */
export function flattenSchema(group: SettingGroup, prefix: readonly string[] = []): SettingEntry[] {
  return Object.entries(group).flatMap(([key, node]) => {
    const path = [...prefix, key];
    return isSetting(node) ? [{ path, id: path.join('.'), spec: node.spec, optional: node.optional }] : flattenSchema(node, path);
  });
}

/** The value at a path of a nested object, or undefined where any step is missing. */
export function getAt(object: unknown, path: readonly string[]): unknown {
  let at = object;
  for (const key of path) {
    if (typeof at !== 'object' || at === null) return undefined;
    at = (at as Record<string, unknown>)[key];
  }
  return at;
}

/** Sets a value at a path, creating the groups on the way (mutates `object`). */
export function setAt(object: Record<string, unknown>, path: readonly string[], value: unknown): void {
  let at = object;
  path.forEach((key, i) => {
    if (i === path.length - 1) at[key] = value;
    else at = (at[key] ??= {}) as Record<string, unknown>;
  });
}

/** The defaults, frozen, nested as the schema is; optional settings are absent. */
export function defaultsOf<G extends SettingGroup>(group: G): SettingsOf<G> {
  const out: Record<string, unknown> = {};
  for (const [key, node] of Object.entries(group)) {
    if (!isSetting(node)) out[key] = defaultsOf(node);
    else if (!node.optional) out[key] = node.spec.default;
  }
  return Object.freeze(out) as SettingsOf<G>;
}

/** `base` with a patch applied: groups are merged (a torch patch keeps the torch's other fields). */
export function mergeSettings<S>(base: S, patch: SettingsPatch<S>): S {
  const out: Record<string, unknown> = { ...(base as Record<string, unknown>) };
  for (const [key, value] of Object.entries(patch as Record<string, unknown>)) {
    if (value === undefined) continue;
    const old = out[key];
    const isGroup = (v: unknown) => typeof v === 'object' && v !== null && !Array.isArray(v);
    out[key] = isGroup(value) && isGroup(old) ? mergeSettings(old, value as SettingsPatch<unknown>) : value;
  }
  return out as S;
}

/** A setting's description as the help and the panel's tooltips give it: the mode it applies to first, where it has one. */
export function settingDescription(spec: SettingSpec): string {
  return spec.mode ? `${MODE_WORDS[spec.mode]}: ${spec.description}` : spec.description;
}

const plain = (n: number) => String(n);

/** The values a setting accepts, as the end of "… must be ___": shared by every message. */
export function describeValues(spec: SettingSpec): string {
  const bounds = (b: Bounds, whole: boolean) => {
    const kind = whole ? 'a whole number' : 'a number';
    if (b.max === Infinity && b.min === 0) return b.above ? `a positive ${whole ? 'whole ' : ''}number` : `a non-negative ${whole ? 'whole ' : ''}number`;
    if (b.max === Infinity) return `${kind} ${b.above ? 'above' : 'from'} ${plain(b.min)}`;
    return `${kind} ${b.above ? 'above' : 'from'} ${plain(b.min)} ${b.above ? 'up ' : ''}to ${plain(b.max)}`;
  };
  switch (spec.type) {
    case 'integer':
      return bounds(spec, true);
    case 'number':
      return bounds(spec, false);
    case 'number-or-auto':
      return `${bounds(spec, false)} or 'auto'`;
    case 'integer-or-unlimited':
      return `${bounds(spec, true)}, or 'unlimited'`;
    case 'color':
      return `three comma-separated numbers, each ${bounds(spec, false).replace(/^a /, '')}`;
    case 'boolean':
      return `${spec.words[1]} or ${spec.words[0]}`;
    case 'choice':
      return `one of ${spec.values.join(', ')}`;
    case 'numbers': {
      const names = spec.components.map((c, i) => (i < spec.required ? c.name : `[${c.name}]`)).join(',').replace(/,\[/g, '[,');
      return `${names}: ${spec.components.map((c) => `${c.name} ${bounds(c, false).replace(/^a number /, '')}`).join(', ')}`;
    }
    case 'text':
      return spec.accepts;
  }
}

const inBounds = (b: Bounds, n: number, whole: boolean) => Number.isFinite(n) && (!whole || Number.isInteger(n)) && (b.above ? n > b.min : n >= b.min) && n <= b.max;

/** Whether a value (not text) is valid for the setting. */
export function isValidValue(spec: SettingSpec, value: unknown): boolean {
  switch (spec.type) {
    case 'integer':
      return typeof value === 'number' && inBounds(spec, value, true);
    case 'number':
      return typeof value === 'number' && inBounds(spec, value, false);
    case 'number-or-auto':
      return value === 'auto' || (typeof value === 'number' && inBounds(spec, value, false));
    case 'integer-or-unlimited':
      return value === 'unlimited' || (typeof value === 'number' && inBounds(spec, value, true));
    case 'color':
      return Array.isArray(value) && value.length === 3 && value.every((c) => typeof c === 'number' && inBounds(spec, c, false));
    case 'boolean':
      return typeof value === 'boolean';
    case 'choice':
      return typeof value === 'string' && spec.values.includes(value);
    case 'numbers':
      return (
        Array.isArray(value) &&
        value.length >= spec.required &&
        value.length <= spec.components.length &&
        value.every((v, i) => typeof v === 'number' && inBounds(spec.components[i]!, v, false))
      );
    case 'text':
      return typeof value === 'string' && value.trim() !== '' && (!spec.pattern || spec.pattern.test(value));
  }
}

/** Refuses an invalid settings object with a LanternError that names the setting and what it accepts. */
export function validateAgainst(entries: readonly SettingEntry[], settings: unknown): void {
  for (const { path, spec, optional } of entries) {
    const value = getAt(settings, path);
    if (optional && value === undefined) continue;
    if (isValidValue(spec, value)) continue;
    if (spec.type === 'choice') throw new LanternError(`unknown ${spec.name} '${String(value)}'`, `Use one of: ${spec.values.join(', ')}`);
    // A value in code is true or false, whatever words the CLI and links use for it.
    const accepted = spec.type === 'boolean' ? 'true or false' : describeValues(spec);
    throw new LanternError(`${spec.name} must be ${accepted}, not ${Array.isArray(value) ? value.join(', ') : String(value)}`);
  }
}

// Links written before the schema spelled booleans 0/1 or on/off; any of these words is understood.
const TRUE_WORDS = ['1', 'on', 'true', 'yes'];
const FALSE_WORDS = ['0', 'off', 'false', 'no'];

/** A number as the CLI and links write it: a plain decimal, nothing else ('0x10', '1e', '' are refused). */
function parseNumber(text: string): number | undefined {
  const t = text.trim();
  if (!/^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i.test(t)) return undefined;
  const n = Number(t);
  return Number.isFinite(n) ? n : undefined;
}

/**
 * A setting's value from its text form (a CLI argument or a link parameter), or why not. The CLI and
 * the links share this, so they accept exactly the same values.
 */
export function parseSettingText(spec: SettingSpec, text: string): { ok: true; value: unknown } | { ok: false; problem: string } {
  const value = textToValue(spec, text.trim());
  return value !== undefined && isValidValue(spec, value) ? { ok: true, value } : { ok: false, problem: `must be ${describeValues(spec)}` };
}

function textToValue(spec: SettingSpec, text: string): unknown {
  switch (spec.type) {
    case 'integer':
    case 'number':
      return parseNumber(text);
    case 'number-or-auto':
      return text === 'auto' ? 'auto' : parseNumber(text);
    case 'integer-or-unlimited':
      return text === 'unlimited' ? 'unlimited' : parseNumber(text);
    case 'color': {
      const parts = text.split(',').map(parseNumber);
      return parts.length === 3 && parts.every((p) => p !== undefined) ? parts : undefined;
    }
    case 'boolean': {
      const word = text.toLowerCase();
      if (word === spec.words[1] || TRUE_WORDS.includes(word)) return true;
      if (word === spec.words[0] || FALSE_WORDS.includes(word)) return false;
      return undefined;
    }
    case 'choice':
    case 'text':
      return text;
    case 'numbers': {
      const parts = text.split(',').map(parseNumber);
      return parts.every((p) => p !== undefined) ? parts : undefined;
    }
    default:
      // Exhaustive: a new setting type fails to compile here until it has a text form.
      return ((t: never) => t)(spec);
  }
}

// Twelve significant digits: a slider's float noise (1.2500000000000002) goes, any value a person
// types survives, and a small value stays itself (fixed decimals would turn 1e-6 into 0, out of range).
const short = (n: number) => String(Number(n.toPrecision(12)));

/** The text form of a value: what a link carries and what the CLI's help shows as the default. */
export function formatSettingText(spec: SettingSpec, value: unknown): string {
  switch (spec.type) {
    case 'integer':
    case 'integer-or-unlimited':
    case 'choice':
      return String(value);
    case 'number':
    case 'number-or-auto':
      return typeof value === 'number' ? short(value) : String(value);
    case 'color':
    case 'numbers':
      return (value as readonly number[]).map(short).join(',');
    case 'text':
      return String(value);
    case 'boolean':
      return value ? spec.words[1] : spec.words[0];
  }
}
