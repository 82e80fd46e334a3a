/**
 * `render --frames 1-1,3` (issue #31): listed frames of a sequence equal the whole sequence's frames
 * byte for byte, the temporal history, the frames' sample indices and the exposure carried over by
 * rendering the frames before them (cli/commands/render-frames.ts renderFrames), and only the
 * listed frames are written; without history (no temporal pass), only the listed frames and the
 * frame before each are traced, the sample index set to what the frames skipped would have left.
 */
import { mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { renderFrames } from '../../src/cli/commands/render-frames.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';

const dir = mkdtempSync(join(tmpdir(), 'lantern-frames-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

async function frames(list: { frames: number } | { frames: { list: number[] } }, out: string, temporal = true): Promise<void> {
  const renderer = await Renderer.create(await testGpu());
  try {
    const scene = builtinScene('cornell');
    await renderer.setScene(scene);
    await renderer.resize(8, 6);
    renderer.updateSettings({ temporal, maxBounces: 2 });
    renderer.setCamera(scene.camera);
    await renderFrames(renderer, scene.camera, 1, { temporal, fps: 10, ...list }, { png: out, exr: out });
  } finally {
    renderer.destroy();
  }
}

describe('frame lists', () => {
  it('write the listed frames only, each the same as in the whole sequence', async () => {
    await frames({ frames: 4 }, join(dir, 'whole'));
    await frames({ frames: { list: [1, 3] } }, join(dir, 'part'));
    expect(readdirSync(join(dir, 'part')).sort()).toEqual(['frame-0001.exr', 'frame-0001.png', 'frame-0003.exr', 'frame-0003.png']);
    for (const f of ['frame-0001.png', 'frame-0003.png', 'frame-0001.exr', 'frame-0003.exr']) expect(readFileSync(join(dir, 'part', f)).equals(readFileSync(join(dir, 'whole', f))), f).toBe(true);
    // The history changes frames: frame 3 is not frame 1.
    expect(readFileSync(join(dir, 'whole', 'frame-0003.png')).equals(readFileSync(join(dir, 'whole', 'frame-0001.png')))).toBe(false);
  });

  it('without history, trace only the listed frames and the frame before each, and still equal the whole sequence', async () => {
    await frames({ frames: 6 }, join(dir, 'whole-free'), false);
    await frames({ frames: { list: [4] } }, join(dir, 'part-free'), false);
    for (const f of ['frame-0004.png', 'frame-0004.exr']) expect(readFileSync(join(dir, 'part-free', f)).equals(readFileSync(join(dir, 'whole-free', f))), f).toBe(true);
  });
});
