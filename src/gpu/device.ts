/**
 * Device acquisition, the same for the browser (navigator.gpu) and Node (Dawn's `webgpu` package, see
 * cli/dawn.ts). Asks for the adapter's real limits rather than WebGPU's defaults, so large scenes fit
 * (the default 128 MiB storage binding holds only ~1.6M triangles of shading data), and for
 * timestamp queries where the adapter has them.
 */
import { LanternError } from '../errors.ts';
import { ResourceCounter } from './resource-count.ts';
import type { StageListener } from './stage-log.ts';

export interface GpuContext {
  readonly device: GPUDevice;
  /**
   * Held for the device's lifetime: Dawn (in Node, and in Chromium) rejects pending promises with "a
   * valid external Instance reference no longer exists" once the adapter is garbage-collected.
   */
  readonly adapter: GPUAdapter;
  /** A human-readable adapter name, e.g. "NVIDIA H100 80GB HBM3" or "SwiftShader". */
  readonly adapterName: string;
  readonly hasTimestamps: boolean;
  /** Resolves when the device is lost (destroyed, driver reset, GPU removed). */
  readonly lost: Promise<GPUDeviceLostInfo>;
  /** Live buffers and textures of the device (what leaks shows here). */
  readonly resources: ResourceCounter;
}

const LIMITS_TO_RAISE = [
  'maxStorageBufferBindingSize',
  'maxBufferSize',
  'maxStorageBuffersPerShaderStage',
  'maxComputeWorkgroupsPerDimension',
  'maxComputeWorkgroupStorageSize',
  'maxComputeInvocationsPerWorkgroup',
  'maxTextureDimension2D',
  // A scene's texture atlas has a layer per page (scene-limits.ts checks the scene against these).
  'maxTextureArrayLayers',
  'maxUniformBufferBindingSize',
] as const;

/**
 * A readable adapter name from whatever the implementation fills in: Dawn on NVIDIA gives vendor
 * "nvidia", architecture "hopper" and the driver version as description; SwiftShader gives a device
 * string; browsers often give vendor and architecture only.
 */
export function adapterName(info: GPUAdapterInfo): string {
  const name = info.device || [info.vendor, info.architecture].filter(Boolean).join(' ');
  const detail = info.description && info.description !== name ? info.description : '';
  if (!name) return detail || 'unknown adapter';
  return detail ? `${name} (${detail})` : name;
}

export async function acquireGpu(
  gpu: GPU | undefined,
  options: {
    powerPreference?: GPUPowerPreference;
    onUncapturedError?: (message: string) => void;
    /** An adapter already requested from `gpu` (Node asks once to see whether there is a GPU at all). */
    adapter?: GPUAdapter;
    /** Hears how long the adapter and the device took (start-up timelines). */
    onStage?: StageListener;
  } = {},
): Promise<GpuContext> {
  if (!gpu) {
    throw new LanternError('WebGPU is not available here', 'Use a browser with WebGPU (Chrome or Edge 113+, Safari 26+, Firefox 141+ on Windows) or run the CLI');
  }
  const t0 = performance.now();
  const adapter = options.adapter ?? (await gpu.requestAdapter({ powerPreference: options.powerPreference ?? 'high-performance' }));
  const t1 = performance.now();
  if (!options.adapter) options.onStage?.({ stage: 'adapter', startMs: t0, endMs: t1 });
  if (!adapter) {
    throw new LanternError('no WebGPU adapter found', 'Check the GPU driver (Vulkan on Linux); without a GPU install Chromium\'s SwiftShader with `apt-get install chromium`');
  }
  const requiredLimits: Record<string, number> = {};
  for (const name of LIMITS_TO_RAISE) requiredLimits[name] = adapter.limits[name];
  const hasTimestamps = adapter.features.has('timestamp-query');
  const device = await adapter.requestDevice({
    label: 'lantern',
    requiredFeatures: hasTimestamps ? ['timestamp-query'] : [],
    requiredLimits,
  });
  options.onStage?.({ stage: 'device', startMs: t1, endMs: performance.now() });
  device.onuncapturederror = (event: GPUUncapturedErrorEvent) => {
    const message = `WebGPU error: ${event.error.message}`;
    if (options.onUncapturedError) options.onUncapturedError(message);
    else console.error(message);
  };
  const resources = new ResourceCounter(device);
  return { device, adapter, adapterName: adapterName(adapter.info), hasTimestamps, lost: device.lost, resources };
}

/**
 * Runs `create` inside validation and out-of-memory error scopes and turns a captured error into a
 * LanternError naming `what`, so that a failed allocation is reported where it happened.
 */
export async function withErrorScope<T>(device: GPUDevice, what: string, create: () => T): Promise<T> {
  device.pushErrorScope('out-of-memory');
  device.pushErrorScope('validation');
  const result = create();
  const validation = await device.popErrorScope();
  const oom = await device.popErrorScope();
  const error = oom ?? validation;
  if (error) {
    const kind = oom ? 'the GPU ran out of memory' : 'WebGPU rejected it';
    throw new LanternError(`could not create ${what}: ${kind}: ${error.message}`);
  }
  return result;
}
