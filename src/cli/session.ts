/**
 * What every GPU command starts with: load the scene, acquire a device (noting a SwiftShader
 * fallback), create the renderer and upload the scene.
 */
import { prepareScene, type PreparedScene } from '../renderer/prepare.ts';
import { withEnvironment } from '../scene/environment-override.ts';
import type { Environment } from '../scene/environment.ts';
import { Renderer } from '../renderer/renderer.ts';
import type { Scene } from '../scene/types.ts';
import { acquireNodeGpu } from './dawn.ts';
import type { SceneOptionValues } from './options.ts';
import { loadSceneArgument, sceneLoadOptions } from './scene-source.ts';

export interface Session {
  readonly renderer: Renderer;
  readonly prepared: PreparedScene;
  readonly loadMs: number;
}

/** `adjust` changes the loaded scene before it is prepared (bench --levels). */
export async function openSession(sceneArg: string, note: (message: string) => void, sceneOptions: SceneOptionValues = {}, environment?: Environment, adjust?: (scene: Scene) => Scene): Promise<Session> {
  const t0 = performance.now();
  const loaded = await loadSceneArgument(sceneArg, sceneLoadOptions(sceneOptions, note));
  const lit = environment ? withEnvironment(loaded, environment) : loaded;
  const scene = adjust ? adjust(lit) : lit;
  const prepared = prepareScene(scene);
  const loadMs = performance.now() - t0;
  const gpu = await acquireNodeGpu({ onNote: note });
  const renderer = await Renderer.create(gpu);
  await renderer.setScene(prepared);
  return { renderer, prepared, loadMs };
}
