/**
 * Frames cut into row bands (Renderer.beginAccumulate, beginFrame: the viewer's short submissions)
 * are bit for bit the unsplit frames: the progressive estimate, the real-time chain's output over two
 * frames with a camera move between them (so the second reprojects the first), and the ray counts,
 * without and with ReSTIR (whose G-buffer and reservoir passes run over the whole image with the first
 * chunk: the spatial reuse reads across band edges, and the second frame reuses the first's reservoirs).
 * A chunk of a frame given up (a change came mid-frame) leaves the real-time history as it was, the
 * ReSTIR reservoirs included.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { SplitFrame } from '../../src/renderer/split-frame.ts';
import { GpuTimer } from '../../src/gpu/timestamps.ts';
import type { Camera } from '../../src/scene/types.ts';
import { testGpu } from './gpu-context.ts';

const WIDTH = 40;
const HEIGHT = 28;
/** Chunks of uneven sizes, none a whole number of workgroups (8): tile origins off the workgroup grid, bands in pieces. */
const CHUNKS: readonly (readonly [number, number])[] = [[5, WIDTH], [9, 13], [9, 100], [3, 7], [3, 11], [3, 100], [100, 100]];

const scene = prepareScene(builtinScene('cornell'));
const cameraA: Camera = scene.scene.camera;
const cameraB: Camera = { ...cameraA, position: [cameraA.position[0] + 20, cameraA.position[1] + 5, cameraA.position[2]] };

let unsplit: Renderer;
let split: Renderer;
beforeAll(async () => {
  const gpu = await testGpu();
  [unsplit, split] = await Promise.all([Renderer.create(gpu), Renderer.create(gpu)]);
  for (const r of [unsplit, split]) {
    await r.compile({}, { frames: true });
    await r.setScene(scene);
    await r.resize(WIDTH, HEIGHT);
  }
  // Compiling the path tracers on SwiftShader alone (when no other test file compiled them first) takes over a minute on a loaded machine.
}, 300_000);
afterAll(() => {
  unsplit?.destroy();
  split?.destroy();
});

/** Submits a split frame chunk by chunk, waiting for each as the viewer does. */
async function submitInBands(renderer: Renderer, frame: SplitFrame): Promise<number> {
  let submissions = 0;
  for (let i = 0; !frame.done; i++) {
    const [rows, columns] = CHUNKS[i % CHUNKS.length]!;
    frame.submitChunk(rows, columns);
    submissions++;
    await renderer.finish();
  }
  return submissions;
}

const bytes = (a: Float32Array) => Buffer.from(a.buffer, a.byteOffset, a.byteLength);

describe('split frames', () => {
  it('progressive: bands of a frame add exactly the samples of the unsplit dispatch', async () => {
    for (const r of [unsplit, split]) {
      r.setCamera(cameraA);
      r.resetAccumulation();
    }
    for (let round = 0; round < 2; round++) {
      unsplit.accumulate(2);
      expect(await submitInBands(split, split.beginAccumulate(2))).toBe(7);
    }
    const [a, b] = await Promise.all([unsplit.readAccumulation(), split.readAccumulation()]);
    expect(b.samples).toBe(4);
    expect(a.samples).toBe(4);
    expect(bytes(b.radiance).equals(bytes(a.radiance))).toBe(true);
    expect(bytes(b.luminanceVariance).equals(bytes(a.luminanceVariance))).toBe(true);
    expect(await split.readRayCounts()).toEqual(await unsplit.readRayCounts());
  });

  for (const restir of [false, true]) {
    it(`real time${restir ? ' with ReSTIR' : ''}: banded frames, one given up mid-way, equal the unsplit frames and their history`, async () => {
      for (const r of [unsplit, split]) {
        r.updateSettings({ restir });
        if (restir) await r.compile({ restir: true }, { frames: true });
        r.setCamera(cameraA);
        r.resetHistory();
      }
      unsplit.renderFrame(1);
      await submitInBands(split, split.beginFrame(1));
      const first = await unsplit.readFrame();
      expect(bytes((await split.readFrame()).radiance).equals(bytes(first.radiance))).toBe(true);

      // A frame begun at another pose, overtaken by a camera change after its first band: given up.
      split.setCamera({ ...cameraA, vfovDegrees: cameraA.vfovDegrees * 0.5 });
      const overtaken = split.beginFrame(1);
      overtaken.submitChunk(8);
      split.setCamera(cameraB);
      expect(overtaken.valid).toBe(false);
      overtaken.abandon();
      expect(() => overtaken.submitChunk(8)).toThrow(/abandoned|overtaken/);

      unsplit.setCamera(cameraB);
      unsplit.renderFrame(1);
      // Timed: the passes each chunk recorded, in order.
      expect(split.gpu.hasTimestamps).toBe(true);
      const timer = new GpuTimer(split.device);
      const chunks = await submitInBands(split, split.beginFrame(1, timer));
      const passes = (await timer.read()).map((p) => p.name);
      timer.destroy();
      const count = (name: string) => passes.filter((p) => p === name).length;
      expect(count('path trace (frame)')).toBe(chunks);
      if (restir) {
        // The whole image's G-buffer and reservoirs once, with the first chunk, before its paths.
        expect(passes.slice(0, 7)).toEqual(['frame G-buffer', 'frame emission', 'restir initial', 'restir temporal', 'restir spatial', 'restir lend', 'path trace (frame)']);
        expect(['frame G-buffer', 'frame emission', 'restir initial', 'restir temporal', 'restir spatial', 'restir lend'].map(count)).toEqual([1, 1, 1, 1, 1, 1]);
      } else {
        expect(count('frame G-buffer')).toBe(chunks);
        expect(passes.some((p) => p.startsWith('restir'))).toBe(false);
      }
      const [a, b] = await Promise.all([unsplit.readFrame(), split.readFrame()]);
      expect(b.width).toBe(WIDTH);
      expect(bytes(b.radiance).equals(bytes(a.radiance))).toBe(true);
      expect(await split.readRayCounts()).toEqual(await unsplit.readRayCounts());
      // Not a trivially equal pair: the frames hold light.
      expect(a.radiance.some((v) => v > 0)).toBe(true);
      if (restir) {
        // ReSTIR did run: the same first frame without it is another image.
        unsplit.updateSettings({ restir: false });
        unsplit.setCamera(cameraA);
        unsplit.resetHistory();
        unsplit.renderFrame(1);
        expect(bytes((await unsplit.readFrame()).radiance).equals(bytes(first.radiance))).toBe(false);
      }
    });
  }
});
