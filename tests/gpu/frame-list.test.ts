/**
 * `render --frames 1-1,3` (issue #31): listed frames of a sequence equal the whole sequence's frames
 * byte for byte, the temporal history, the frames' sample indices and the exposure carried over by
 * rendering the frames before them (cli/commands/render-frames.ts renderFrames), and only the
 * listed frames are written.
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

async function frames(list: { frames: number } | { frames: { list: number[] } }, out: string): Promise<void> {
  const renderer = await Renderer.create(await testGpu());
  try {
    const scene = builtinScene('cornell');
    await renderer.setScene(scene);
    await renderer.resize(8, 6);
    renderer.updateSettings({ temporal: true, maxBounces: 2 });
    renderer.setCamera(scene.camera);
    await renderFrames(renderer, scene.camera, 1, { temporal: true, fps: 10, ...list }, { png: out });
  } finally {
    renderer.destroy();
  }
}

describe('frame lists', () => {
  it('write the listed frames only, each the same as in the whole sequence', async () => {
    await frames({ frames: 4 }, join(dir, 'whole'));
    await frames({ frames: { list: [1, 3] } }, join(dir, 'part'));
    expect(readdirSync(join(dir, 'part')).sort()).toEqual(['frame-0001.png', 'frame-0003.png']);
    for (const f of ['frame-0001.png', 'frame-0003.png']) expect(readFileSync(join(dir, 'part', f)).equals(readFileSync(join(dir, 'whole', f))), f).toBe(true);
    // The history changes frames: frame 3 is not frame 1.
    expect(readFileSync(join(dir, 'whole', 'frame-0003.png')).equals(readFileSync(join(dir, 'whole', 'frame-0001.png')))).toBe(false);
  });
});
