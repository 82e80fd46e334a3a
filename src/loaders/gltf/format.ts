/** The glTF 2.0 entry of the loader registry: a .glb, or a .gltf with its .bin and images beside it. */
import { WarningCap } from '../../budgets.ts';
import type { SceneFormat } from '../format.ts';
import { checkGltfFile, gltfSiblings, sniffGltf } from './document.ts';
import { loadGltf } from './index.ts';

export const GLTF_FORMAT: SceneFormat = {
  id: 'gltf',
  kind: 'scene',
  description: 'glTF 2.0 scenes',
  extensions: ['.glb', '.gltf'],
  siblingExtensions: ['.bin', '.png', '.jpg', '.jpeg', '.webp', '.ktx2'],
  sniff: sniffGltf,
  linkParam: 'gltf',
  stacks: false,
  example: 'model.glb',
  siblings: (main) => gltfSiblings(main),
  checkFile: checkGltfFile,
  async open(set, options = {}) {
    const file = set.files[0]!;
    return {
      description: file.name,
      parts: [],
      scene: async (_part, sceneOptions = options) => {
        const scene = await loadGltf(file, set.resolve);
        // Capped per kind: a file with thousands of unsupported materials would print thousands of lines.
        const onWarning = sceneOptions.onWarning;
        if (onWarning) {
          const cap = new WarningCap(onWarning);
          for (const w of scene.warnings ?? []) cap.warn(w);
          cap.finish();
        }
        return scene;
      },
    };
  },
};
