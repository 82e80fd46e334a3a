/** Writing rendered images: PNG (tone-mapped sRGB) and EXR (linear radiance, float32 RGB). */
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname } from 'node:path';
import { deflateSync } from 'node:zlib';
import { LanternError } from '../errors.ts';
import { encodeExr } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import type { Renderer } from '../renderer/renderer.ts';
import type { Timeline } from './timeline.ts';

/** Writes a file, creating its folder; a failure is a LanternError naming the path. */
export function writeFile(path: string, bytes: Uint8Array): void {
  try {
    mkdirSync(dirname(path), { recursive: true });
    writeFileSync(path, bytes);
  } catch (e) {
    throw new LanternError(`cannot write '${path}': ${(e as NodeJS.ErrnoException).code ?? (e as Error).message}`);
  }
}

/** Node's own zlib (C): several times faster than the portable one for a large image, the same bytes out of the decoder. */
const nativeZlib = (raw: Uint8Array): Uint8Array => deflateSync(raw, { level: 3 });

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
  const values = await renderer.readDebugValues();
  const rgb = new Float32Array(renderer.width * renderer.height * 3);
  for (let i = 0; i < rgb.length / 3; i++) rgb.set(values.subarray(i * 4, i * 4 + 3), i * 3);
  writeFile(path, encodeExr(renderer.width, renderer.height, rgb));
}

export async function writeExr(renderer: Renderer, path: string): Promise<void> {
  const { width, height, radiance } = await renderer.readAccumulation();
  writeFile(path, encodeExr(width, height, radiance));
}
