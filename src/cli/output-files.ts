/** Writing rendered images: PNG (tone-mapped sRGB) and EXR (linear radiance, float32 RGB). */
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname } from 'node:path';
import { LanternError } from '../errors.ts';
import { encodeExr } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import type { Renderer } from '../renderer/renderer.ts';

/** Writes a file, creating its folder; a failure is a LanternError naming the path. */
export function writeFile(path: string, bytes: Uint8Array): void {
  try {
    mkdirSync(dirname(path), { recursive: true });
    writeFileSync(path, bytes);
  } catch (e) {
    throw new LanternError(`cannot write '${path}': ${(e as NodeJS.ErrnoException).code ?? (e as Error).message}`);
  }
}

export async function writePng(renderer: Renderer, path: string): Promise<void> {
  writeFile(path, encodePng(renderer.width, renderer.height, await renderer.readImage()));
}

export async function writeExr(renderer: Renderer, path: string): Promise<void> {
  const { width, height, radiance } = await renderer.readAccumulation();
  writeFile(path, encodeExr(width, height, radiance));
}
