/**
 * The things of Doom and Doom II by editor number (doomednum): what sprite each shows, whether it is a
 * monster, an item or a decoration, its size, whether it hangs from the ceiling, and whether it gives
 * light. From the games' mobjinfo table (info.c) and https://doomwiki.org/wiki/Thing_types; docs/doom.md
 * has the same table for people. Also which things appear at a skill level (P_SpawnMapThing).
 *
 * - `frame` is the sprite frame of the thing's spawn state: 'A' for the living and the items, a late
 *   death frame for the corpses placed as decorations (a dead imp is TROO frame M). `states` is the
 *   cycle of spawn states a thing loops through while nothing happens to it (a monster waiting, a
 *   torch's flames, a bonus's shimmer), each a frame and its duration in tics (1/35 s), from the
 *   games' state table; absent for things that hold one frame.
 * - `hanging` things (MF_SPAWNCEILING) are placed with their top at the ceiling: Doom sets their z to
 *   the ceiling height less their `height` (P_SpawnMobj), and their sprites' top offsets are drawn to
 *   meet the ceiling from there.
 * - `light`: the thing is drawn full bright in Doom (its frames carry FF_FULLBRIGHT) and depicts a
 *   light: 'lamp' for electric lamps, 'fire' for flames (torches, candles, burning barrels, the
 *   floating skull rock, the candles of the skull pile, the evil eye's glow). light-table.ts turns these into emitters, keyed by sprite
 *   name, where users can override them.
 * - Things with no picture (player starts, teleport destinations, the boss spawner's targets) are in
 *   INVISIBLE_THINGS; a number in neither table is unknown and skipped with a warning.
 */

export type ThingKind = 'monster' | 'item' | 'decoration';

/** One state of a cycle: the sprite frame shown and for how many tics. */
export interface ThingState {
  readonly frame: string;
  readonly tics: number;
}

/** Doom's game tics per second. */
export const TICS_PER_SECOND = 35;
export type ThingLight = 'lamp' | 'fire';

export interface ThingType {
  readonly name: string;
  /** Four-character sprite name (TROO, CBRA, ...). */
  readonly sprite: string;
  /** Frame letter of the spawn state. */
  readonly frame: string;
  /** The spawn states' cycle, when the thing animates: frames and their tics (1/35 s), in order. */
  readonly states?: readonly ThingState[];
  readonly kind: ThingKind;
  /** Map units (mobjinfo radius and height). */
  readonly radius: number;
  readonly height: number;
  readonly hanging?: boolean;
  readonly light?: ThingLight;
  /** Only in Doom II (its sprites are absent from Doom's IWADs). */
  readonly doom2?: boolean;
}

/** number, sprite, the spawn frame or its states' cycle ('A10 B10': frame A for 10 tics, then B for 10), kind, radius, height, name, tags. */
type Row = readonly [number, string, string, ThingKind, number, number, string, ...('hanging' | 'lamp' | 'fire' | 'doom2')[]];

const ROWS: readonly Row[] = [
  // Monsters.
  [3004, 'POSS', 'A10 B10', 'monster', 20, 56, 'Zombieman'],
  [9, 'SPOS', 'A10 B10', 'monster', 20, 56, 'Shotgun guy'],
  [65, 'CPOS', 'A10 B10', 'monster', 20, 56, 'Heavy weapon dude', 'doom2'],
  [3001, 'TROO', 'A10 B10', 'monster', 20, 56, 'Imp'],
  [3002, 'SARG', 'A10 B10', 'monster', 30, 56, 'Demon'],
  [58, 'SARG', 'A10 B10', 'monster', 30, 56, 'Spectre'],
  [3006, 'SKUL', 'A10 B10', 'monster', 16, 56, 'Lost soul'],
  [3005, 'HEAD', 'A', 'monster', 31, 56, 'Cacodemon'],
  [69, 'BOS2', 'A10 B10', 'monster', 24, 64, 'Hell knight', 'doom2'],
  [3003, 'BOSS', 'A10 B10', 'monster', 24, 64, 'Baron of Hell'],
  [68, 'BSPI', 'A10 B10', 'monster', 64, 64, 'Arachnotron', 'doom2'],
  [71, 'PAIN', 'A', 'monster', 31, 56, 'Pain elemental', 'doom2'],
  [66, 'SKEL', 'A10 B10', 'monster', 20, 56, 'Revenant', 'doom2'],
  [67, 'FATT', 'A15 B15', 'monster', 48, 64, 'Mancubus', 'doom2'],
  [64, 'VILE', 'A10 B10', 'monster', 20, 56, 'Arch-vile', 'doom2'],
  [7, 'SPID', 'A10 B10', 'monster', 128, 100, 'Spider Mastermind'],
  [16, 'CYBR', 'A10 B10', 'monster', 40, 110, 'Cyberdemon'],
  [84, 'SSWV', 'A10 B10', 'monster', 20, 56, 'Wolfenstein SS', 'doom2'],
  [72, 'KEEN', 'A', 'monster', 16, 72, 'Commander Keen', 'hanging', 'doom2'],
  [88, 'BBRN', 'A', 'monster', 16, 16, 'Boss brain', 'doom2'],
  // Weapons.
  [2005, 'CSAW', 'A', 'item', 20, 16, 'Chainsaw'],
  [2001, 'SHOT', 'A', 'item', 20, 16, 'Shotgun'],
  [82, 'SGN2', 'A', 'item', 20, 16, 'Super shotgun', 'doom2'],
  [2002, 'MGUN', 'A', 'item', 20, 16, 'Chaingun'],
  [2003, 'LAUN', 'A', 'item', 20, 16, 'Rocket launcher'],
  [2004, 'PLAS', 'A', 'item', 20, 16, 'Plasma gun'],
  [2006, 'BFUG', 'A', 'item', 20, 16, 'BFG 9000'],
  // Ammunition.
  [2007, 'CLIP', 'A', 'item', 20, 16, 'Clip'],
  [2048, 'AMMO', 'A', 'item', 20, 16, 'Box of bullets'],
  [2008, 'SHEL', 'A', 'item', 20, 16, 'Shotgun shells'],
  [2049, 'SBOX', 'A', 'item', 20, 16, 'Box of shells'],
  [2010, 'ROCK', 'A', 'item', 20, 16, 'Rocket'],
  [2046, 'BROK', 'A', 'item', 20, 16, 'Box of rockets'],
  [2047, 'CELL', 'A', 'item', 20, 16, 'Energy cell'],
  [17, 'CELP', 'A', 'item', 20, 16, 'Energy cell pack'],
  [8, 'BPAK', 'A', 'item', 20, 16, 'Backpack'],
  // Health, armour, powerups.
  [2011, 'STIM', 'A', 'item', 20, 16, 'Stimpack'],
  [2012, 'MEDI', 'A', 'item', 20, 16, 'Medikit'],
  [2014, 'BON1', 'A6 B6 C6 D6 C6 B6', 'item', 20, 16, 'Health bonus'],
  [2015, 'BON2', 'A6 B6 C6 D6 C6 B6', 'item', 20, 16, 'Armor bonus'],
  [2018, 'ARM1', 'A6 B7', 'item', 20, 16, 'Armor'],
  [2019, 'ARM2', 'A6 B6', 'item', 20, 16, 'Megaarmor'],
  [2013, 'SOUL', 'A6 B6 C6 D6 C6 B6', 'item', 20, 16, 'Soulsphere'],
  [83, 'MEGA', 'A6 B6 C6 D6', 'item', 20, 16, 'Megasphere', 'doom2'],
  [2022, 'PINV', 'A6 B6 C6 D6', 'item', 20, 16, 'Invulnerability'],
  [2023, 'PSTR', 'A', 'item', 20, 16, 'Berserk'],
  [2024, 'PINS', 'A6 B6 C6 D6', 'item', 20, 16, 'Partial invisibility'],
  [2025, 'SUIT', 'A', 'item', 20, 16, 'Radiation shielding suit'],
  [2026, 'PMAP', 'A6 B6 C6 D6 C6 B6', 'item', 20, 16, 'Computer area map'],
  [2045, 'PVIS', 'A6 B6', 'item', 20, 16, 'Light amplification visor'],
  // Keys.
  [5, 'BKEY', 'A10 B10', 'item', 20, 16, 'Blue keycard'],
  [40, 'BSKU', 'A10 B10', 'item', 20, 16, 'Blue skull key'],
  [13, 'RKEY', 'A10 B10', 'item', 20, 16, 'Red keycard'],
  [38, 'RSKU', 'A10 B10', 'item', 20, 16, 'Red skull key'],
  [6, 'YKEY', 'A10 B10', 'item', 20, 16, 'Yellow keycard'],
  [39, 'YSKU', 'A10 B10', 'item', 20, 16, 'Yellow skull key'],
  // Lights.
  [2028, 'COLU', 'A', 'decoration', 16, 16, 'Floor lamp', 'lamp'],
  [85, 'TLMP', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Tall techno floor lamp', 'lamp', 'doom2'],
  [86, 'TLP2', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Short techno floor lamp', 'lamp', 'doom2'],
  [34, 'CAND', 'A', 'decoration', 20, 16, 'Candle', 'fire'],
  [35, 'CBRA', 'A', 'decoration', 16, 16, 'Candelabra', 'fire'],
  [44, 'TBLU', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Tall blue firestick', 'fire'],
  [45, 'TGRN', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Tall green firestick', 'fire'],
  [46, 'TRED', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Tall red firestick', 'fire'],
  [55, 'SMBT', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Short blue firestick', 'fire'],
  [56, 'SMGT', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Short green firestick', 'fire'],
  [57, 'SMRT', 'A4 B4 C4 D4', 'decoration', 16, 16, 'Short red firestick', 'fire'],
  [70, 'FCAN', 'A4 B4 C4', 'decoration', 16, 16, 'Burning barrel', 'fire', 'doom2'],
  [42, 'FSKU', 'A6 B6 C6', 'decoration', 16, 16, 'Floating skull rock', 'fire'],
  [41, 'CEYE', 'A6 B6 C6 B6', 'decoration', 16, 16, 'Evil eye', 'fire'],
  // Obstacles and decorations.
  [2035, 'BAR1', 'A6 B6', 'decoration', 10, 42, 'Exploding barrel'],
  [48, 'ELEC', 'A', 'decoration', 16, 16, 'Tall techno column'],
  [30, 'COL1', 'A', 'decoration', 16, 16, 'Tall green pillar'],
  [31, 'COL2', 'A', 'decoration', 16, 16, 'Short green pillar'],
  [32, 'COL3', 'A', 'decoration', 16, 16, 'Tall red pillar'],
  [33, 'COL4', 'A', 'decoration', 16, 16, 'Short red pillar'],
  [36, 'COL5', 'A14 B14', 'decoration', 16, 16, 'Short green pillar with beating heart'],
  [37, 'COL6', 'A', 'decoration', 16, 16, 'Short red pillar with skull'],
  [43, 'TRE1', 'A', 'decoration', 16, 16, 'Burnt tree'],
  [54, 'TRE2', 'A', 'decoration', 32, 16, 'Large brown tree'],
  [47, 'SMIT', 'A', 'decoration', 16, 16, 'Brown stump'],
  [25, 'POL1', 'A', 'decoration', 16, 16, 'Impaled human'],
  [26, 'POL6', 'A6 B8', 'decoration', 16, 16, 'Twitching impaled human'],
  [27, 'POL4', 'A', 'decoration', 16, 16, 'Skull on a pole'],
  [28, 'POL2', 'A', 'decoration', 16, 16, 'Five skulls "shish kebab"'],
  [29, 'POL3', 'A6 B6', 'decoration', 16, 16, 'Pile of skulls and candles', 'fire'],
  [24, 'POL5', 'A', 'decoration', 20, 16, 'Pool of blood and flesh'],
  [79, 'POB1', 'A', 'decoration', 20, 16, 'Pool of blood', 'doom2'],
  [80, 'POB2', 'A', 'decoration', 20, 16, 'Pool of blood', 'doom2'],
  [81, 'BRS1', 'A', 'decoration', 20, 16, 'Pool of brains', 'doom2'],
  // Hanging from the ceiling (49–53 block, 59–63 do not).
  [49, 'GOR1', 'A10 B15 C8 B6', 'decoration', 16, 68, 'Hanging victim, twitching', 'hanging'],
  [50, 'GOR2', 'A', 'decoration', 16, 84, 'Hanging victim, arms out', 'hanging'],
  [51, 'GOR3', 'A', 'decoration', 16, 84, 'Hanging victim, one-legged', 'hanging'],
  [52, 'GOR4', 'A', 'decoration', 16, 68, 'Hanging pair of legs', 'hanging'],
  [53, 'GOR5', 'A', 'decoration', 16, 52, 'Hanging leg', 'hanging'],
  [63, 'GOR1', 'A10 B15 C8 B6', 'decoration', 20, 68, 'Hanging victim, twitching (non-blocking)', 'hanging'],
  [59, 'GOR2', 'A', 'decoration', 20, 84, 'Hanging victim, arms out (non-blocking)', 'hanging'],
  [61, 'GOR3', 'A', 'decoration', 20, 52, 'Hanging victim, one-legged (non-blocking)', 'hanging'],
  [60, 'GOR4', 'A', 'decoration', 20, 68, 'Hanging pair of legs (non-blocking)', 'hanging'],
  [62, 'GOR5', 'A', 'decoration', 20, 52, 'Hanging leg (non-blocking)', 'hanging'],
  [73, 'HDB1', 'A', 'decoration', 16, 88, 'Hanging victim, guts removed', 'hanging', 'doom2'],
  [74, 'HDB2', 'A', 'decoration', 16, 88, 'Hanging victim, guts and brain removed', 'hanging', 'doom2'],
  [75, 'HDB3', 'A', 'decoration', 16, 64, 'Hanging torso, looking down', 'hanging', 'doom2'],
  [76, 'HDB4', 'A', 'decoration', 16, 64, 'Hanging torso, open skull', 'hanging', 'doom2'],
  [77, 'HDB5', 'A', 'decoration', 16, 64, 'Hanging torso, looking up', 'hanging', 'doom2'],
  [78, 'HDB6', 'A', 'decoration', 16, 64, 'Hanging torso, brain removed', 'hanging', 'doom2'],
  // Corpses: the last frame of a death.
  [15, 'PLAY', 'N', 'decoration', 20, 16, 'Dead player'],
  [10, 'PLAY', 'W', 'decoration', 20, 16, 'Bloody mess'],
  [12, 'PLAY', 'W', 'decoration', 20, 16, 'Bloody mess'],
  [18, 'POSS', 'L', 'decoration', 20, 16, 'Dead zombieman'],
  [19, 'SPOS', 'L', 'decoration', 20, 16, 'Dead shotgun guy'],
  [20, 'TROO', 'M', 'decoration', 20, 16, 'Dead imp'],
  [21, 'SARG', 'N', 'decoration', 20, 16, 'Dead demon'],
  [22, 'HEAD', 'L', 'decoration', 20, 16, 'Dead cacodemon'],
];

export const THING_TYPES: ReadonlyMap<number, ThingType> = new Map(
  ROWS.map(([num, sprite, cycle, kind, radius, height, name, ...tags]) => {
    const states = cycle.split(' ').map((s) => ({ frame: s[0]!, tics: s.length > 1 ? Number(s.slice(1)) : -1 }));
    return [num, {
      name, sprite, frame: states[0]!.frame, kind, radius, height,
      ...(states.length > 1 ? { states } : {}),
      ...(tags.includes('hanging') ? { hanging: true } : {}),
      ...(tags.includes('lamp') ? { light: 'lamp' as const } : tags.includes('fire') ? { light: 'fire' as const } : {}),
      ...(tags.includes('doom2') ? { doom2: true } : {}),
    }] as const;
  }),
);

/**
 * Things that are markers, not pictures: player and deathmatch starts, teleport destinations, the
 * boss brain's spawn targets and spawner, the dead lost soul (its spawn frame, SKUL K, is drawn as
 * nothing in the games), and an editor's camera marker.
 */
export const INVISIBLE_THINGS: ReadonlyMap<number, string> = new Map([
  [1, 'Player 1 start'], [2, 'Player 2 start'], [3, 'Player 3 start'], [4, 'Player 4 start'],
  [11, 'Deathmatch start'], [14, 'Teleport destination'], [87, 'Boss spawn target'], [89, 'Boss spawn shooter'],
  [23, 'Dead lost soul'],
  // Doom Builder's visual-mode camera, left in a few Freedoom maps; the games ignore it.
  [32000, 'Doom Builder camera'],
]);

/** Thing flags (https://doomwiki.org/wiki/Thing#Flags). */
export const THING_FLAGS = {
  /** Present at skills 1 and 2. */
  EASY: 0x01,
  /** Present at skill 3. */
  MEDIUM: 0x02,
  /** Present at skills 4 and 5. */
  HARD: 0x04,
  /** Monsters wait for sight (ambush, "deaf"): no effect on what is drawn. */
  DEAF: 0x08,
  /** Only in multiplayer games. */
  MULTIPLAYER: 0x10,
} as const;

export const MIN_SKILL = 1;
export const MAX_SKILL = 5;
/** Hurt me plenty. */
export const DEFAULT_SKILL = 3;

/**
 * Whether a thing with `flags` is spawned at `skill` (1–5) in a single-player (or multiplayer) game,
 * as P_SpawnMapThing decides: the multiplayer-only flag keeps it out of single player; skills 1–2
 * need bit 0, skill 3 bit 1, skills 4–5 bit 2.
 */
export function thingAppears(flags: number, skill: number, multiplayer = false): boolean {
  if (!multiplayer && flags & THING_FLAGS.MULTIPLAYER) return false;
  const bit = skill <= 2 ? THING_FLAGS.EASY : skill === 3 ? THING_FLAGS.MEDIUM : THING_FLAGS.HARD;
  return (flags & bit) !== 0;
}

/** The sprite names of things that give light, and what kind of light (light-table.ts makes emitters of them). */
export function lightGivingSprites(): ReadonlyMap<string, ThingLight> {
  const out = new Map<string, ThingLight>();
  for (const t of THING_TYPES.values()) if (t.light) out.set(t.sprite, t.light);
  return out;
}
