/** Compiler errors point at the module and line they come from, not at the linked text. */
import { describe, expect, it } from 'vitest';
import { testGpu } from './gpu-context.ts';
import { testKernel } from './compute.ts';

describe('kernel compilation', () => {
  it('reports a WGSL error at its module and line', async () => {
    const { device } = await testGpu();
    const broken = '#import lib/random\n\nfn oops() -> u32 { return undefined_name; }\n@compute @workgroup_size(1) fn main() { _ = oops(); }';
    await expect(testKernel(device, 'test/broken', broken, 'main')).rejects.toThrow(/test\/broken\.wgsl:3:\d+: .*undefined_name/);
  });
});
