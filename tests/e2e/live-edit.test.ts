/**
 * Live material editing in the page (headless Chromium, WebGPU on SwiftShader): a click on the
 * Cornell box's red wall selects it; a colour typed into the panel's Material folder restarts the
 * image with the wall blue within two frames while the opposite (green) wall barely changes; the
 * link then carries the edit, and opening it shows the blue wall again. Alt-click focuses the lens
 * on the back wall without touching the selection; Esc deselects. Renders are tiny (1/8 of the canvas).
 */
import { describe, expect, it } from 'vitest';
import type { Page } from 'playwright-core';
import { parseViewParams } from '../../src/app/view-params.ts';
import { decodePng } from '../../src/image/png.ts';
import { openWatchedPage, pageReport, pageTestbed, waitForSamples, waitForScene } from './browser.ts';

const bed = pageTestbed();
const VIEWPORT = { width: 640, height: 400 };

interface Image {
  readonly samples: number;
  readonly width: number;
  readonly height: number;
  readonly rgba: number[];
}

/** Mean RGB over a rectangle given in fractions of the image. */
function meanRgb(img: Image, x0: number, x1: number, y0: number, y1: number): [number, number, number] {
  const sum: [number, number, number] = [0, 0, 0];
  let n = 0;
  for (let y = Math.floor(y0 * img.height); y < Math.floor(y1 * img.height); y++) {
    for (let x = Math.floor(x0 * img.width); x < Math.floor(x1 * img.width); x++) {
      for (let c = 0; c < 3; c++) sum[c] = sum[c]! + img.rgba[(y * img.width + x) * 4 + c]!;
      n++;
    }
  }
  return sum.map((s) => s / n) as [number, number, number];
}

/** The red wall is on the left of the image, the green one on the right (loaders/builtin/cornell.ts). */
const RED_WALL = [0.03, 0.12, 0.3, 0.7] as const;
const GREEN_WALL = [0.88, 0.97, 0.3, 0.7] as const;

async function openPage(query: string): Promise<{ page: Page; errors: string[] }> {
  const opened = await openWatchedPage(bed.browser, `${bed.served.url}?${query}`, VIEWPORT);
  await waitForScene(opened.page, 'the first scene');
  return opened;
}

async function playUntil(page: Page, samples: number): Promise<void> {
  if ((await page.evaluate(() => window.lantern.state)) !== 'playing') await page.click('#play');
  await waitForSamples(page, samples, 120_000);
}

/** Pixels of the canvas in the selection outline's orange (1, 0.55, 0.1). */
async function orangePixels(page: Page): Promise<number> {
  const img = decodePng(await page.locator('#view').screenshot());
  let n = 0;
  for (let i = 0; i < img.data.length; i += 4) {
    const r = img.data[i]!, g = img.data[i + 1]!, b = img.data[i + 2]!;
    if (r > 220 && g > 100 && g < 180 && b < 70) n++;
  }
  return n;
}

/**
 * Waits in the page for the estimate to restart (fewer samples than `before`) and reads its first
 * frame at once. Bounded: an edit that never restarts the image fails naming the samples, the link
 * and the panel's colour field instead of running into the test's limit.
 */
/** The Material folder's colour field (the one labelled exactly 'colour', not 'emission colour'): its text input. */
const colourInput = (page: Page) => page.locator('.tp-lblv').filter({ has: page.locator('.tp-lblv_l', { hasText: /^colour$/ }) }).locator('input').first();

const RESTART_TIMEOUT_MS = 90_000;

async function firstFramesAfterRestart(page: Page, before: number): Promise<Image> {
  const first = await page.evaluate(async ([n, timeout]) => {
    const end = performance.now() + timeout;
    const restarted = await new Promise<boolean>((resolve) => {
      const check = () => {
        if (window.lantern.samples >= 1 && window.lantern.samples < n) resolve(true);
        else if (performance.now() > end) resolve(false);
        else requestAnimationFrame(check);
      };
      check();
    });
    // Read in the same turn as the check, so that the frame read is the restart's first.
    return restarted ? window.lantern.readImage() : undefined;
  }, [before, RESTART_TIMEOUT_MS] as const);
  if (!first) {
    const field = await colourInput(page).inputValue();
    throw new Error(`the image did not restart within ${RESTART_TIMEOUT_MS / 1000} s of the colour edit (samples before ${before}; colour field '${field}'; link ${await page.evaluate(() => window.lantern.link)}); ${await pageReport(page)}`);
  }
  return first;
}

describe('live material editing', () => {
  it('selects the red wall by a click, turns it blue from the panel within two frames, and the link carries the edit', async () => {
    const { page, errors } = await openPage('scene=cornell&scale=0.125&spf=1');
    await playUntil(page, 2);
    const orangeBefore = await orangePixels(page);
    const box = (await page.locator('#view').boundingBox())!;
    await page.mouse.click(box.x + box.width * 0.07, box.y + box.height * 0.5);
    await page.waitForFunction(() => window.lantern.selection?.materialName === 'red', undefined, { timeout: 30_000 });
    await expect.poll(() => page.locator('.tp-lblv', { hasText: 'selected' }).locator('textarea').inputValue(), { timeout: 5_000 }).toMatch(/red \(diffuse/);

    // The canvas shows the outline (SELECTION_COLOR), drawn over the image.
    await expect.poll(() => orangePixels(page), { timeout: 10_000 }).toBeGreaterThan(orangeBefore + 50);

    await playUntil(page, 12);
    const before = await page.evaluate(() => window.lantern.readImage());
    const red = meanRgb(before, ...RED_WALL);
    expect(red[0]).toBeGreaterThan(2 * red[2]);

    // Type a colour into the Material folder's colour field.
    const text = colourInput(page);
    await text.fill('#0000ff');
    await text.press('Enter');
    const after = await firstFramesAfterRestart(page, before.samples);
    expect(after.samples).toBeLessThanOrEqual(2);
    const blue = meanRgb(after, ...RED_WALL);
    // The light is warm (little blue), so the blue wall is dim, but its red is gone.
    expect(blue[2]).toBeGreaterThan(2 * blue[0]);
    expect(blue[2]).toBeGreaterThan(red[2] + 10);
    expect(blue[0]).toBeLessThan(0.25 * red[0]);
    // The opposite wall is lit by the light, not by the edited wall: it barely changes (noise of a
    // frame or two, and a little less red light bounced across).
    const green0 = meanRgb(before, ...GREEN_WALL), green1 = meanRgb(after, ...GREEN_WALL);
    for (let c = 0; c < 3; c++) expect(Math.abs(green1[c]! - green0[c]!), `channel ${c}: ${green0} → ${green1}`).toBeLessThan(0.2 * green0[c]! + 8);

    const link = await page.evaluate(() => window.lantern.link);
    const { view, problems } = parseViewParams(new URL(link).searchParams);
    expect(problems).toEqual([]);
    expect(view.materials).toEqual([{ index: 1, name: 'red', edit: { color: [0, 0, 1] } }]);

    // Alt-click focuses on the back wall (z = 559.2; the camera is at z = −800 looking along +z),
    // seen above the tall block and below the ceiling, and leaves the selection alone.
    await page.locator('#view').click({ position: { x: box.width * 0.5, y: box.height * 0.4 }, modifiers: ['Alt'] });
    await page.waitForFunction(() => window.lantern.lens !== undefined, undefined, { timeout: 10_000 });
    expect((await page.evaluate(() => window.lantern.lens))!.focusDistance).toBeCloseTo(1359.2, 0);
    expect(await page.evaluate(() => window.lantern.selection?.materialName)).toBe('red');
    expect(await page.evaluate(() => window.lantern.link)).toMatch(/focus=1359/);

    // Esc deselects (outside the panel's text fields, where Esc belongs to the field).
    await page.locator('#view').focus();
    await page.keyboard.press('Escape');
    await page.waitForFunction(() => window.lantern.selection === undefined, undefined, { timeout: 10_000 });

    // The link restores the edit in a new page.
    const second = await bed.browser.newPage({ viewport: VIEWPORT });
    const secondErrors: string[] = [];
    second.on('pageerror', (e) => secondErrors.push(e.message));
    await second.goto(link);
    await second.waitForFunction(() => window.lantern && !window.lantern.loading && window.lantern.scene === 'cornell', undefined, { timeout: 60_000 });
    await playUntil(second, 2);
    const restored = meanRgb(await second.evaluate(() => window.lantern.readImage()), ...RED_WALL);
    expect(restored[2]).toBeGreaterThan(2 * restored[0]);
    expect(await second.locator('#message').isHidden()).toBe(true);
    expect([...errors, ...secondErrors]).toEqual([]);
    await second.close();
    await page.close();
  });

  it('warns about a link whose material edit does not fit the scene, and renders on', async () => {
    const { page, errors } = await openPage('scene=cornell&scale=0.1&mat=1:1:blue:c=0,0,1&mat=1:0:white:r=0.5&mat=7:bad');
    await expect.poll(async () => (await page.locator('#message').textContent()) ?? '', { timeout: 30_000 }).toMatch(/material 1 is 'red', not 'blue'/);
    const text = (await page.locator('#message').textContent()) ?? '';
    expect(text).toMatch(/diffuse material has no roughness/);
    expect(text).toMatch(/mat=7:bad/);
    await playUntil(page, 1);
    expect(await page.evaluate(() => window.lantern.link)).not.toMatch(/mat=/);
    expect(errors).toEqual([]);
    await page.close();
  });
});
