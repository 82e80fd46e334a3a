/**
 * What the numbers in a Wolfenstein 3D map's planes mean, from the game's source (v1.4: WL_GAME.C
 * SetupGameLevel and ScanInfoPlane, WL_ACT1.C statinfo and SpawnDoor, WL_DRAW.C's wall and door
 * pages). Pure.
 *
 * Plane 0 (walls):
 * - 1–63: a wall; wall k = code − 1 shows wall page 2k on its north and south faces (the light
 *   side) and 2k + 1 on its east and west faces (the dark side), as SetupWalls' horizwall and
 *   vertwall say. Other codes below AREATILE (64–89, 102–105) are walls to the game too, but have no
 *   pages of their own: the loader warns and draws them plain.
 * - 90–101: doors. Even codes are "vertical" doors (the panel runs north–south: one walks through
 *   east–west), odd codes "horizontal" ones; (code − 90) >> 1 is the lock: 0 none, 1–4 keys (gold,
 *   silver; 3 and 4 unused), 5 the elevator's door.
 * - 106 (AMBUSHTILE), 107 and up (AREATILE + area number), and 0: open floor.
 *
 * Door pages (WL_DRAW.C, DOORWALL = the number of wall pages − 8): DOORWALL + 0 and + 1 are the
 * plain door as a horizontal and as a vertical door shows it (the light and the dark side), + 2 and
 * + 3 the door frame ("door side") that the walls beside a door show toward it, on their north or
 * south faces and on their east or west faces; + 4 and + 5 the elevator door; + 6 and + 7 the
 * locked door.
 *
 * Plane 1 (objects):
 * - 19–22: the player's start, facing north, east, south, west;
 * - 23–71: static objects, statinfo[code − 23] (STATICS below);
 * - 98 (PUSHABLETILE): the wall under it (plane 0) is a push wall;
 * - 90–97 (ICONARROWS: where patrolling guards turn) and 99 (EXITTILE: the end of the last level)
 *   are invisible marks;
 * - 108 and up: guards, dogs and the other actors, in three blocks of 36 codes by skill (108–143
 *   at every skill, 144–179 from "bring 'em on", 180–215 at "I am death incarnate"): ACTORS below
 *   for the ones drawn (standing still).
 */

/** The game's AREATILE: plane-0 codes from here on are open floor (and name the area). */
export const AREATILE = 107;
export const AMBUSHTILE = 106;
export const PUSHABLETILE = 98;
export const FIRST_DOOR = 90;
export const LAST_DOOR = 101;
/** Codes 1–63 have wall pages of their own (MAXWALLTILES = 64). */
export const LAST_TEXTURED_WALL = 63;

/** What a plane-0 tile is. */
export type TileKind = 'open' | 'wall' | 'door';

export function tileKind(code: number): TileKind {
  if (code >= FIRST_DOOR && code <= LAST_DOOR) return 'door';
  if (code === 0 || code === AMBUSHTILE || code >= AREATILE) return 'open';
  return 'wall';
}

/** The light (north and south faces) and dark (east and west faces) wall pages of wall code `code`, 1–63. */
export function wallPages(code: number): { readonly light: number; readonly dark: number } {
  return { light: (code - 1) * 2, dark: (code - 1) * 2 + 1 };
}

export type DoorLock = 'none' | 'gold' | 'silver' | 'lock3' | 'lock4' | 'elevator';
const LOCKS: readonly DoorLock[] = ['none', 'gold', 'silver', 'lock3', 'lock4', 'elevator'];

export interface DoorCode {
  /** The panel runs north–south (one walks through it east–west). */
  readonly vertical: boolean;
  readonly lock: DoorLock;
}

export function doorCode(code: number): DoorCode {
  return { vertical: (code - FIRST_DOOR) % 2 === 0, lock: LOCKS[(code - FIRST_DOOR) >> 1]! };
}

/** DOORWALL: the first door page, for a VSWAP of `wallPageCount` wall pages. */
export const doorWall = (wallPageCount: number): number => wallPageCount - 8;

/** The page a door panel shows (HitHorizDoor, HitVertDoor). */
export function doorPage(door: DoorCode, wallPageCount: number): number {
  const base = door.lock === 'none' ? 0 : door.lock === 'elevator' ? 4 : 6;
  return doorWall(wallPageCount) + base + (door.vertical ? 1 : 0);
}

/** The door-frame page a wall face beside a door shows: + 2 on north and south faces, + 3 on east and west faces. */
export function doorSidePage(faceNorthSouth: boolean, wallPageCount: number): number {
  return doorWall(wallPageCount) + (faceNorthSouth ? 2 : 3);
}

/** The player's start: plane-1 codes 19–22, facing north, east, south, west. */
export const PLAYER_START_CODES = [19, 20, 21, 22] as const;

/** A start's facing as a unit step on the map (x east, y south). */
export function startFacing(code: number): readonly [number, number] | undefined {
  switch (code) {
    case 19:
      return [0, -1];
    case 20:
      return [1, 0];
    case 21:
      return [0, 1];
    case 22:
      return [-1, 0];
    default:
      return undefined;
  }
}

export interface StaticInfo {
  /** What it is (the comments of the game's statinfo table). */
  readonly name: string;
  /** Its sprite: SPR_STAT_0 + this (numbering of the game's sprite list, WL_DEF.H). */
  readonly stat: number;
  /** The player cannot walk into its tile (statinfo's `block`). */
  readonly blocks: boolean;
  /** A lamp: the scene gives it a light (Wolfenstein has no lighting; these are what depict light). */
  readonly light?: 'ceiling' | 'floor';
}

/** The game's sprite list numbers SPR_DEMO 0, SPR_DEATHCAM 1, then SPR_STAT_0. */
export const SPR_STAT_0 = 2;
export const FIRST_STATIC = 23;

const s = (name: string, stat: number, blocks = false, light?: 'ceiling' | 'floor'): StaticInfo => ({ name, stat, blocks, ...(light && { light }) });

/** statinfo (Wolfenstein 3D, not Spear of Destiny): plane-1 code 23 + i is entry i. */
export const STATICS: readonly StaticInfo[] = [
  s('puddle', 0), s('green barrel', 1, true), s('table and chairs', 2, true), s('floor lamp', 3, true, 'floor'),
  s('chandelier', 4, false, 'ceiling'), s('hanged man', 5, true), s('dog food', 6), s('red pillar', 7, true),
  s('tree', 8, true), s('skeleton', 9), s('sink', 10, true), s('potted plant', 11, true),
  s('urn', 12, true), s('bare table', 13, true), s('ceiling light', 14, false, 'ceiling'), s('kitchen stuff', 15),
  s('suit of armour', 16, true), s('hanging cage', 17, true), s('skeleton in cage', 18, true), s('skeleton relaxing', 19),
  s('gold key', 20), s('silver key', 21), s('bed', 22, true), s('basket', 23),
  s('food', 24), s('first aid', 25), s('clip', 26), s('machine gun', 27),
  s('chain gun', 28), s('cross', 29), s('chalice', 30), s('bible', 31),
  s('crown', 32), s('one up', 33), s('gibs', 34), s('barrel', 35, true),
  s('well', 36, true), s('empty well', 37, true), s('gibs', 38), s('flag', 39, true),
  s('call Apogee', 40, true), s('junk', 41), s('junk', 42), s('junk', 43),
  s('pots', 44), s('stove', 45, true), s('spears', 46, true), s('vines', 47),
  s('clip', 26),
];

/** The static object of plane-1 code `code`, or undefined when the code is not one. */
export function staticInfo(code: number): StaticInfo | undefined {
  return code >= FIRST_STATIC ? STATICS[code - FIRST_STATIC] : undefined;
}

/** Invisible plane-1 marks: the patrol arrows 90–97 and EXITTILE 99. */
export const isInvisibleMark = (code: number): boolean => (code >= 90 && code <= 97) || code === 99;

/** Plane-1 codes of the actors (guards, dogs, officers, SS, mutants, bosses, ghosts, dead guards). */
export const FIRST_ACTOR = 108;

/** How an actor is drawn: its sprite (SPR_* number) and whether it has eight rotations from there. */
export interface ActorInfo {
  readonly name: string;
  /** The first sprite: rotation 1 (seen from the front) when `rotations` is 8. */
  readonly sprite: number;
  readonly rotations: 1 | 8;
  /** Facing east, north, west, south (0–3), for those with rotations. */
  readonly facing: number;
}

/**
 * The game's sprite list (WL_DEF.H) after the 48 statics: the guard from SPR_GRD_S_1 = 50 (eight
 * standing rotations, then four walking frames of eight, pain, dying, dead at 95, shooting: 49),
 * the dog from SPR_DOG_W1_1 = 99 (walking only: 39), the SS from SPR_SS_S_1 = 138 (as the guard).
 */
const SPR_GRD_S_1 = 50, SPR_GRD_W1_1 = 58, SPR_GRD_DEAD = 95, SPR_DOG_W1_1 = 99, SPR_SS_S_1 = 138, SPR_SS_W1_1 = 146;

/**
 * The actor of plane-1 code `code` at Wolfenstein skill `skill` (1 "can I play, daddy?" … 4 "I am
 * death incarnate"), drawn as it stands when the level starts: guards and SS standing (their
 * standing rotations) or on patrol (their first walking frame), dogs (always walking), the dead
 * guard. ScanInfoPlane's blocks: code − 108 − 36·k for k = 0, 1, 2 (the last two only from skill 3
 * and 4), offsets 0–3 guard standing, 4–7 guard patrolling, 16 the dead guard (first block only),
 * 18–21 SS standing, 22–25 SS patrolling, 26–29 dog standing, 30–33 dog patrolling, each facing
 * east, north, west, south. Undefined for the others (officers, mutants, bosses, ghosts: not drawn)
 * and for actors of a higher skill.
 */
export function actorInfo(code: number, skill: number): ActorInfo | { readonly skipped: 'skill' | 'kind' } {
  if (code < FIRST_ACTOR || code >= FIRST_ACTOR + 3 * 36) return { skipped: 'kind' };
  const block = Math.floor((code - FIRST_ACTOR) / 36);
  if (block > 0 && skill < block + 2) return { skipped: 'skill' };
  const o = (code - FIRST_ACTOR) % 36;
  const facing = (o - (o < 16 ? 0 : 2)) % 4;
  if (o === 16) return block === 0 ? { name: 'dead guard', sprite: SPR_GRD_DEAD, rotations: 1, facing: 0 } : { skipped: 'kind' };
  if (o < 4) return { name: 'guard', sprite: SPR_GRD_S_1, rotations: 8, facing };
  if (o < 8) return { name: 'guard on patrol', sprite: SPR_GRD_W1_1, rotations: 8, facing };
  if (o >= 18 && o < 22) return { name: 'SS', sprite: SPR_SS_S_1, rotations: 8, facing };
  if (o >= 22 && o < 26) return { name: 'SS on patrol', sprite: SPR_SS_W1_1, rotations: 8, facing };
  if (o >= 26 && o < 34) return { name: 'dog', sprite: SPR_DOG_W1_1, rotations: 8, facing };
  return { skipped: 'kind' };
}
