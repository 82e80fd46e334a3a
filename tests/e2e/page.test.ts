/**
 * The page opens without touching the GPU, Play starts the shared renderer, and the canvas shows
 * the Cornell box: a red-dominant left wall and a green-dominant right wall.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser } from 'playwright-core';
import { decodePng } from '../../src/image/png.ts';
import { launchBrowser, servePage, type ServedPage } from './browser.ts';

let browser: Browser;
let served: ServedPage;

beforeAll(async () => {
  served = await servePage();
  browser = await launchBrowser();
});

afterAll(async () => {
  await browser?.close();
  await served?.close();
});

/** Mean RGB over a rectangle of an RGBA image given in fractions of its size. */
function meanRgb(img: { width: number; height: number; data: Uint8Array }, x0: number, x1: number, y0: number, y1: number): [number, number, number] {
  let r = 0, g = 0, b = 0, n = 0;
  for (let y = Math.floor(y0 * img.height); y < Math.floor(y1 * img.height); y++) {
    for (let x = Math.floor(x0 * img.width); x < Math.floor(x1 * img.width); x++) {
      const i = (y * img.width + x) * 4;
      r += img.data[i]!;
      g += img.data[i + 1]!;
      b += img.data[i + 2]!;
      n++;
    }
  }
  return [r / n, g / n, b / n];
}

describe('the page', () => {
  it('shows the Cornell box after Play, and nothing runs before', async () => {
    const page = await browser.newPage();
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    // A 64×64 render (scale 1/8 of the 512×512 canvas) keeps SwiftShader frames short.
    await page.goto(`${served.url}?scale=0.125`);
    await expect.poll(() => page.evaluate(() => window.lantern?.state)).toBe('idle');
    // No GPU work before Play: the canvas has no context and nothing accumulated.
    await page.waitForTimeout(500);
    expect(await page.evaluate(() => window.lantern.samples)).toBe(0);
    expect(await page.locator('#view').getAttribute('data-state')).toBe('idle');

    await page.click('#play');
    await page.waitForFunction(() => window.lantern.samples >= 8, undefined, { timeout: 240_000 });
    await page.click('#play'); // pause, so the screenshot sees a settled frame
    await expect.poll(() => page.evaluate(() => window.lantern.state)).toBe('paused');

    const img = decodePng(await page.locator('#view').screenshot());
    const left = meanRgb(img, 0.03, 0.12, 0.3, 0.7);
    const right = meanRgb(img, 0.88, 0.97, 0.3, 0.7);
    const centre = meanRgb(img, 0.3, 0.7, 0.3, 0.7);
    expect(left[0]).toBeGreaterThan(2 * left[1]);
    expect(right[1]).toBeGreaterThan(1.5 * right[0]);
    // Not black: the lit room is there.
    expect(centre[0] + centre[1] + centre[2]).toBeGreaterThan(60);
    expect(errors).toEqual([]);
    expect(await page.locator('#message').isHidden()).toBe(true);
    await page.close();
  });

  it('says plainly when an unknown scene is asked for, and still offers the built-ins', async () => {
    const page = await browser.newPage();
    await page.goto(`${served.url}?scene=nope`);
    await expect.poll(() => page.locator('#message').textContent()).toMatch(/unknown scene 'nope'/);
    expect(await page.locator('#scene').inputValue()).toBe('cornell');
    await page.close();
  });
});
