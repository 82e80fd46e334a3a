import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { gpuIdentity, holdGpu, type LeaseClient } from './gpu-lease.ts';

/** Redis's SET NX, GET, KEYS (glob * only), PEXPIRE and DEL over a map, without expiry. */
function memoryRedis(): LeaseClient & { readonly data: Map<string, string> } {
  const data = new Map<string, string>();
  return {
    data,
    set: async (key, value) => (data.has(key) ? null : (data.set(key, value), 'OK')),
    get: async (key) => data.get(key) ?? null,
    keys: async (pattern) => {
      const re = new RegExp(`^${pattern.replace(/\\(.)/g, '$1').split('*').map((p) => p.replace(/[.+?^${}()|[\]\\]/g, '\\$&')).join('.*')}$`);
      return [...data.keys()].filter((k) => re.test(k));
    },
    pexpire: async (key) => (data.has(key) ? 1 : 0),
    del: async (key) => (data.delete(key) ? 1 : 0),
  };
}

async function refused(holding: Promise<unknown>, pattern: RegExp): Promise<void> {
  const e = await holding.then(() => undefined, (e: unknown) => e);
  expect(e).toBeInstanceOf(LanternError);
  expect((e as Error).message).toMatch(pattern);
}

describe('one farm worker a GPU', () => {
  it('knows a lone NVIDIA GPU by its UUID, from any host; else by host, adapter and the variables that select a device', () => {
    const h200 = 'NVIDIA H200 (NVIDIA 580.159.04)';
    expect(gpuIdentity(h200, {}, ['GPU-1234-abcd'], 'a').key).toBe(gpuIdentity(h200, {}, ['GPU-1234-abcd'], 'b').key);
    expect(gpuIdentity(h200, {}, ['GPU-1234-abcd'], 'a').described).toContain('GPU-1234-abcd');
    // Two GPUs seen: which one Dawn took is not known, so the selection decides.
    const two = ['GPU-1', 'GPU-2'];
    expect(gpuIdentity(h200, { DRI_PRIME: 'pci-0000_41_00_0' }, two, 'a').key).not.toBe(gpuIdentity(h200, { DRI_PRIME: 'pci-0000_61_00_0' }, two, 'a').key);
    expect(gpuIdentity(h200, {}, two, 'a').key).toBe(gpuIdentity(h200, { CUDA_VISIBLE_DEVICES: '1' }, two, 'a').key);
    expect(gpuIdentity(h200, {}, two, 'a').key).not.toBe(gpuIdentity(h200, {}, two, 'b').key);
    expect(gpuIdentity('SwiftShader', { NVIDIA_VISIBLE_DEVICES: '0' }, [], 'a').described).toBe('SwiftShader on a (NVIDIA_VISIBLE_DEVICES=0)');
  });

  it('refuses a second worker on a GPU held by one alone, and one alone on a GPU that sharers hold; sharers join each other', async () => {
    const redis = memoryRedis();
    const gpu = gpuIdentity('GPU', {}, [], 'host');
    const release = await holdGpu(redis, gpu, 'w0', false);
    await refused(holdGpu(redis, gpu, 'w1', false), /^worker w0 already renders on this GPU \(GPU on host\)/);
    await refused(holdGpu(redis, gpu, 'w1', true), /^worker w0 already renders on this GPU/);
    await release();
    expect(redis.data.size).toBe(0);
    const s1 = await holdGpu(redis, gpu, 's1', true);
    const s2 = await holdGpu(redis, gpu, 's2', true);
    await refused(holdGpu(redis, gpu, 'w2', false), /^worker s[12] already renders on this GPU/);
    // Another GPU is free.
    await (await holdGpu(redis, gpuIdentity('GPU', { DRI_PRIME: '1' }, [], 'host'), 'w3', false))();
    await s1();
    await s2();
    await (await holdGpu(redis, gpu, 'w2', false))();
    expect(redis.data.size).toBe(0);
  });
});
