/**
 * glTF 2.0 (.gltf with its sibling files, or .glb) → Scene. Pure: bytes in, the caller's resolver for
 * the files the model names, a Scene out; no fetch, no GPU, no DOM, so it runs in a Web Worker.
 *
 * Files: document.ts (container, resources), meshes.ts (+ tangents.ts), materials.ts, textures.ts
 * (+ images.ts), cameras.ts, lights.ts, scene.ts (node hierarchy and assembly).
 */
import type { Scene } from '../../scene/types.ts';
import { readGltfSource } from './document.ts';
import { assembleScene } from './scene.ts';
import { Warnings } from './warnings.ts';

/**
 * Loads a glTF model. `resolve` returns a sibling file by its URI as written in the glTF (relative
 * to the main file, not percent-decoded), or undefined when it is not there; data: URIs never reach
 * it. Missing textures and buffers are worked around and named once each in Scene.warnings; only a
 * model with nothing left to show, or bytes that are not glTF, throw a LanternError.
 */
export async function loadGltf(main: { name: string; bytes: Uint8Array }, resolve: (uri: string) => Promise<Uint8Array | undefined>): Promise<Scene> {
  const warnings = new Warnings();
  const source = await readGltfSource(main, resolve, warnings);
  return assembleScene(main.name.replace(/\.(gltf|glb)$/i, ''), source, warnings);
}
