/**
 * What gives light in a Doom map, and how bright it is.
 *
 * Doom has no light sources: each sector has a light level (0–255) and every surface in it is drawn
 * that bright. A path tracer needs emitters, so the textures that depict light (lamps, light
 * panels, glowing liquids, fire) emit, the sky emits, and the player carries a torch.
 *
 * Units. The reference is "full light": a surface whose outgoing radiance equals its texture's
 * linear colour, which is how Doom draws a wall near the viewer in a sector at light 255. A diffuse
 * surface looks like that when the light arriving at it is as if a uniform radiance of 1 surrounded
 * it (irradiance π). An emitter of strength s sends out s × its texture's linear colour: s times as
 * bright as a fully lit wall of the same colour. (Exposure is the renderer's business; these numbers
 * fix how the sources compare with each other and with the torch.)
 *
 * - Lamps and light panels: 16, the top of "5–20× a lit wall". A lamp has to be far brighter than
 *   what it lights: a 64×64 ceiling light 128 units above a 256×256 room lights the floor to about
 *   3 % of its own radiance on average (half its flux π·L·64² spread over 256²), so fixture-lit
 *   rooms come out dimmer than Doom draws them; the torch and bounce light make up some of it.
 *   Much higher strengths would make the dark frames of lamp textures glow as well, since emission
 *   follows the whole texture.
 * - Lava and fire: 8. Large areas, so a lower strength still lights the room red.
 * - Nukage and slime falls: 6. Doom's toxic pools glow too, but less.
 * - Blood, water and brown sludge: nothing. They are drawn bright in Doom only when the mapper
 *   gave their sector a high light level.
 * - Computer screens, switches, exit signs: nothing. Their lit parts are small, and emission
 *   follows the whole texture, so the metal around them would glow too.
 * - Light-giving things (thing-types.ts: floor lamps, torches, candles, the burning barrel), by
 *   sprite name: electric lamps as the lamp textures, flames at FIRE_THING_STRENGTH, bright texels
 *   only. Doom draws their frames full bright, so the sector's light level does not scale them, and
 *   both faces of the sprite emit.
 * - The sky: 5 (SKY_STRENGTH). An outdoor floor sees sky over roughly a third to two thirds of its
 *   hemisphere, so a sky of strength 5 lights it to about 0.5–1 of full light with a sky texture of
 *   daylight brightness (Freedoom's E1 sky averages 0.32 in linear terms): the sky itself reads
 *   brighter than the walls and dimmer than the lamps. A dark sky lights little, as it should
 *   (Freedoom 2's MAP01–11 dusk averages 0.03).
 *
 * Sector light levels scale the emitters of their sector by (level / 255)². Doom's light level is
 * close to a brightness as displayed (the COLORMAP fades palette colours toward black in steps,
 * in display values), and displayed values are roughly the square root of linear radiance (sRGB's
 * gamma is about 2.2). A lamp in a sector at 160 thus emits 0.39 of its full strength, so the light
 * it sheds, and the lamp itself, look about as much darker as Doom draws that sector. The sky is not
 * scaled: Doom draws it at full brightness everywhere.
 *
 * Names are those of the Doom and Doom II IWADs, which Freedoom fills with its own art, plus light
 * textures Freedoom adds; every name here is in freedoom1.wad or freedoom2.wad, and animated
 * textures list every frame. Callers may override any entry
 * (strength 0 turns one off) or add their own: the table is plain JSON.
 */
import { LanternError } from '../../errors.ts';
import { luminance, type Vec3 } from '../../math/vec3.ts';
import type { Texture, Torch } from '../../scene/types.ts';
import { lightGivingSprites } from './thing-types.ts';

export interface LightSource {
  /** Emitted radiance = strength × colour × texture colour (linear), at sector light 255. */
  readonly strength: number;
  /** Linear RGB tint, white by default. */
  readonly color?: readonly [number, number, number];
  /**
   * Only texels at least this fraction of the texture's brightest texel's luminance emit (0 or
   * absent: the whole texture). Lamps use it so the glass glows and the frame does not, which lets
   * the glass be as bright as a real fixture.
   */
  readonly glow?: number;
}

export interface LightTable {
  /** Wall textures (TEXTURE1/TEXTURE2 names). */
  readonly textures: Readonly<Record<string, LightSource>>;
  /** Flats, for floors and ceilings. */
  readonly flats: Readonly<Record<string, LightSource>>;
  /**
   * Things, by sprite name (CBRA, TLMP, ...: every frame and rotation of the sprite). Their emission
   * ignores the sector's light level (Doom draws these frames full bright), and both faces of the
   * sprite emit.
   */
  readonly things: Readonly<Record<string, LightSource>>;
}

/**
 * Lamps emit from their bright texels only (LAMP_GLOW), so they can be bright: the glass of a light
 * panel at sector light 255 shines at 48 × its texture colour, about 50× a lit wall.
 */
export const LAMP_STRENGTH = 48;
export const LAMP_GLOW = 0.6;
export const LAVA_STRENGTH = 8;
export const NUKAGE_STRENGTH = 6;
export const SKY_STRENGTH = 5;
/**
 * Flames on things (torches, candles, the burning barrel): only their bright texels emit (the
 * yellow-white of the flame, FIRE_GLOW of the brightest), at a third of a lamp's strength: a flame's
 * sprite is mostly flame, so more of it glows than of a lamp texture. Electric floor lamps are lamps.
 */
export const FIRE_THING_STRENGTH = 16;
export const FIRE_GLOW = 0.5;

const range = (prefix: string, from: number, to: number, digits = 1): string[] =>
  Array.from({ length: to - from + 1 }, (_, i) => `${prefix}${String(from + i).padStart(digits, '0')}`);

const LAMP_TEXTURES = [
  // Doom: light strips and panels in walls; BRICKLIT is Doom II's wall lamp.
  'LITE2', 'LITE3', 'LITE4', 'LITE5', 'LITE96', 'LITEMET', 'LITESTON', 'BRICKLIT',
  'LITEBLU1', 'LITEBLU2', 'LITEBLU3', 'LITEBLU4', 'LITERED',
  // More strips and panels found in Freedoom's IWADs (AQLITE04 is an ornament, not a light).
  'LITERED1', 'LITERED2', 'LITEYEL1', 'LITEYEL2', 'LITEYEL3', 'LITEGRN1',
  ...range('AQLITE', 1, 3, 2), ...range('AQLITE', 5, 25, 2),
];

const LAMP_FLATS = [
  // Ceiling lights and lit floor panels.
  'CEIL1_2', 'CEIL1_3', 'CEIL3_4', 'CEIL3_6', 'FLAT2', 'FLAT17', 'FLAT22', 'FLOOR1_7', 'GRNLITE1',
  'TLITE6_1', 'TLITE6_4', 'TLITE6_5', 'TLITE6_6',
];

/** Lava, and Doom II's animated lava among rocks (RROCK05–08, SLIME09–12). */
const LAVA_FLATS = [...range('LAVA', 1, 4), ...range('RROCK', 5, 8, 2), ...range('SLIME', 9, 12, 2)];
/** Doom II's fire walls. */
const FIRE_TEXTURES = ['FIRELAVA', 'FIRELAV2', 'FIRELAV3', 'FIREMAG1', 'FIREMAG2', 'FIREMAG3', 'FIREWALA', 'FIREWALB', 'FIREWALL', 'FIREBLU1', 'FIREBLU2'];
const NUKAGE_FLATS = range('NUKAGE', 1, 3);
/** Falling slime (green), Doom II. */
const NUKAGE_TEXTURES = range('SFALL', 1, 4);

const entries = (names: readonly string[], source: LightSource) => Object.fromEntries(names.map((n) => [n, source]));
const lamp: LightSource = { strength: LAMP_STRENGTH, glow: LAMP_GLOW };

const flame: LightSource = { strength: FIRE_THING_STRENGTH, glow: FIRE_GLOW };

export const DEFAULT_LIGHT_TABLE: LightTable = {
  textures: { ...entries(LAMP_TEXTURES, lamp), ...entries(FIRE_TEXTURES, { strength: LAVA_STRENGTH }), ...entries(NUKAGE_TEXTURES, { strength: NUKAGE_STRENGTH }) },
  flats: { ...entries(LAMP_FLATS, lamp), ...entries(LAVA_FLATS, { strength: LAVA_STRENGTH }), ...entries(NUKAGE_FLATS, { strength: NUKAGE_STRENGTH }) },
  // The light-giving things of thing-types.ts.
  things: Object.fromEntries([...lightGivingSprites()].map(([sprite, kind]) => [sprite, kind === 'lamp' ? lamp : flame])),
};

/**
 * The part of a texture that glows: texels whose linear luminance is at least `threshold` × the
 * brightest texel's keep their colour, the others turn black (alpha kept).
 */
export function glowTexture(texture: Texture, threshold: number): Texture {
  const lin = (c: number) => {
    const v = c / 255;
    return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
  };
  const n = texture.width * texture.height;
  const lum = new Float64Array(n);
  let max = 0;
  for (let i = 0; i < n; i++) {
    const p = i * 4;
    lum[i] = luminance([lin(texture.rgba[p]!), lin(texture.rgba[p + 1]!), lin(texture.rgba[p + 2]!)]);
    if (texture.rgba[p + 3]! >= 128 && lum[i]! > max) max = lum[i]!;
  }
  const rgba = new Uint8Array(texture.rgba);
  for (let i = 0; i < n; i++) {
    if (lum[i]! < threshold * max) rgba.fill(0, i * 4, i * 4 + 3);
  }
  return { name: `${texture.name}@glow`, width: texture.width, height: texture.height, rgba };
}

/** `base` with the entries of `overrides` replacing or adding to its own (names upper-cased). */
export function mergeLightTables(base: LightTable, overrides: Partial<LightTable> = {}): LightTable {
  const upper = (r: Readonly<Record<string, LightSource>> = {}) => Object.fromEntries(Object.entries(r).map(([k, v]) => [k.toUpperCase(), v]));
  return {
    textures: { ...base.textures, ...upper(overrides.textures) },
    flats: { ...base.flats, ...upper(overrides.flats) },
    things: { ...base.things, ...upper(overrides.things) },
  };
}

/**
 * A user's light table overrides from parsed JSON, checked: `{ "textures": { "NAME": { "strength": 48,
 * "color": [1, 0.9, 0.8], "glow": 0.6 } }, "flats": { ... }, "things": { "SPRITE": { ... } } }` (things
 * by their four-letter sprite name). Throws a LanternError naming the first bad entry.
 */
export function parseLightTable(json: unknown, source = 'light table'): Partial<LightTable> {
  const fail = (what: string): never => {
    throw new LanternError(`${source}: ${what}`, 'Expected { "textures": { "NAME": { "strength": 16, "color": [1, 1, 1], "glow": 0.6 } }, "flats": { ... }, "things": { "SPRITE": { ... } } }');
  };
  if (typeof json !== 'object' || json === null || Array.isArray(json)) fail('not a JSON object');
  const out: { textures?: Record<string, LightSource>; flats?: Record<string, LightSource>; things?: Record<string, LightSource> } = {};
  for (const [key, value] of Object.entries(json as Record<string, unknown>)) {
    if (key !== 'textures' && key !== 'flats' && key !== 'things') fail(`unknown key '${key}' (use "textures", "flats" and "things")`);
    if (typeof value !== 'object' || value === null || Array.isArray(value)) fail(`"${key}" must be an object of names`);
    const entries: Record<string, LightSource> = {};
    for (const [name, entry] of Object.entries(value as Record<string, unknown>)) {
      const e = entry as { strength?: unknown; color?: unknown; glow?: unknown };
      const where = `${key}.${name}`;
      if (typeof e !== 'object' || e === null) fail(`${where} must be an object`);
      if (typeof e.strength !== 'number' || !Number.isFinite(e.strength) || e.strength < 0) fail(`${where}.strength must be a number ≥ 0`);
      if (e.color !== undefined && !(Array.isArray(e.color) && e.color.length === 3 && e.color.every((c) => typeof c === 'number' && Number.isFinite(c) && c >= 0))) {
        fail(`${where}.color must be three numbers ≥ 0`);
      }
      if (e.glow !== undefined && !(typeof e.glow === 'number' && e.glow >= 0 && e.glow <= 1)) fail(`${where}.glow must be a number from 0 to 1`);
      entries[name.toUpperCase()] = {
        strength: e.strength as number,
        ...(e.color !== undefined ? { color: e.color as [number, number, number] } : {}),
        ...(e.glow !== undefined ? { glow: e.glow as number } : {}),
      };
    }
    out[key as 'textures' | 'flats' | 'things'] = entries;
  }
  return out;
}

/** How a sector's light level scales its emitters: (level / 255)², level clamped to 0–255. */
export function sectorLightFactor(level: number): number {
  const l = Math.min(255, Math.max(0, level)) / 255;
  return l * l;
}

/**
 * The emission colour (multiplying the texture) of a wall texture or flat in a sector at
 * `lightLevel`, or undefined when it does not emit.
 */
export function emissionOf(source: LightSource | undefined, lightLevel: number): Vec3 | undefined {
  if (!source || !(source.strength > 0)) return undefined;
  const s = source.strength * sectorLightFactor(lightLevel);
  if (!(s > 0)) return undefined;
  const [r, g, b] = source.color ?? [1, 1, 1];
  return [s * r, s * g, s * b];
}

/**
 * The torch the player carries: warm white, fading out by 1024 units, a 4-unit sphere for soft
 * shadows. Its intensity makes a wall facing it at 181 units (the geometric mean of 128 and 256) as
 * bright as a sector at light 160 in the units above: radiance = albedo × I·window(d) / (π d²) must
 * equal albedo × (160/255)², for the torch colour's luminance. Nearer walls get brighter and farther
 * ones darker with 1/d², within a factor of two of that over 128–256 units.
 */
const TORCH_COLOR: Vec3 = [1, 0.86, 0.66];
const TORCH_RANGE = 1024;
const TORCH_REFERENCE_DISTANCE = Math.sqrt(128 * 256);
/** The torch's smooth range window (shaders/scene/torch.wgsl). */
const torchWindow = (d: number) => (1 - (d / TORCH_RANGE) ** 4) ** 2;

export const DOOM_TORCH: Torch = {
  color: TORCH_COLOR,
  intensity:
    (sectorLightFactor(160) * Math.PI * TORCH_REFERENCE_DISTANCE ** 2) / torchWindow(TORCH_REFERENCE_DISTANCE) / luminance(TORCH_COLOR),
  range: TORCH_RANGE,
  radius: 4,
};
