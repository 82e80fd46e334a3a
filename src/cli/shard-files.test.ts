import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { encodeShard, SHARD_VERSION } from '../farm/shard.ts';
import { readShard, readShardHeader } from './shard-files.ts';

describe('shard files', () => {
  const dir = mkdtempSync(join(tmpdir(), 'lantern-shards-'));
  afterAll(() => rmSync(dir, { recursive: true, force: true }));
  // A long command line: the header is far beyond the first read.
  const header = { version: SHARD_VERSION, render: ['cornell', ...Array.from({ length: 200 }, (_, i) => `--option-${i}`)], width: 3, height: 2, start: 0, end: 4 };
  const bytes = encodeShard({ header, sums: new Float32Array(24).map((_, i) => i / 7) });

  it('read the header from the first bytes, and the whole shard once', () => {
    const path = join(dir, 'a.shard');
    writeFileSync(path, bytes);
    expect(readShardHeader(path)).toEqual(header);
    expect([...readShard(path).sums]).toEqual([...new Float32Array(24).map((_, i) => i / 7)]);
  });

  it('refuse a cut file from its header alone, and what is not a file, in one line', () => {
    const cut = join(dir, 'cut.shard');
    writeFileSync(cut, bytes.subarray(0, bytes.length - 8));
    expectLanternError(() => readShardHeader(cut), /cut\.shard is not a Lantern shard: .* bytes of sums/);
    expectLanternError(() => readShardHeader(dir), /shard: cannot read .*not a regular file/);
  });
});
