/**
 * The Doom loader's front door: a WAD stack and an optional map name in, a Scene out, with the
 * warnings and sector failures the builders reported. Also the per-map summary `lantern info`
 * prints. Pure, like every loader.
 */
import { LanternError } from '../../errors.ts';
import { WarningCap } from '../../budgets.ts';
import { DOOM_ANIMATIONS, readAnimatedLump, resolveCycles, type DoomCycles } from './animations.ts';
import type { LightTable } from './light-table.ts';
import { readMap } from './map-lumps.ts';
import type { SectorFailure } from './sectors.ts';
import { SpriteSet } from './sprites.ts';
import { DoomGraphics } from './textures.ts';
import type { ThingOptions } from './things.ts';
import { doomMapToScene, type DoomScene } from './to-scene.ts';
import type { MapInfo, WadStack } from './wad.ts';

export interface DoomLoadOptions {
  readonly lightTable?: Partial<LightTable>;
  readonly onWarning?: (message: string) => void;
  /** Reuse graphics across maps of the same stack (textures are composed once). */
  readonly graphics?: DoomGraphics;
  /** Reuse the sprite index and pictures across maps of the same stack. */
  readonly sprites?: SpriteSet;
  /** Which things appear: skill 1–5 (default 3), single player unless `multiplayer`. */
  readonly things?: ThingOptions;
}

export interface DoomLoad extends DoomScene {
  readonly map: MapInfo;
  readonly things: number;
  readonly linedefs: number;
}

/**
 * The stack's animated flats and textures: its BOOM ANIMATED lump's when it has one, else Doom's
 * built-in table (animations.ts), over the flats and textures in WAD order.
 */
export function doomCycles(stack: WadStack, graphics: DoomGraphics, onWarning?: (message: string) => void): DoomCycles {
  const lump = stack.lump('ANIMATED');
  const defs = lump ? readAnimatedLump(lump, `${stack.describe()}: ANIMATED`) : DOOM_ANIMATIONS;
  return resolveCycles(defs, { flats: graphics.flatNames(), textures: graphics.textureNames() }, onWarning);
}

/** Loads `mapName`, or the stack's first map when none is given. */
export function loadDoomMap(stack: WadStack, mapName: string | undefined, options: DoomLoadOptions = {}): DoomLoad {
  const maps = stack.maps();
  if (maps.length === 0) throw new LanternError(`${stack.describe()} has no maps`);
  const info = mapName === undefined ? maps[0]! : maps.find((m) => m.name === mapName.toUpperCase());
  if (!info) {
    throw new LanternError(`${stack.describe()} has no map '${mapName}'`, `Its maps are: ${maps.map((m) => m.name).join(', ')}`);
  }
  // Warnings of one kind are capped (a broken WAD once printed 119,996 lines); the closing lines say how many were held back.
  const cap = options.onWarning ? new WarningCap(options.onWarning) : undefined;
  const onWarning = cap?.warn;
  try {
    const map = readMap(stack, info.name, onWarning ? { onWarning } : {});
    const graphics = options.graphics ?? new DoomGraphics(stack, onWarning ? { onWarning } : {});
    const sky = graphics.sky(info.name);
    const sprites = options.sprites ?? new SpriteSet(stack, graphics.palette, onWarning, graphics.texels);
    const built = doomMapToScene(map, graphics, {
      sprites,
      ...(options.things ? { things: options.things } : {}),
      ...(sky ? { sky } : {}),
      cycles: doomCycles(stack, graphics, onWarning),
      ...(options.lightTable ? { lightTable: options.lightTable } : {}),
      ...(onWarning ? { onWarning } : {}),
    });
    return { ...built, map: info, things: map.things.length, linedefs: map.linedefs.length };
  } finally {
    cap?.finish();
  }
}

export interface MapSummary {
  readonly name: string;
  readonly format: MapInfo['format'];
  readonly things?: number;
  readonly linedefs?: number;
  readonly sectors?: number;
  readonly triangles?: number;
  readonly textures?: number;
  /** Things drawn (at the skill summarised), and those of them that give light. */
  readonly sprites?: number;
  readonly emittingSprites?: number;
  readonly failures?: readonly SectorFailure[];
  /** Why the map was not built (Hexen or UDMF format, a broken lump). */
  readonly error?: string;
}

/**
 * Every map of a stack with its counts (things drawn at `things`' skill, 3 by default); maps that
 * cannot be built say why instead of stopping the list.
 */
export function summarizeMaps(stack: WadStack, things: ThingOptions = {}): MapSummary[] {
  const graphics = new DoomGraphics(stack);
  const sprites = new SpriteSet(stack, graphics.palette, undefined, graphics.texels);
  return stack.maps().map((info) => {
    try {
      const m = loadDoomMap(stack, info.name, { graphics, sprites, things });
      return {
        name: info.name,
        format: info.format,
        things: m.things,
        linedefs: m.linedefs,
        sectors: m.stats.sectors,
        triangles: m.stats.triangles,
        textures: m.stats.textures,
        sprites: m.stats.sprites,
        emittingSprites: m.stats.emittingSprites,
        failures: m.failures,
      };
    } catch (e) {
      // Every map answers for itself: one that breaks the loader (a bug, or a stack overflow on a
      // hostile map) is listed with its error and the other maps are still summarised.
      const error = e instanceof LanternError ? e.userMessage : `internal error: ${e instanceof Error ? e.message : String(e)}`;
      return { name: info.name, format: info.format, error };
    }
  });
}
