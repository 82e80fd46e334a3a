/**
 * The Doom-format map lumps as plain data, in the map's own units and coordinates (x east, y north,
 * heights up). The contract between the lump parser (map-lumps.ts) and the geometry builders
 * (sectors, walls, to-scene). See the Doom specs: https://doomwiki.org/wiki/Map_format
 */

export interface MapVertex {
  readonly x: number;
  readonly y: number;
}

/** Linedef flags (https://doomwiki.org/wiki/Linedef#Linedef_flags). */
export const LINEDEF_FLAGS = {
  BLOCKING: 0x0001,
  BLOCK_MONSTERS: 0x0002,
  TWO_SIDED: 0x0004,
  UPPER_UNPEGGED: 0x0008,
  LOWER_UNPEGGED: 0x0010,
  SECRET: 0x0020,
  BLOCK_SOUND: 0x0040,
  NOT_ON_MAP: 0x0080,
  ALREADY_ON_MAP: 0x0100,
} as const;

/** Marks an absent sidedef in a linedef (0xFFFF in the lump). */
export const NO_SIDEDEF = -1;

export interface Linedef {
  readonly v1: number;
  readonly v2: number;
  readonly flags: number;
  readonly special: number;
  readonly tag: number;
  /** Sidedef on the right of v1 -> v2, or NO_SIDEDEF. */
  readonly front: number;
  /** Sidedef on the left, or NO_SIDEDEF. */
  readonly back: number;
}

export interface Sidedef {
  readonly xOffset: number;
  readonly yOffset: number;
  /** Texture names, upper-cased, trimmed; '-' (or empty) means none. */
  readonly upper: string;
  readonly lower: string;
  readonly middle: string;
  readonly sector: number;
}

export interface Sector {
  readonly floorHeight: number;
  readonly ceilingHeight: number;
  /** Flat names, upper-cased, trimmed. */
  readonly floorFlat: string;
  readonly ceilingFlat: string;
  /** 0..255. */
  readonly lightLevel: number;
  readonly special: number;
  readonly tag: number;
}

export interface Thing {
  readonly x: number;
  readonly y: number;
  /** Degrees, 0 = east, 90 = north. */
  readonly angle: number;
  readonly type: number;
  readonly flags: number;
}

export interface DoomMap {
  /** Lump name of the map marker: 'E1M1', 'MAP01', ... */
  readonly name: string;
  readonly vertices: readonly MapVertex[];
  readonly linedefs: readonly Linedef[];
  readonly sidedefs: readonly Sidedef[];
  readonly sectors: readonly Sector[];
  readonly things: readonly Thing[];
}

/** The flat name Doom draws as sky (ceilings and, rarely, floors). */
export const SKY_FLAT = 'F_SKY1';
/** Thing type of player 1's start. */
export const PLAYER1_START = 1;
/** Eye height above the floor in map units (Doom's VIEWHEIGHT). */
export const EYE_HEIGHT = 41;

/**
 * Where the geometry builders get images from (implemented by the WAD graphics code, textures.ts).
 * Names are upper-cased lump or texture names; undefined when the WAD has no such image.
 */
export interface DoomImageSource {
  /** A wall texture composed from patches (TEXTURE1/TEXTURE2 + PNAMES). */
  texture(name: string): import('../../scene/types.ts').Texture | undefined;
  /** A 64×64 flat from between F_START and F_END. */
  flat(name: string): import('../../scene/types.ts').Texture | undefined;
}
