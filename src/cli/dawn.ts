/**
 * WebGPU in Node through Dawn (the `webgpu` npm package). Where the machine has no GPU driver, falls
 * back to SwiftShader, the CPU Vulkan implementation Debian's `chromium` package installs: slow, but
 * exact enough for tests and small renders. On a machine with a GPU (or with VK_ICD_FILENAMES /
 * VK_DRIVER_FILES set) the system's driver is used as is.
 */
import { existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { acquireGpu, type GpuContext } from '../gpu/device.ts';
import { LanternError } from '../errors.ts';
import type { StageListener } from '../gpu/stage-log.ts';

export const SWIFTSHADER_ICD = '/usr/lib/chromium/vk_swiftshader_icd.json';

type DawnModule = { create: (options: string[]) => GPU; globals: Record<string, unknown> };

let dawn: DawnModule | undefined;

// Every Dawn instance this process creates stays referenced until exit: Dawn for Node (webgpu 0.6)
// frees the native instance when its JS object is garbage-collected, even while a device made from it
// is alive, and the process then aborts in a driver thread.
const liveInstances: GPU[] = [];

function createInstance(create: DawnModule['create'], options: string[]): GPU {
  const gpu = create(options);
  liveInstances.push(gpu);
  return gpu;
}

async function loadDawn(): Promise<DawnModule> {
  if (!dawn) {
    try {
      dawn = (await import('webgpu')) as unknown as DawnModule;
    } catch (e) {
      throw new LanternError(`could not load Dawn (the 'webgpu' package): ${(e as Error).message}`, 'Run `npm ci` in the Lantern folder', { cause: e });
    }
    // WebGPU constants (GPUBufferUsage, GPUMapMode, ...) that browser code expects as globals.
    Object.assign(globalThis, dawn.globals);
  }
  return dawn;
}

export interface NodeGpuOptions {
  /** Dawn options, e.g. 'backend=vulkan' or 'adapter=<name>'. */
  readonly dawnOptions?: string[];
  /** Called with a one-line note when Lantern falls back to SwiftShader. */
  readonly onNote?: (note: string) => void;
  /** Use SwiftShader even where a GPU exists (tests: identical results on every machine). */
  readonly forceSwiftShader?: boolean;
  /** Hears how long each step took: loading Dawn, the adapter, the device (start-up timelines). */
  readonly onStage?: StageListener;
}

/**
 * Dawn quantizes timestamp queries by default (a browser defence against timing attacks, 65.5 µs
 * steps here), which makes sub-millisecond pass timings meaningless for a local benchmark.
 */
const DEFAULT_DAWN_OPTIONS = ['disable-dawn-features=timestamp_quantization'];

/**
 * Extra Dawn options from the environment, space-separated (LANTERN_DAWN_OPTIONS, e.g.
 * 'enable-dawn-features=disable_robustness'): for measuring what a Dawn toggle changes.
 */
function environmentDawnOptions(): string[] {
  return (process.env.LANTERN_DAWN_OPTIONS ?? '').split(/\s+/).filter((o) => o !== '');
}

export async function acquireNodeGpu(options: NodeGpuOptions = {}): Promise<GpuContext> {
  const t0 = performance.now();
  const { create } = await loadDawn();
  options.onStage?.({ stage: 'load Dawn', startMs: t0, endMs: performance.now() });
  const dawnOptions = [...DEFAULT_DAWN_OPTIONS, ...(options.dawnOptions ?? []), ...environmentDawnOptions()];
  // The Vulkan loader complains on every start without it.
  process.env.XDG_RUNTIME_DIR ??= tmpdir();
  const driverChosen = process.env.VK_ICD_FILENAMES !== undefined || process.env.VK_DRIVER_FILES !== undefined;
  const stages = options.onStage ? { onStage: options.onStage } : {};
  if (options.forceSwiftShader) useSwiftShader();
  else if (!driverChosen) {
    // Where a GPU answers, its adapter is the one to use: no second instance, no second enumeration.
    const t1 = performance.now();
    const instance = createInstance(create, dawnOptions);
    const adapter = await instance.requestAdapter({ powerPreference: 'high-performance' });
    options.onStage?.({ stage: 'adapter', startMs: t1, endMs: performance.now() });
    if (adapter) return acquireGpu(instance, { adapter, ...stages });
    if (existsSync(SWIFTSHADER_ICD)) {
      useSwiftShader();
      options.onNote?.('no GPU adapter found; rendering on the CPU with SwiftShader (slow)');
    }
  }
  return acquireGpu(createInstance(create, dawnOptions), stages);
}

function useSwiftShader(): void {
  if (!existsSync(SWIFTSHADER_ICD)) {
    throw new LanternError(`SwiftShader is not installed (${SWIFTSHADER_ICD} is missing)`, 'Install it with `apt-get install chromium`');
  }
  process.env.VK_ICD_FILENAMES = SWIFTSHADER_ICD;
  delete process.env.VK_DRIVER_FILES;
}
