/**
 * One SwiftShader device for the test process: the gpu project is not isolated (vitest.config.ts), so
 * every GPU test file shares it, and a pipeline compiled by one file is not compiled again by the next
 * (kernel.ts caches shader modules per device; Dawn returns the pipeline it already made). Tests
 * destroy what they create; resource counts are compared before and after, never as totals.
 * SwiftShader is forced so that results do not depend on the machine running the tests.
 */
import { acquireNodeGpu } from '../../src/cli/dawn.ts';
import type { GpuContext } from '../../src/gpu/device.ts';

let context: Promise<GpuContext> | undefined;

export function testGpu(): Promise<GpuContext> {
  context ??= acquireNodeGpu({ forceSwiftShader: true });
  return context;
}
