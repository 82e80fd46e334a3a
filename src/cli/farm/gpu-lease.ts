/**
 * One worker a GPU (issue #31): a `farm worker` holds a lease on its GPU in Redis for as long as it
 * runs, and a second worker that would render on the same GPU is refused in one line, unless both
 * say `--share-gpu` (N workers on one GPU on purpose).
 *
 * Which GPU a worker renders on is decided by its environment (docs/farm.md, GPU selection), and
 * Dawn cannot name the physical device it picked. So the GPU is known as:
 * - its UUID, when `nvidia-smi -L` sees exactly one NVIDIA GPU (a container given one GPU with
 *   NVIDIA_VISIBLE_DEVICES, a machine with one): the same GPU from any container or host name;
 * - else this host, the adapter's name and the variables that select a device (DRI_PRIME,
 *   MESA_VK_DEVICE_SELECT, NVIDIA_VISIBLE_DEVICES, LANTERN_DAWN_OPTIONS, VK_ICD_FILENAMES): two
 *   workers on one host asking for the same device the same way share it, and are told so.
 * What this cannot see: two containers on one host that each see all its GPUs, or a selection
 * variable that selects nothing (Mesa's device-select layer not installed). docs/farm.md says so.
 */
import { spawnSync } from 'node:child_process';
import { hostname } from 'node:os';
import { LanternError } from '../../errors.ts';

/** The environment variables that choose which device a Vulkan or Dawn process gets. */
export const GPU_SELECTION_ENV = ['NVIDIA_VISIBLE_DEVICES', 'DRI_PRIME', 'MESA_VK_DEVICE_SELECT', 'MESA_VK_DEVICE_SELECT_FORCE_DEFAULT_DEVICE', 'LANTERN_DAWN_OPTIONS', 'VK_ICD_FILENAMES'] as const;

export interface GpuIdentity {
  /** The lease's Redis key. */
  readonly key: string;
  /** How the GPU is known, for the logs and the refusal. */
  readonly described: string;
}

/** The UUIDs `nvidia-smi -L` lists (none where it is missing or fails). */
export function nvidiaGpuUuids(): string[] {
  const r = spawnSync('nvidia-smi', ['-L'], { encoding: 'utf8', timeout: 5000 });
  if (r.status !== 0 || !r.stdout) return [];
  return [...r.stdout.matchAll(/\(UUID: (GPU-[0-9a-fA-F-]+)\)/g)].map((m) => m[1]!);
}

export function gpuIdentity(adapterName: string, env: NodeJS.ProcessEnv = process.env, uuids: readonly string[] = nvidiaGpuUuids(), host: string = hostname()): GpuIdentity {
  if (uuids.length === 1 && /nvidia/i.test(adapterName)) return { key: `lantern:farm:gpu:${uuids[0]}`, described: `${adapterName} ${uuids[0]}` };
  const selection = GPU_SELECTION_ENV.filter((name) => env[name]).map((name) => `${name}=${env[name]}`);
  const described = `${adapterName} on ${host}${selection.length ? ` (${selection.join(' ')})` : ''}`;
  return { key: `lantern:farm:gpu:${host}:${adapterName}:${selection.join(' ')}`, described };
}

/** What the lease needs of a Redis client (ioredis's, through BullMQ). */
export interface LeaseClient {
  set(key: string, value: string, px: 'PX', ms: number, nx: 'NX'): Promise<string | null>;
  get(key: string): Promise<string | null>;
  keys(pattern: string): Promise<string[]>;
  pexpire(key: string, ms: number): Promise<number>;
  del(key: string): Promise<number>;
}

/** How long a lease lasts unrenewed: a killed worker's GPU is free again within this long. */
export const LEASE_MS = 15_000;

const escapePattern = (key: string) => key.replace(/[*?[\]\\]/g, (c) => `\\${c}`);

/**
 * Takes the GPU's lease for `worker`, renewed every third of LEASE_MS until the returned release is
 * called. A worker alone on its GPU holds the GPU's key; sharing workers (--share-gpu) hold a key
 * each beside it. Refused (LanternError, one line) when the GPU is held otherwise: by another worker
 * alone, or by sharers when this one would be alone.
 */
export async function holdGpu(client: LeaseClient, gpu: GpuIdentity, worker: string, share: boolean): Promise<() => Promise<void>> {
  const key = share ? `${gpu.key}:shared:${worker}` : gpu.key;
  const refuse = (holder: string, hint: string): never => {
    throw new LanternError(`worker ${holder} already renders on this GPU (${gpu.described})`, `${hint}; a worker that was killed frees it within ${LEASE_MS / 1000} s`);
  };
  const alone = await client.get(gpu.key);
  if (alone !== null && alone !== worker) refuse(alone, 'Give each worker its own GPU (docs/farm.md, GPU selection)');
  if (!share) {
    const sharers = (await client.keys(`${escapePattern(gpu.key)}:shared:*`)).filter((k) => k !== key);
    if (sharers.length > 0) refuse(sharers[0]!.slice(`${gpu.key}:shared:`.length), 'Give each worker its own GPU, or start this one with --share-gpu too');
  }
  if ((await client.set(key, worker, 'PX', LEASE_MS, 'NX')) === null && (await client.get(key)) !== worker) refuse((await client.get(key)) ?? '?', 'Give each worker its own GPU (docs/farm.md, GPU selection), or start both with --share-gpu to share it on purpose');
  const timer = setInterval(() => {
    client.pexpire(key, LEASE_MS).catch(() => undefined);
  }, LEASE_MS / 3);
  timer.unref();
  return async () => {
    clearInterval(timer);
    if ((await client.get(key)) === worker) await client.del(key);
  };
}
