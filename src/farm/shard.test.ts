import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { decodeShard, decodeShardHeader, encodeShard, mergeShards, SHARD_PREFIX_BYTES, SHARD_VERSION, ShardPrefixShort, type Shard } from './shard.ts';

const render = ['cornell', '-W', '2', '-H', '1'];
const shard = (start: number, end: number, values: number[], r = render): Shard => ({ header: { version: SHARD_VERSION, render: r, width: 2, height: 1, start, end }, sums: new Float32Array(values) });

describe('shards', () => {
  it('round-trip through their file form exactly', () => {
    const s = shard(4, 8, [0.1, 1e-30, 3.5, 7, Math.fround(1 / 3), 0, 2 ** 60, 1]);
    const back = decodeShard(encodeShard(s), 'a.shard');
    expect(back.header).toEqual(s.header);
    expect([...back.sums]).toEqual([...s.sums]);
  });
  it('merge in sample order whatever order they come in, rounding to float32 after each addition', () => {
    // 1 + 2^-24 + 2^-24: in float32 the order decides (1 + 2^-24 rounds to 1; 2^-24 + 2^-24 = 2^-23 does not vanish).
    const a = shard(0, 1, [1, 0, 0, 0, 0, 0, 0, 0]);
    const b = shard(1, 2, [2 ** -24, 0, 0, 0, 0, 0, 0, 0]);
    const c = shard(2, 3, [2 ** -24, 0, 0, 0, 0, 0, 0, 0]);
    const merged = mergeShards([c, a, b].map((s, i) => ({ shard: s, name: `${i}` })));
    expect(merged.sums[0]).toBe(Math.fround(Math.fround(1 + 2 ** -24) + 2 ** -24));
    expect(merged.sums[0]).toBe(1);
    expect({ start: merged.start, end: merged.end }).toEqual({ start: 0, end: 3 });
  });
  it('refuse gaps, overlaps, other renders and files that are not shards, in one line', () => {
    const z = new Array(8).fill(0);
    expectLanternError(() => mergeShards([{ shard: shard(0, 4, z), name: 'a' }, { shard: shard(5, 8, z), name: 'b' }]), /samples 4-4 are missing between a and b/);
    expectLanternError(() => mergeShards([{ shard: shard(0, 4, z), name: 'a' }, { shard: shard(3, 8, z), name: 'b' }]), /overlaps/);
    expectLanternError(() => mergeShards([{ shard: shard(0, 4, z), name: 'a' }, { shard: shard(4, 8, z, ['cornell', '--seed', '2']), name: 'b' }]), /another render/);
    expectLanternError(() => decodeShard(new TextEncoder().encode('P6 not a shard'), 'x.ppm'), /x.ppm is not a Lantern shard/);
    const bytes = encodeShard(shard(0, 1, z));
    expectLanternError(() => decodeShard(bytes.subarray(0, bytes.length - 4), 'cut.shard'), /bytes of sums/);
  });
  it('give their header from the first bytes and the file size, asking for more where the header is longer', () => {
    const bytes = encodeShard(shard(4, 8, new Array(8).fill(1)));
    const short = () => decodeShardHeader(bytes.subarray(0, SHARD_PREFIX_BYTES), bytes.length, 'a.shard');
    expect(short).toThrow(ShardPrefixShort);
    let need = 0;
    try {
      short();
    } catch (e) {
      need = (e as ShardPrefixShort).bytes;
    }
    expect(need).toBeGreaterThan(SHARD_PREFIX_BYTES);
    expect(decodeShardHeader(bytes.subarray(0, need), bytes.length, 'a.shard').header).toEqual(shard(4, 8, []).header);
    // The size is checked against the header's without the sums: a cut file is refused from its first bytes.
    expectLanternError(() => decodeShardHeader(bytes.subarray(0, need), bytes.length - 4, 'cut.shard'), /bytes of sums/);
    expectLanternError(() => decodeShardHeader(bytes.subarray(0, 10), 10, 'tiny.shard'), /no LANTERN-SHARD header/);
  });
  it('decode their sums as a view of the bytes where aligned, and as a copy where not', () => {
    const s = shard(0, 2, [1, 2, 3, 4, 5, 6, 7, 8]);
    const bytes = encodeShard(s);
    const view = decodeShard(bytes, 'a.shard');
    expect(view.sums.buffer).toBe(bytes.buffer);
    const shifted = new Uint8Array(bytes.length + 1);
    shifted.set(bytes, 1);
    const copy = decodeShard(shifted.subarray(1), 'b.shard');
    expect(copy.sums.buffer).not.toBe(shifted.buffer);
    expect([...copy.sums]).toEqual([...s.sums]);
  });
});
