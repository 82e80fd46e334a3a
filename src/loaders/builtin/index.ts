/** The closed list of built-in scenes, selectable by name from the CLI and the page. */
import { LanternError } from '../../errors.ts';
import type { Scene } from '../../scene/types.ts';
import { bvhTeaching } from './bvh-teaching.ts';
import { cornellBox } from './cornell.ts';
import { whiteFurnace } from './furnace.ts';
import { materialsScene } from './materials.ts';
import { prismScene } from './prism.ts';

export const BUILTIN_SCENES = {
  cornell: { description: 'the Cornell box, from the published measurements (mm)', make: cornellBox },
  furnace: { description: 'white furnace: every pixel converges to 5.0', make: whiteFurnace },
  'bvh-teaching': { description: 'BVH teaching room: separated cubes, a dense cluster and a diagonal slab', make: bvhTeaching },
  prism: { description: 'a dense-flint prism splits a narrow beam of white light into a spectrum on a screen (render with --spectral)', make: () => prismScene() },
  materials: { description: 'a row of spheres under a sky: mirror to rough metal, gold, clear and frosted glass, plastic, diffuse', make: materialsScene },
} as const satisfies Record<string, { description: string; make: () => Scene }>;

export type BuiltinSceneName = keyof typeof BUILTIN_SCENES;

export const builtinSceneNames = (): BuiltinSceneName[] => Object.keys(BUILTIN_SCENES) as BuiltinSceneName[];

export const isBuiltinScene = (name: string): name is BuiltinSceneName => Object.hasOwn(BUILTIN_SCENES, name);

export function builtinScene(name: string): Scene {
  if (!isBuiltinScene(name)) {
    throw new LanternError(`unknown scene '${name}'`, `Built-in scenes are: ${builtinSceneNames().join(', ')}`);
  }
  return BUILTIN_SCENES[name].make();
}
