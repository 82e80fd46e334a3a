/**
 * The scene half of the page's URL contract, shared by the page (app/view-params.ts) and
 * `lantern view`, which writes the link: `scene=<built-in>`, or a format's own parameter naming
 * served files (`wad=<url>[&wad=<url>…]&map=E1M1`, `ply=<url>`), taken from the registry so that a
 * new format brings its parameter with it, and `skill=1..5` (Doom maps: which things appear; other
 * formats ignore it). Pure: URLSearchParams in and out.
 */
import { FORMATS, formatById } from './registry.ts';

export type SceneLocation =
  | { readonly kind: 'builtin'; readonly name: string }
  /** Files the server offers: `format` is a registry id; `part` a map of a WAD; `skill` Doom's skill level (LoadOptions.skill). */
  | { readonly kind: 'files'; readonly format: string; readonly urls: readonly string[]; readonly part?: string; readonly skill?: number };

/** The link's skill level: a digit 1–5, anything else ignored. */
const SKILL = /^[1-5]$/;

export function parseSceneLocation(params: URLSearchParams): SceneLocation | undefined {
  for (const format of FORMATS) {
    const all = params.getAll(format.linkParam);
    if (all.length === 0) continue;
    // A format of one file per scene takes the first; extra copies of the parameter are ignored.
    const urls = format.stacks ? all : all.slice(0, 1);
    const part = format.part ? params.get(format.part.linkParam) : null;
    const normalize = format.part?.normalize ?? ((name: string) => name);
    const skill = params.get('skill');
    return { kind: 'files', format: format.id, urls, ...(part ? { part: normalize(part) } : {}), ...(skill && SKILL.test(skill) ? { skill: Number(skill) } : {}) };
  }
  const scene = params.get('scene');
  return scene ? { kind: 'builtin', name: scene } : undefined;
}

export function formatSceneLocation(location: SceneLocation, into: URLSearchParams = new URLSearchParams()): URLSearchParams {
  if (location.kind === 'builtin') {
    into.set('scene', location.name);
    return into;
  }
  const format = formatById(location.format);
  if (!format) throw new Error(`no format '${location.format}' in the registry`);
  for (const url of location.urls) into.append(format.linkParam, url);
  if (location.part && format.part) into.set(format.part.linkParam, location.part);
  if (location.skill !== undefined) into.set('skill', String(location.skill));
  return into;
}
