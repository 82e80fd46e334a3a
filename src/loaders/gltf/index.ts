/**
 * glTF 2.0 (.gltf with its sibling files, or .glb) → Scene. Pure: bytes in, the caller's resolver for
 * the files the model names, a Scene out; no fetch, no GPU, no DOM, so it runs in a Web Worker.
 *
 * Files: document.ts (container, resources; preflight.ts checks the JSON's counts first), meshes.ts
 * (+ tangents.ts), materials.ts, textures.ts (+ images.ts), cameras.ts, lights.ts, scene.ts (node
 * hierarchy and assembly).
 */
import type { Scene } from '../../scene/types.ts';
import { siblingPath } from '../sibling-uri.ts';
import { readGltfSource } from './document.ts';
import { assembleScene } from './scene.ts';
import { Warnings } from './warnings.ts';

/**
 * Loads a glTF model. `resolve` returns a sibling file by its URI as written in the glTF (relative
 * to the main file, not percent-decoded), or undefined when it is not there; data: URIs never reach
 * it, nor URIs that leave the model's folder (sibling-uri.ts), which are named in a warning instead.
 * Missing textures and buffers are worked around and named once each in Scene.warnings; only a
 * model with nothing left to show, or bytes that are not glTF, throw a LanternError.
 */
export async function loadGltf(main: { name: string; bytes: Uint8Array }, resolve: (uri: string) => Promise<Uint8Array | undefined>): Promise<Scene> {
  const warnings = new Warnings();
  const source = await readGltfSource(main, siblingsWithin(resolve, warnings), warnings);
  return assembleScene(main.name.replace(/\.(gltf|glb)$/i, ''), source, warnings);
}

/**
 * The resolver the loader uses: a URI outside the model's folder is refused (recorded with its
 * reason, so that the missing-file warning says why), and each URI is asked for once, so that a
 * hundred images naming one file read it once and share its bytes.
 */
function siblingsWithin(resolve: (uri: string) => Promise<Uint8Array | undefined>, warnings: Warnings): (uri: string) => Promise<Uint8Array | undefined> {
  const asked = new Map<string, Promise<Uint8Array | undefined>>();
  return (uri) => {
    let answer = asked.get(uri);
    if (!answer) {
      const checked = siblingPath(uri);
      if (!checked.ok) warnings.refuse(uri, checked.reason);
      answer = checked.ok ? resolve(uri) : Promise.resolve(undefined);
      asked.set(uri, answer);
    }
    return answer;
  };
}
