/**
 * Wolfenstein 3D's data as the loader decodes it: the maps of GAMEMAPS (through MAPHEAD) and the
 * wall and sprite pages of VSWAP, coloured by the game palette. The readers (maps.ts, vswap.ts,
 * palette.ts) produce it; to-scene.ts turns one map into a Scene. Pure.
 */

/** Where a map is listed: its number in GAMEMAPS and the names it goes by. */
export interface WolfMapInfo {
  /** 0-based index in MAPHEAD's offset table. */
  readonly index: number;
  /** `E1L1`: episode floor(index / 10) + 1, level index % 10 + 1 (the game's 10 maps per episode). */
  readonly id: string;
  /** The name stored in the map's header ("Wolf1 Map1"). */
  readonly title: string;
  readonly width: number;
  readonly height: number;
}

/** One map, decompressed (Carmack, then RLEW with MAPHEAD's tag). */
export interface WolfMap extends WolfMapInfo {
  /**
   * The three planes, width × height words each, row-major from the map's top-left (index
   * y · width + x; y grows southward, x eastward, as the game's tilemap[x][y] does):
   * 0 = walls, doors and floor codes (areas); 1 = objects (player start, statics, actors, push-wall
   * markers); 2 = unused by the game (kept for completeness).
   */
  readonly planes: readonly [Uint16Array, Uint16Array, Uint16Array];
}

/** A 64 × 64 picture in RGBA8, rows from the top, columns from the left. */
export interface WolfImage {
  readonly width: number;
  readonly height: number;
  /** width · height · 4 bytes; alpha is 255 on wall pages, 0 where a sprite has no post. */
  readonly rgba: Uint8Array;
}

/** VSWAP's graphics, coloured by the palette. */
export interface WolfGraphics {
  /** 768 bytes: 256 colours × 8-bit RGB (the game's 6-bit VGA values scaled to 0–255). */
  readonly palette: Uint8Array;
  /** Wall pages: page 2k is wall k's light side (north and south faces), 2k + 1 its dark side (east and west faces). */
  readonly wallCount: number;
  wall(page: number): WolfImage;
  /** Sprite pages, numbered from VSWAP's sprite start (0 = the first sprite page). */
  readonly spriteCount: number;
  sprite(index: number): WolfImage;
}

/** One game's data: the files of one installation (`.WL1` shareware, `.WL6` registered). */
export interface WolfGame {
  /** The files' extension without the dot, upper case: 'WL1' or 'WL6'. */
  readonly extension: string;
  readonly maps: readonly WolfMapInfo[];
  /** Decodes a map by its id (`E1L1`) or listed index; throws LanternError naming the problem. */
  map(idOrIndex: string | number): WolfMap;
  readonly graphics: WolfGraphics;
}
