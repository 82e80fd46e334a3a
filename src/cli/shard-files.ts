/**
 * Shard files (farm/shard.ts) as the CLI reads them: a header from the file's first bytes alone,
 * its size checked against what the header says (a 4K shard is 127 MiB: merge checks every shard's
 * header before it reads any sums, and a farm worker checks a chunk's shard to know it is done), and
 * a whole shard read once.
 */
import { decodeShard, decodeShardHeader, SHARD_PREFIX_BYTES, ShardPrefixShort, type Shard, type ShardHeader } from '../farm/shard.ts';
import { readUserFile, readUserFilePrefix } from './user-files.ts';

export function readShardHeader(path: string): ShardHeader {
  let want = SHARD_PREFIX_BYTES;
  for (;;) {
    const { bytes, fileBytes } = readUserFilePrefix(path, want, { what: 'shard' });
    try {
      return decodeShardHeader(bytes, fileBytes, path).header;
    } catch (e) {
      // The header is longer than what was read (a long command line): read that much and look again.
      if (!(e instanceof ShardPrefixShort) || e.bytes <= want) throw e;
      want = e.bytes;
    }
  }
}

export const readShard = (path: string): Shard => decodeShard(readUserFile(path, { what: 'shard' }), path);
