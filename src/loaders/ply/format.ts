/** The PLY entry of the loader registry: one mesh per file, plain or gzip-compressed. */
import { Gunzip } from 'fflate';
import { SNIFF_BYTES, type SceneFormat } from '../format.ts';
import { loadPly } from './ply.ts';

const PLY_MAGIC = [0x70, 0x6c, 0x79]; // "ply", then "\n" or "\r\n"

function startsPly(bytes: Uint8Array): boolean {
  return PLY_MAGIC.every((b, i) => bytes[i] === b) && (bytes[3] === 0x0a || (bytes[3] === 0x0d && bytes[4] === 0x0a));
}

/**
 * Gzip says nothing about what it holds, so the head is inflated as far as it goes: a few hundred
 * compressed bytes give the first bytes of the PLY header. A .gz of anything else is not a PLY.
 */
function gzippedPly(head: Uint8Array): boolean {
  if (head[0] !== 0x1f || head[1] !== 0x8b) return false;
  let first: Uint8Array | undefined;
  try {
    // Only the first bytes: callers may pass the whole file, and inflating all of a gzip bomb here
    // would take its full size before the loader's limit is ever checked.
    new Gunzip((chunk) => {
      first ??= chunk;
    }).push(head.subarray(0, SNIFF_BYTES), false);
  } catch {
    return false;
  }
  return first !== undefined && startsPly(first);
}

export const PLY_FORMAT: SceneFormat = {
  id: 'ply',
  kind: 'scene',
  description: 'PLY meshes',
  extensions: ['.ply.gz', '.ply'],
  sniff: (head) => startsPly(head) || gzippedPly(head),
  linkParam: 'ply',
  stacks: false,
  async open(set) {
    // One file by construction (stacks: false); its name is the scene's, so messages say which file.
    const file = set.files[0]!;
    return {
      description: file.name,
      parts: [],
      // async so that a corrupt file rejects the promise instead of throwing before there is one.
      scene: async (_part, options = {}) => loadPly(file.bytes, file.name, options.onWarning ? { onWarning: options.onWarning } : {}),
    };
  },
};
