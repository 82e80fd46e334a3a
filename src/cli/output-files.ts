/** Writing rendered images: PNG (tone-mapped sRGB) and EXR (linear radiance, float32 RGB). */
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname } from 'node:path';
import { LanternError } from '../errors.ts';
import { encodeExr } from '../image/exr.ts';
import { encodePng } from '../image/png.ts';
import type { Renderer } from '../renderer/renderer.ts';

function write(path: string, bytes: Uint8Array): void {
  try {
    mkdirSync(dirname(path), { recursive: true });
    writeFileSync(path, bytes);
  } catch (e) {
    throw new LanternError(`cannot write '${path}': ${(e as NodeJS.ErrnoException).code ?? (e as Error).message}`);
  }
}

export async function writePng(renderer: Renderer, path: string): Promise<void> {
  write(path, encodePng(renderer.width, renderer.height, await renderer.readImage()));
}

export async function writeExr(renderer: Renderer, path: string): Promise<void> {
  const { width, height, radiance } = await renderer.readAccumulation();
  write(path, encodeExr(width, height, radiance));
}
