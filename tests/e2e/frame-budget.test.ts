/**
 * The frame budget and short submissions in the page (Lantern issue #16): Pause and a settings change take effect while a
 * long frame renders (its GPU work goes in chunks of tens of milliseconds, and the page answers
 * between them), and held keys move by the time held when frames are slow (a test hook delays each
 * frame: a deterministic 0.5 fps), and so does the world (Lantern issue #27). The budget keeps its
 * resolution floor, and the panel's resolution shows the scale that renders.
 */
import { describe, expect, it } from 'vitest';
import type { Page } from 'playwright-core';
import { openWatchedPage, pageTestbed, waitForPage, waitForSamples, waitForScene, withPageReport } from './browser.ts';

const bed = pageTestbed();

async function open(query: string, viewport: { width: number; height: number }): Promise<{ page: Page; errors: string[] }> {
  const opened = await openWatchedPage(bed.browser, `${bed.served.url}?${query}`, viewport);
  await waitForScene(opened.page, 'the scene');
  return opened;
}

const frame = (page: Page) => page.evaluate(() => window.lantern.frame);
/** A row of the settings panel by its label. */
const row = (page: Page, label: RegExp) => page.locator('.tp-lblv').filter({ has: page.locator('.tp-lblv_l', { hasText: label }) });

describe('short submissions', () => {
  it('Pause takes effect within a chunk of a frame that takes seconds, Play goes on with that frame, and a settings change starts a new one at once', async () => {
    // The whole canvas at full resolution (scale=1 fixes it: the budget is off), so one SwiftShader
    // frame takes seconds; the page must still answer.
    const { page, errors } = await open('scene=cornell&scale=1', { width: 900, height: 600 });
    expect(await page.evaluate(() => window.lantern.budget)).toMatchObject({ on: false, scale: 1, text: 'budget: off (resolution fixed at 1×)' });
    await page.click('#play');
    // A few chunks into the first frame (after the pipelines compiled).
    await waitForPage(page, () => (window.lantern.frame?.chunks ?? 0) >= 4, undefined, 180_000, 'the first chunks');
    const clicked = Date.now();
    await page.click('#play');
    await waitForPage(page, () => window.lantern.state === 'paused', undefined, 60_000, 'Pause');
    const pauseMs = Date.now() - clicked;
    // The chunk already on the GPU when Pause came finishes and is counted; none goes after it.
    await page.waitForTimeout(300);
    const stopped = (await frame(page))!;
    // The frame's cost: the chunks' time over their share of the frame.
    const frameMs = (stopped.busyMs / stopped.pixelsDone) * stopped.pixels;
    expect(stopped.pixelsDone).toBeLessThan(stopped.pixels);
    // Long frames, or this proves nothing; and Pause far quicker than one.
    expect(frameMs).toBeGreaterThan(2000);
    expect(pauseMs).toBeLessThan(frameMs / 4);
    // Stopped: no chunk goes to the GPU while paused.
    await page.waitForTimeout(500);
    expect(await frame(page)).toMatchObject({ chunks: stopped.chunks, pixelsDone: stopped.pixelsDone, suspended: true });
    // Play goes on with the same frame.
    await page.click('#play');
    await withPageReport(page, 'the frame going on', () => expect.poll(async () => (await frame(page))?.pixelsDone ?? Infinity, { timeout: 60_000, interval: 100 }).toBeGreaterThan(stopped.pixelsDone));
    expect(await page.evaluate(() => window.lantern.samples)).toBe(0);

    // A setting changed while the frame renders takes effect within a chunk: that frame is given up and
    // a new one starts (its chunk count starts again from 0), long before the old one would have ended.
    await waitForPage(page, (n: number) => (window.lantern.frame?.chunks ?? 0) >= n, stopped.chunks + 2, 60_000, 'more chunks');
    const running = (await frame(page))!;
    const bounces = page.locator('.tp-lblv', { hasText: 'max bounces' }).locator('input');
    await bounces.fill('2');
    const edited = Date.now();
    await bounces.press('Enter');
    await withPageReport(page, 'a new frame after the change', () =>
      expect.poll(async () => (await frame(page))?.chunks ?? Infinity, { timeout: 60_000, interval: 25 }).toBeLessThan(running.chunks),
    );
    expect(Date.now() - edited).toBeLessThan(frameMs / 2);
    expect(errors).toEqual([]);
    await page.close();
  });
});

describe('slow frames', () => {
  it('at 0.5 fps, W held for 3 s moves three times as far as W held for 1 s', async () => {
    const { page, errors } = await open('scene=cornell&scale=0.05&mode=fly', { width: 640, height: 400 });
    await page.click('#play');
    await waitForSamples(page, 1, 180_000);
    await page.locator('#view').focus();
    // How long W was held as the page saw it (the events' own times, which the viewer also uses): on
    // a loaded machine the keys arrive a few hundred milliseconds off the test's wall clock, the same
    // for a short press as for a long one, which would bend a ratio of wall-clock holds.
    await page.evaluate(() => {
      const w = window as unknown as { heldW: number[] };
      w.heldW = [];
      addEventListener('keydown', (e) => e.code === 'KeyW' && !e.repeat && w.heldW.push(-e.timeStamp));
      addEventListener('keyup', (e) => e.code === 'KeyW' && w.heldW.push(e.timeStamp));
    });
    const held = () => page.evaluate(() => (window as unknown as { heldW: number[] }).heldW.splice(0).reduce((a, b) => a + b, 0) / 1000);
    const z = () => page.evaluate(() => window.lantern.camera!.position[2]);
    /** Holds W for `ms`, then waits for the frame that applies it: the distance moved per second held. */
    const hold = async (ms: number, frameMs: number) => {
      const before = await z();
      await page.keyboard.down('KeyW');
      await page.waitForTimeout(ms);
      await page.keyboard.up('KeyW');
      // Two frames after the key came up: the span held is in the camera.
      await page.waitForTimeout(2 * frameMs + 500);
      const after = await z();
      await page.waitForTimeout(frameMs + 200);
      expect(await z()).toBe(after);
      const seconds = await held();
      expect(seconds).toBeGreaterThan(ms / 1000 - 0.05);
      return { distance: Math.abs(after - before), seconds };
    };
    const quick = await hold(1000, 100);
    expect(quick.distance).toBeGreaterThan(0);
    await page.evaluate(() => window.lantern.delayFrames(2000));
    const slow = await hold(3000, 2000);
    // Speed per second held is the same at 0.5 fps as at full rate, so three times the hold is three
    // times the distance. (A frame that moved by what is held when it starts would move 0 or 2 s'
    // worth of a 3 s press; one that capped its step would move far less.)
    expect(slow.seconds / quick.seconds).toBeGreaterThan(2);
    expect(slow.distance / slow.seconds / (quick.distance / quick.seconds)).toBeGreaterThan(0.9);
    expect(slow.distance / slow.seconds / (quick.distance / quick.seconds)).toBeLessThan(1.1);
    expect(errors).toEqual([]);
    await page.close();
  });

  it("at 0.5 fps the world keeps real time: the dungeon's phantom walks at its speed", async () => {
    const { page, errors } = await open('scene=dungeon&scale=0.05', { width: 640, height: 400 });
    await page.click('#play');
    await waitForSamples(page, 1, 180_000);
    await page.evaluate(() => window.lantern.delayFrames(2000));
    // The world's clock where it moves (once a frame, as the frame is planned), on the page's clock.
    const seen = await page.evaluate(async () => {
      const changes: [number, number][] = [];
      let last = window.lantern.worldSeconds;
      for (const end = performance.now() + 12_000; performance.now() < end; ) {
        await new Promise((resolve) => setTimeout(resolve, 50));
        const w = window.lantern.worldSeconds;
        if (w !== last) changes.push([performance.now() / 1000, (last = w)]);
      }
      return changes;
    });
    expect(seen.length).toBeGreaterThanOrEqual(3);
    const [t0, w0] = seen[0]!, [t1, w1] = seen.at(-1)!;
    // Slow frames (2 s apart or more), and the world played the time between them: the phantom's pose
    // is a function of the world's time (scene/paths.ts; frame-clock.test.ts checks it at 0.5 fps).
    // At most 0.1 s a frame, as before, would have been a twentieth.
    expect((t1 - t0) / (seen.length - 1)).toBeGreaterThan(1.9);
    expect((w1 - w0) / (t1 - t0)).toBeGreaterThan(0.95);
    expect((w1 - w0) / (t1 - t0)).toBeLessThan(1.05);
    expect(errors).toEqual([]);
    await page.close();
  });
});

describe('the resolution the budget chooses', () => {
  it('keeps its floor on a software adapter, the panel shows the scale that renders, and a scale typed in fixes it', async () => {
    const { page, errors } = await open('scene=cornell', { width: 640, height: 400 });
    await page.click('#play');
    await waitForSamples(page, 3, 180_000);
    const resolution = row(page, /^resolution$/).locator('input');
    const auto = row(page, /^auto resolution$/).locator('input');
    /** The image of the last whole frame, the canvas, the budget, and what the resolution control shows, at one moment. */
    const shown = async () => {
      const state = await page.evaluate(async () => {
        const image = await window.lantern.readImage();
        const canvas = document.querySelector<HTMLCanvasElement>('#view')!;
        return { width: image.width, height: image.height, canvasWidth: canvas.width, canvasHeight: canvas.height, budget: window.lantern.budget };
      });
      return { ...state, control: Number(await resolution.inputValue()) };
    };
    // The panel's resolution is the scale rendered (to its two decimals), not the 1 it showed before
    // Play: SwiftShader cannot hold 3 fps at this canvas, so the budget scaled down, to no fewer than
    // 160 rows (or the canvas's own).
    await withPageReport(page, 'the resolution control', () =>
      expect.poll(async () => {
        const s = await shown();
        return s.budget.scale < 1 && s.width === Math.round(s.canvasWidth * s.budget.scale) && Math.abs(s.control - s.budget.scale) <= 0.005;
      }, { timeout: 60_000, interval: 500 }).toBe(true),
    );
    const s = await shown();
    expect(s.budget.on).toBe(true);
    expect(Math.min(s.width, s.height)).toBeGreaterThanOrEqual(Math.min(160, s.canvasWidth, s.canvasHeight));
    expect(await auto.isChecked()).toBe(true);
    // The user's choice: the budget is off, the scale is theirs (below the floor too), the control keeps it.
    await resolution.fill('0.3');
    await resolution.press('Enter');
    await withPageReport(page, 'the fixed scale', () => expect.poll(async () => (await shown()).width, { timeout: 120_000, interval: 500 }).toBe(Math.round(s.canvasWidth * 0.3)));
    const fixed = await page.evaluate(() => window.lantern.budget);
    expect(fixed.on).toBe(false);
    // Tweakpane's step of 0.01 gives 0.29999999999999993.
    expect(fixed.scale).toBeCloseTo(0.3, 12);
    expect(Number(await resolution.inputValue())).toBe(0.3);
    expect(await auto.isChecked()).toBe(false);
    expect(errors).toEqual([]);
    await page.close();
  });
});
