/**
 * The closed list of built-in scenes, selectable by name from the CLI and the page. A scene that
 * takes a parameter is named `<scene>:<parameter>` (`rtiow:7`: the seed of its random field); the
 * plain name gives its default.
 */
import { LanternError } from '../../errors.ts';
import type { Scene } from '../../scene/types.ts';
import { bvhTeaching } from './bvh-teaching.ts';
import { caffeineScene } from './caffeine.ts';
import { cornellBox } from './cornell.ts';
import { dungeonScene } from './dungeon.ts';
import { whiteFurnace } from './furnace.ts';
import { goldenGridScene } from './golden-grid.ts';
import { hexGridScene } from './hex-grid.ts';
import { manyLightsScene } from './many-lights.ts';
import { materialsScene } from './materials.ts';
import { orbScene } from './orb.ts';
import { prismScene } from './prism.ts';
import { rtiowScene } from './rtiow.ts';
import { spheresScene } from './spheres.ts';

interface BuiltinScene {
  readonly description: string;
  /** What `<scene>:<parameter>` sets, for messages ('seed'); absent: the scene takes none. */
  readonly parameter?: string;
  readonly make: (parameter?: string) => Scene;
}

export const BUILTIN_SCENES = {
  cornell: { description: 'the Cornell box, from the published measurements (mm)', make: cornellBox },
  furnace: { description: 'white furnace: every pixel converges to 5.0', make: whiteFurnace },
  'bvh-teaching': { description: 'BVH teaching room: separated cubes, a dense cluster and a diagonal slab', make: bvhTeaching },
  materials: { description: 'a row of spheres under a sky: mirror to rough metal, gold, clear and frosted glass, plastic, diffuse', make: materialsScene },
  spheres: { description: 'the sphere tutorial scene: diffuse, glass and metal spheres on a ground sphere, a sphere lamp, a gradient sky', make: spheresScene },
  rtiow: { description: "Ray Tracing in One Weekend's final scene with depth of field ('rtiow:<seed>' for another random field)", parameter: 'seed', make: rtiowScene },
  orb: { description: 'a glass orb over a polished floor and one small lamp: a caustic study', make: orbScene },
  'golden-grid': { description: 'a grid of gold spheres under a sky, shallow depth of field', make: goldenGridScene },
  'hex-grid': { description: 'a hexagonal grid of coloured spheres seen through a thin lens: focal blur', make: hexGridScene },
  caffeine: { description: 'the caffeine molecule (PubChem CID 2519), ball-and-stick, in the studio', make: caffeineScene },
  dungeon: { description: 'a torch-lit stone dungeon on a 16 × 16 tile map, walkable, with a glowing phantom that wanders its corridors', make: dungeonScene },
  'many-lights': { description: 'a room with 40 small ceiling lamps of mixed power, pillars and a low wall: a many-light sampling test (ReSTIR)', make: manyLightsScene },
  prism: { description: 'a dense-flint prism splits a narrow beam of white light into a spectrum on a screen (render with --spectral)', make: () => prismScene() },
} as const satisfies Record<string, BuiltinScene>;

export type BuiltinSceneName = keyof typeof BUILTIN_SCENES;

export const builtinSceneNames = (): BuiltinSceneName[] => Object.keys(BUILTIN_SCENES) as BuiltinSceneName[];

/** `rtiow:7` -> the scene's entry and its parameter; undefined when the name is no built-in (or takes no parameter). */
function lookUp(name: string): { readonly scene: BuiltinScene; readonly parameter?: string } | undefined {
  const colon = name.indexOf(':');
  const base = colon < 0 ? name : name.slice(0, colon);
  if (!Object.hasOwn(BUILTIN_SCENES, base)) return undefined;
  const scene: BuiltinScene = BUILTIN_SCENES[base as BuiltinSceneName];
  if (colon < 0) return { scene };
  return scene.parameter ? { scene, parameter: name.slice(colon + 1) } : undefined;
}

/** True for a built-in's name, and for `<scene>:<parameter>` of a scene that takes one (the parameter is checked when the scene is made). */
export const isBuiltinScene = (name: string): boolean => lookUp(name) !== undefined;

export function builtinScene(name: string): Scene {
  const found = lookUp(name);
  if (!found) {
    const base = name.split(':')[0]!;
    if (Object.hasOwn(BUILTIN_SCENES, base)) throw new LanternError(`the scene '${base}' takes no parameter ('${name}')`, `Name it plainly: ${base}`);
    throw new LanternError(`unknown scene '${name}'`, `Built-in scenes are: ${builtinSceneNames().join(', ')}`);
  }
  return found.scene.make(found.parameter);
}
