/**
 * One SwiftShader device per test file. SwiftShader is forced so that results do not depend on the
 * machine running the tests.
 */
import { acquireNodeGpu } from '../../src/cli/dawn.ts';
import type { GpuContext } from '../../src/gpu/device.ts';

let context: Promise<GpuContext> | undefined;

export function testGpu(): Promise<GpuContext> {
  context ??= acquireNodeGpu({ forceSwiftShader: true });
  return context;
}
