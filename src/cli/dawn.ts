/**
 * WebGPU in Node through Dawn (the `webgpu` npm package). Where the machine has no GPU driver, falls
 * back to SwiftShader, the CPU Vulkan implementation Debian's `chromium` package installs: slow, but
 * exact enough for tests and small renders. On a machine with a GPU (or with VK_ICD_FILENAMES /
 * VK_DRIVER_FILES set) the system's driver is used as is.
 *
 * Dawn and the Vulkan loader write their own diagnostics straight to file descriptor 2 (C's stderr,
 * not Node's process.stderr), and on a machine without a driver the first look for one prints
 * `vkCreateInstance: Found no drivers!` and a `VK_ERROR_INCOMPATIBLE_DRIVER` trace: lines that read
 * like a failure before Lantern's own note. Node cannot redirect its own descriptor 2, so that first
 * look runs in a child process whose stderr is kept (probeSystemGpu): Lantern shows it with
 * --verbose (onDawnOutput) and drops it otherwise. Where the child found an adapter, this process
 * looks again and finds it without a word; where it found none, SwiftShader is used at once.
 */
import { execFile } from 'node:child_process';
import { appendFileSync, existsSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { pathToFileURL } from 'node:url';
import { acquireGpu, type GpuContext } from '../gpu/device.ts';
import { LanternError } from '../errors.ts';
import type { StageListener } from '../gpu/stage-log.ts';
import { observeCompiles } from '../gpu/pipeline-compiles.ts';

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
  /** Hears what Dawn and the Vulkan loader printed while looking for the system's GPU (the CLI shows it with --verbose). */
  readonly onDawnOutput?: (text: string) => void;
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

/**
 * LANTERN_PIPELINE_LOG=<file>: every pipeline this process compiles is appended to the file, a line
 * each (its label and variant, and the compile's milliseconds), so that a test or a person can count
 * what a command compiles.
 */
export const PIPELINE_LOG_ENV = 'LANTERN_PIPELINE_LOG';

function logPipelines(gpu: GpuContext): GpuContext {
  const file = process.env[PIPELINE_LOG_ENV];
  if (!file) return gpu;
  const logged = new Set<string>();
  observeCompiles(gpu.device, ({ compiles }) => {
    for (const c of compiles) {
      const id = `${c.key}@${c.requestedMs}`;
      if (c.endMs === undefined || c.startMs === undefined || logged.has(id)) continue;
      logged.add(id);
      appendFileSync(file, `${c.key}\t${(c.endMs - c.startMs).toFixed(0)} ms\n`);
    }
  });
  return gpu;
}

export async function acquireNodeGpu(options: NodeGpuOptions = {}): Promise<GpuContext> {
  return logPipelines(await acquireDawnGpu(options));
}

async function acquireDawnGpu(options: NodeGpuOptions): Promise<GpuContext> {
  const t0 = performance.now();
  const dawnOptions = [...DEFAULT_DAWN_OPTIONS, ...(options.dawnOptions ?? []), ...environmentDawnOptions()];
  // The Vulkan loader complains on every start without it.
  process.env.XDG_RUNTIME_DIR ??= tmpdir();
  const driverChosen = process.env.VK_ICD_FILENAMES !== undefined || process.env.VK_DRIVER_FILES !== undefined;
  const probeFirst = !options.forceSwiftShader && !driverChosen;
  // The child looks for the system's GPU while this process loads Dawn.
  const probing = probeFirst ? probeSystemGpu(dawnOptions) : undefined;
  const { create } = await loadDawn();
  options.onStage?.({ stage: 'load Dawn', startMs: t0, endMs: performance.now() });
  const stages = options.onStage ? { onStage: options.onStage } : {};
  if (options.forceSwiftShader) useSwiftShader();
  else if (probing) {
    const t1 = performance.now();
    const probe = await probing;
    if (probe?.output) options.onDawnOutput?.(probe.output);
    options.onStage?.({ stage: 'look for a GPU (child process)', startMs: t1, endMs: performance.now() });
    // Where the child found a GPU, this process finds it too, and its adapter is the one to use. A
    // probe that could not run says nothing either way: this process looks itself then, as it did
    // before the probe existed (Dawn's lines reach stderr).
    if (probe?.found !== false) {
      const t2 = performance.now();
      const instance = createInstance(create, dawnOptions);
      const adapter = await instance.requestAdapter({ powerPreference: 'high-performance' });
      options.onStage?.({ stage: 'adapter', startMs: t2, endMs: performance.now() });
      if (adapter) return acquireGpu(instance, { adapter, ...stages });
    }
    if (existsSync(SWIFTSHADER_ICD)) {
      useSwiftShader();
      options.onNote?.('no GPU adapter found; rendering on the CPU with SwiftShader (slow)');
    }
  }
  return acquireGpu(createInstance(create, dawnOptions), stages);
}

/** What the child process's look for the system's GPU found, and what Dawn and Vulkan printed meanwhile. */
interface SystemGpuProbe {
  readonly found: boolean;
  readonly output: string;
}

/**
 * The child's program: Dawn (the `webgpu` module this process would load, by URL) asked for an adapter
 * with this process's options, the answer on stdout. Exits at once: Dawn's threads would keep it alive.
 */
const PROBE_PROGRAM = `
const { create } = await import(process.env.LANTERN_PROBE_DAWN);
const adapter = await create(JSON.parse(process.env.LANTERN_PROBE_OPTIONS)).requestAdapter({ powerPreference: 'high-performance' });
process.stdout.write(adapter ? 'found' : 'none', () => process.exit(0));
`;

/** A driver that takes longer than this to answer is looked for in this process instead. */
const PROBE_TIMEOUT_MS = 30_000;

/** Undefined when the probe could not run or answer (no Node to start, a crash, a timeout). */
function probeSystemGpu(dawnOptions: readonly string[]): Promise<SystemGpuProbe | undefined> {
  let dawnUrl: string;
  try {
    dawnUrl = pathToFileURL(createRequire(import.meta.url).resolve('webgpu')).href;
  } catch {
    return Promise.resolve(undefined);
  }
  const env = { ...process.env, LANTERN_PROBE_DAWN: dawnUrl, LANTERN_PROBE_OPTIONS: JSON.stringify(dawnOptions) };
  return new Promise((resolve) => {
    execFile(process.execPath, ['--input-type=module', '--eval', PROBE_PROGRAM], { env, timeout: PROBE_TIMEOUT_MS, maxBuffer: 1 << 20, encoding: 'utf8' }, (error, stdout, stderr) => {
      resolve(error || (stdout !== 'found' && stdout !== 'none') ? undefined : { found: stdout === 'found', output: stderr });
    });
  });
}

function useSwiftShader(): void {
  if (!existsSync(SWIFTSHADER_ICD)) {
    throw new LanternError(`SwiftShader is not installed (${SWIFTSHADER_ICD} is missing)`, 'Install it with `apt-get install chromium`');
  }
  process.env.VK_ICD_FILENAMES = SWIFTSHADER_ICD;
  delete process.env.VK_DRIVER_FILES;
}
