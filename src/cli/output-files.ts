/** Writing rendered images: PNG (tone-mapped sRGB) and EXR (linear radiance, float32 RGB). */
import { accessSync, constants, mkdirSync, realpathSync, renameSync, rmSync, statfsSync, statSync, writeFileSync, type Stats } from 'node:fs';
import { basename, dirname, join, resolve, sep } from 'node:path';
import { promisify } from 'node:util';
import { deflate, deflateSync } from 'node:zlib';
import { LanternError } from '../errors.ts';
import { encodeExrAsync, type ChunkDeflate } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import type { Renderer } from '../renderer/renderer.ts';
import type { Timeline } from './timeline.ts';

/**
 * Folders of the kernel's pseudo file systems: nothing Lantern writes belongs there, and Node's
 * recursive mkdir never returns on a missing folder under /proc (it retries ENOENT forever).
 */
const SPECIAL_FOLDERS = ['/proc', '/sys', '/dev'];
// statfs f_type of procfs, sysfs, cgroup, cgroup2, debugfs, securityfs, tracefs: the same file systems mounted elsewhere.
const SPECIAL_FILE_SYSTEMS = new Set([0x9fa0, 0x62656572, 0x27e0eb, 0x63677270, 0x64626720, 0x73636673, 0x74726163]);

const statOrUndefined = (path: string): Stats | undefined => {
  try {
    return statSync(path);
  } catch {
    return undefined;
  }
};

/**
 * What is wrong with writing `path` (a file, or a folder that files go into), or undefined when
 * nothing is: checked before any work starts, so that a long render is not lost at the end. The
 * folders to create are not created here; only the nearest existing one must be a writable,
 * ordinary folder.
 */
export function outputPathProblem(path: string, kind: 'file' | 'folder'): string | undefined {
  if (path.trim() === '') return 'the name is empty';
  const full = resolve(path);
  const existing = statOrUndefined(full);
  if (existing && kind === 'file' && existing.isDirectory()) return 'it is a folder';
  if (existing && kind === 'folder' && !existing.isDirectory()) return 'it is a file, not a folder';
  let ancestor = existing?.isDirectory() ? full : dirname(full);
  let stat = statOrUndefined(ancestor);
  while (!stat && dirname(ancestor) !== ancestor) {
    ancestor = dirname(ancestor);
    stat = statOrUndefined(ancestor);
  }
  if (!stat) return 'no folder on its path exists';
  if (!stat.isDirectory()) return `${ancestor} is a file, not a folder`;
  const real = realpathSync(ancestor);
  if (SPECIAL_FOLDERS.some((f) => real === f || real.startsWith(f + sep)) || SPECIAL_FILE_SYSTEMS.has(Number(statfsSync(real).type))) {
    return `${real} is a system folder (${SPECIAL_FOLDERS.join(', ')}), not a place for files`;
  }
  try {
    accessSync(ancestor, constants.W_OK);
  } catch {
    return `the folder ${ancestor} is not writable`;
  }
  return undefined;
}

/** outputPathProblem as a LanternError naming the option. */
export function checkOutputPath(option: string, path: string, kind: 'file' | 'folder'): void {
  const problem = outputPathProblem(path, kind);
  if (problem) throw new LanternError(`${option}: cannot write '${path}': ${problem}`);
}

/**
 * Writes a file, creating its folder; a failure is a LanternError naming the path. The bytes go to a
 * temporary name beside it first and are renamed into place, so a reader (a farm's merge, a worker
 * doing the same chunk again) sees the whole file or none, and the same file written twice is one.
 */
export function writeFile(path: string, bytes: Uint8Array): void {
  const problem = outputPathProblem(path, 'file');
  if (problem) throw new LanternError(`cannot write '${path}': ${problem}`);
  const temporary = join(dirname(path), `.${basename(path)}.${process.pid}.tmp`);
  try {
    mkdirSync(dirname(path), { recursive: true });
    writeFileSync(temporary, bytes);
    renameSync(temporary, path);
  } catch (e) {
    rmSync(temporary, { force: true });
    throw new LanternError(`cannot write '${path}': ${(e as NodeJS.ErrnoException).code ?? (e as Error).message}`);
  }
}

/** Node's own zlib (C): several times faster than the portable one for a large image, the same bytes out of the decoder. */
export const nativeZlib = (raw: Uint8Array): Uint8Array => deflateSync(raw, { level: 3 });

/** An EXR chunk through Node's zlib at OpenEXR's level 4 (the frame writer's threads; the file decodes to the same pixels as fflate's). */
export const nativeExrDeflate: ChunkDeflate = (filtered) => deflateSync(filtered, { level: 4 });

const deflateAsync = promisify(deflate);

/**
 * An EXR with its chunks compressed in parallel on Node's thread pool (libuv's, 4 threads unless
 * UV_THREADPOOL_SIZE says otherwise): a 4K image is 135 chunks of 16 scanlines, which fflate
 * compressed one after another on the main thread.
 */
export const encodeExrNative = (width: number, height: number, rgb: Float32Array): Promise<Uint8Array> =>
  encodeExrAsync(width, height, rgb, {}, (chunks) => Promise.all(chunks.map((c) => deflateAsync(c, { level: 4 }))));

export async function writePng(renderer: Renderer, path: string, timeline?: Timeline): Promise<void> {
  const t0 = performance.now();
  const rgba = await renderer.readImage();
  const t1 = performance.now();
  const png = encodePng(renderer.width, renderer.height, rgba, nativeZlib);
  const t2 = performance.now();
  writeFile(path, png);
  if (timeline) {
    timeline.add({ stage: 'tone map + read back', startMs: t0, endMs: t1 });
    timeline.add({ stage: 'PNG encode', startMs: t1, endMs: t2 });
    timeline.end('PNG write', t2);
  }
}

/** The debug view's raw values as EXR: R, G, B = the first three of shaders/passes/debug-view.wgsl's four. */
export async function writeDebugExr(renderer: Renderer, path: string): Promise<void> {
  writeFile(path, await encodeExrNative(renderer.width, renderer.height, await readDebugRgb(renderer)));
}

/** The debug view's raw values, the first three of each pixel's four (what an EXR of a debug view holds). */
export async function readDebugRgb(renderer: Renderer): Promise<Float32Array> {
  const values = await renderer.readDebugValues();
  const rgb = new Float32Array(renderer.width * renderer.height * 3);
  for (let i = 0; i < rgb.length / 3; i++) rgb.set(values.subarray(i * 4, i * 4 + 3), i * 3);
  return rgb;
}

export async function writeExr(renderer: Renderer, path: string): Promise<void> {
  const { width, height, radiance } = await renderer.readAccumulation();
  writeFile(path, await encodeExrNative(width, height, radiance));
}
