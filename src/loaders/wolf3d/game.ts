/**
 * One installation's data as a WolfGame: MAPHEAD, GAMEMAPS and VSWAP read and checked up front
 * (headers and tables), maps and pages decoded when first asked for and kept. Pure.
 */
import { LanternError } from '../../errors.ts';
import type { NamedBytes } from '../format.ts';
import { listMaps, mapIndexOf, readMap, readMapHead } from './maps.ts';
import { gamePalette } from './palette.ts';
import type { WolfGame, WolfGraphics, WolfImage, WolfMap } from './types.ts';
import { decodeSprite, decodeWall, readVswap } from './vswap.ts';

export interface WolfFiles {
  readonly maphead: NamedBytes;
  readonly gamemaps: NamedBytes;
  readonly vswap: NamedBytes;
}

/** The extension of a file name, without the dot, upper case ('' for none). */
export function extensionOf(name: string): string {
  const base = name.slice(Math.max(name.lastIndexOf('/'), name.lastIndexOf('\\')) + 1);
  const dot = base.lastIndexOf('.');
  return dot < 0 ? '' : base.slice(dot + 1).toUpperCase();
}

export function readWolfGame(files: WolfFiles): WolfGame {
  const extension = extensionOf(files.maphead.name);
  for (const f of [files.gamemaps, files.vswap]) {
    if (extensionOf(f.name) !== extension) {
      throw new LanternError(`${files.maphead.name} and ${f.name} are not of one game (extensions .${extension} and .${extensionOf(f.name)})`, 'Use MAPHEAD, GAMEMAPS and VSWAP of one installation: all .WL1 (shareware) or all .WL6');
    }
  }
  const head = readMapHead(files.maphead);
  const maps = listMaps(head, files.gamemaps);
  if (maps.length === 0) throw new LanternError(`${files.maphead.name} lists no maps`, 'the file is damaged; use the files of one installation of the game');
  const vswap = readVswap(files.vswap);
  const palette = gamePalette();
  const decodedMaps = new Map<number, WolfMap>();
  const walls = new Map<number, WolfImage>();
  const sprites = new Map<number, WolfImage>();
  const cached = <T>(cache: Map<number, T>, key: number, make: () => T): T => {
    let value = cache.get(key);
    if (value === undefined) {
      value = make();
      cache.set(key, value);
    }
    return value;
  };
  const graphics: WolfGraphics = {
    palette,
    wallCount: vswap.spriteStart,
    wall: (page) => cached(walls, page, () => decodeWall(vswap, page, palette)),
    spriteCount: vswap.soundStart - vswap.spriteStart,
    sprite: (index) => cached(sprites, index, () => decodeSprite(vswap, index, palette)),
  };
  return {
    extension,
    maps,
    // A number is a map's `index` (MAPHEAD's slot, as WolfMapInfo.index), not its place in `maps`.
    map(idOrIndex) {
      const index = typeof idOrIndex === 'number' ? idOrIndex : mapIndexOf(idOrIndex);
      const info = maps.find((m) => m.index === index);
      if (!info) {
        throw new LanternError(`${files.gamemaps.name} has no map ${typeof idOrIndex === 'number' ? `number ${idOrIndex + 1}` : `'${idOrIndex}'`}`, `Its maps are: ${maps.map((m) => m.id).join(', ')}`);
      }
      return cached(decodedMaps, info.index, () => readMap(head, files.gamemaps, info.index));
    },
    graphics,
  };
}
