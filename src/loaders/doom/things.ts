/**
 * A map's THINGS as billboards (scene/billboards.ts): which things appear at the chosen skill
 * (thing-types.ts thingAppears), what sprite frame each shows (thing-types.ts, sprites.ts), where it
 * stands (on its sector's floor, or hanging from its ceiling) and which way it faces. Doom draws a
 * sprite with its picture's origin at the thing's position: the picture's top row `topOffset` above
 * the thing's z and its left column `leftOffset` to the left of it (R_ProjectSprite: gzt = z +
 * spritetopoffset, tx −= spriteoffset), one map unit per texel. Mirrored rotations show the picture
 * flipped over the same extent (vanilla draws the columns in reverse without moving them). Things
 * whose spawn states cycle (thing-types.ts `states`) animate: each state is a billboard frame of its
 * tics / 35 seconds, and each thing starts part-way into its first state, as P_SpawnMapThing's
 * `tics = 1 + P_Random() % tics` does (a hash of the thing's index stands in for P_Random).
 */
import { toWorld } from './coordinates.ts';
import type { LightSource, LightTable } from './light-table.ts';
import type { DoomMap } from './map-types.ts';
import type { Picture } from './picture.ts';
import { sectorAt, type SectorShapes } from './sectors.ts';
import type { SpriteSource } from './sprites.ts';
import { DEFAULT_SKILL, INVISIBLE_THINGS, MAX_SKILL, MIN_SKILL, THING_TYPES, thingAppears, TICS_PER_SECOND } from './thing-types.ts';
import { LanternError } from '../../errors.ts';
import type { Billboard, BillboardFrame, BillboardImage } from '../../scene/dynamics-types.ts';

export interface ThingOptions {
  /** 1–5; DEFAULT_SKILL (3) when absent. */
  readonly skill?: number;
  /** Include multiplayer-only things. Default false (a single-player game). */
  readonly multiplayer?: boolean;
}

export interface BuiltThings {
  /** One per thing drawn; `instance` numbers them from 0 in this list's order. */
  readonly billboards: readonly Billboard[];
  /** Names of the things drawn, in the same order. */
  readonly names: readonly string[];
  /** Things drawn whose sprite emits light. */
  readonly emitting: number;
}

/** Makes (or finds) the material of a sprite lump's picture, emitting when `light` says so. */
export type SpriteMaterial = (lump: string, picture: Picture, light: LightSource | undefined) => number;

/** Checks a skill level from the command line or a link; throws a LanternError naming the problem. */
export function checkSkill(skill: number): number {
  if (!Number.isInteger(skill) || skill < MIN_SKILL || skill > MAX_SKILL) {
    throw new LanternError(`skill ${skill} is not a Doom skill level`, `Use ${MIN_SKILL} (I'm too young to die) to ${MAX_SKILL} (Nightmare!); the default is ${DEFAULT_SKILL}`);
  }
  return skill;
}

export function buildThings(
  map: DoomMap,
  shapes: SectorShapes,
  sprites: SpriteSource,
  table: LightTable,
  material: SpriteMaterial,
  options: ThingOptions = {},
  warn: (message: string) => void = () => {},
): BuiltThings {
  const skill = checkSkill(options.skill ?? DEFAULT_SKILL);
  const billboards: Billboard[] = [];
  const names: string[] = [];
  let emitting = 0;
  const unknown = new Map<number, number>();
  const unseen = new Map<string, number>();
  let outside = 0;
  for (const [index, thing] of map.things.entries()) {
    if (INVISIBLE_THINGS.has(thing.type) || !thingAppears(thing.flags, skill, options.multiplayer)) continue;
    const type = THING_TYPES.get(thing.type);
    if (!type) {
      unknown.set(thing.type, (unknown.get(thing.type) ?? 0) + 1);
      continue;
    }
    const sectorIndex = sectorAt(shapes, thing.x, thing.y);
    const sector = sectorIndex === undefined ? undefined : map.sectors[sectorIndex];
    if (!sector) {
      outside++;
      continue;
    }
    const light = table.things[type.sprite];
    const states = type.states ?? [{ frame: type.frame, tics: -1 }];
    const frames: BillboardFrame[] = [];
    for (const state of states) {
      const images = imagesOf(sprites, type.sprite, state.frame, (lump, picture) => material(lump, picture, light));
      if (!images) {
        const key = `${type.sprite}${state.frame}`;
        unseen.set(key, (unseen.get(key) ?? 0) + 1);
        break;
      }
      frames.push({ duration: Math.max(state.tics, 0) / TICS_PER_SECOND, images });
    }
    if (frames.length !== states.length) continue;
    // P_SpawnMobj: on the floor, or (MF_SPAWNCEILING) its height below the ceiling.
    const z = type.hanging ? sector.ceilingHeight - type.height : sector.floorHeight;
    const first = states[0]!.tics;
    const phase = type.states ? (first - 1 - (spawnRandom(index) % first)) / TICS_PER_SECOND : 0;
    billboards.push({ instance: billboards.length, position: toWorld(thing.x, thing.y, z), facing: (thing.angle * Math.PI) / 180, frames, ...(phase > 0 ? { phase } : {}) });
    names.push(type.name);
    if (light && light.strength > 0) emitting++;
  }
  for (const [type, n] of unknown) warn(`${map.name}: ${n} thing(s) of unknown type ${type}; not drawn`);
  for (const [frame, n] of unseen) warn(`${map.name}: the WADs have no usable sprite ${frame.slice(0, 4)} frame ${frame[4]} for ${n} thing(s); not drawn`);
  if (outside > 0) warn(`${map.name}: ${outside} thing(s) stand outside every built sector; not drawn`);
  return { billboards, names, emitting };
}

/** The images of one sprite frame (one or eight rotations), or undefined when the WADs lack it or a picture is unreadable. */
function imagesOf(sprites: SpriteSource, sprite: string, frame: string, material: (lump: string, picture: Picture) => number): BillboardImage[] | undefined {
  const views = sprites.frame(sprite, frame)?.views;
  if (!views) return undefined;
  const images: BillboardImage[] = [];
  for (const view of views) {
    const picture = sprites.picture(view.lump);
    if (!picture) return undefined;
    images.push({ material: material(view.lump, picture), width: picture.width, height: picture.height, left: picture.leftOffset, top: picture.topOffset, mirrored: view.mirrored });
  }
  return images;
}

/** A well-mixed whole number from a thing's index (a stand-in for Doom's P_Random at spawn). */
function spawnRandom(index: number): number {
  let h = Math.imul(index + 1, 0x9e3779b1) >>> 0;
  h = Math.imul(h ^ (h >>> 16), 0x85ebca6b) >>> 0;
  return (h ^ (h >>> 13)) >>> 0;
}
