/**
 * Doom's doors in the page (headless Chromium, WebGPU on SwiftShader): in Freedoom's E1M1 the
 * walker stands in front of the first door reachable from the start (sector 10, a manual door,
 * linedef special 1: its south face runs along map y = 512, world z = −512, x 768..896; the door is
 * 32 units deep, so its far face is at z = −544). Walking north, the closed door stops it; E opens
 * the door, and walking on takes it through. Frames are cheap: a tiny image and the normals debug
 * view instead of path tracing.
 */
import { existsSync } from 'node:fs';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser, Page } from 'playwright-core';
import { lagAnimationFrames, launchBrowser, servePage, waitForPage, watchPage, withPageReport, type ServedPage } from './browser.ts';

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';
const present = existsSync(FREEDOOM1);
if (!present) console.warn(`skipped: no ${FREEDOOM1} (apt-get install freedoom)`);

/** The door's near and far faces (world z), and the walker's radius. */
const NEAR_FACE = -512;
const FAR_FACE = -544;
const RADIUS = 16;

describe.skipIf(!present)('Doom doors in the page', () => {
  let browser: Browser;
  let served: ServedPage;

  beforeAll(async () => {
    served = await servePage([FREEDOOM1]);
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await served?.close();
  });

  const z = (page: Page) => page.evaluate(() => window.lantern.camera!.position[2]);

  it('walks to E1M1\'s first door, cannot pass it closed, opens it with E and walks through', async () => {
    const page = await browser.newPage({ viewport: { width: 320, height: 200 } });
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    watchPage(page);
    // Frame times older than Play, as a loaded machine gives them (the first step must not go back in time).
    await lagAnimationFrames(page, 50);
    // 92 units south of the door (room floor −128, eye at −87), facing north (yaw 0 looks along −z).
    await page.goto(`${served.url}?wad=${served.fileUrls[0]}&map=E1M1&mode=walk&cam=832,-87,-420,0,0&scale=0.05&debug=normals&layout=replace`);
    await waitForPage(page, () => window.lantern && !window.lantern.loading && window.lantern.scene === 'E1M1', undefined, 120_000, 'the map');
    await page.click('#play');
    // Play waits for the pipelines: on a software adapter under a loaded machine, over a minute.
    await waitForPage(page, () => window.lantern.state === 'playing', undefined, 180_000, 'Play');
    // The normals replace the image: the page compiled the debug views and none of the real-time chain
    // it opens in (its G-buffer and path kernels, the denoiser), whose frames would never be shown.
    const pipelines = await page.evaluate(() => window.lantern.pipelines);
    console.log(`E1M1 under its normals compiled ${pipelines.length} pipelines: ${pipelines.map((p) => p.split(' ')[0]).join(', ')}`);
    expect(pipelines.some((p) => p.startsWith('passes/debug-view:debug_view'))).toBe(true);
    expect(pipelines.filter((p) => /path-trace-frame|temporal|denoise/.test(p))).toEqual([]);

    // Walk north into the closed door until the walker stops: one radius short of its face.
    await page.keyboard.down('KeyW');
    await withPageReport(page, 'the walker', () => expect.poll(() => z(page), { timeout: 60_000, interval: 200 }).toBeLessThan(NEAR_FACE + RADIUS + 1));
    await page.waitForTimeout(1000);
    await page.keyboard.up('KeyW');
    const stopped = await z(page);
    expect(stopped).toBeGreaterThan(NEAR_FACE + RADIUS - 0.5);

    // E opens it (2 units a tic: 1.8 s to the top); pressing on, the walker passes the far face.
    await page.keyboard.press('KeyE');
    await page.keyboard.down('KeyW');
    await withPageReport(page, 'the walker', () => expect.poll(() => z(page), { timeout: 90_000, interval: 200 }).toBeLessThan(FAR_FACE - RADIUS));
    await page.keyboard.up('KeyW');
    expect(errors).toEqual([]);
    await page.close();
  });
});
