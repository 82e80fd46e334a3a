/**
 * Wolfenstein 3D's doors in the page (headless Chromium, WebGPU on SwiftShader): E1L1 of the
 * shareware (read in place; skipped where absent) opened by link, in walk mode at the player's
 * start, the cell at tile (29, 57) facing east. Its door, a vertical door at tile (32, 57), spans
 * world x 2048–2112 (tiles are 64 units), its panel in the tile's middle. A walking player opens doors
 * with the use key, as in the game: walking east, the closed door stops the walker; E opens it, and
 * walking on takes the walker through, past the door tile's far edge. Frames are cheap:
 * a tiny image and the normals debug view instead of path tracing.
 */
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser, Page } from 'playwright-core';
import { lagAnimationFrames, launchBrowser, servePage, waitForPage, watchPage, withPageReport, type ServedPage } from './browser.ts';

const SHAREWARE = ['../shared/assets/wolf3d-shareware', '/work/shared/assets/wolf3d-shareware'].find((d) => ['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'].every((f) => existsSync(join(d, f))));
if (!SHAREWARE) console.warn('skipped: the Wolfenstein 3D shareware files are absent (../shared/assets/wolf3d-shareware)');

const TILE = 64;
/** The walker's radius (the game's MINDIST: 22 units). */
const RADIUS = 22;

describe.skipIf(!SHAREWARE)('Wolfenstein 3D doors in the page', () => {
  let browser: Browser;
  let served: ServedPage;

  beforeAll(async () => {
    served = await servePage(['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'].map((f) => join(SHAREWARE!, f)));
    browser = await launchBrowser();
  });

  afterAll(async () => {
    await browser?.close();
    await served?.close();
  });

  const x = (page: Page) => page.evaluate(() => window.lantern.camera!.position[0]);

  it("walks out of E1L1's cell: the closed door stops the walker, E opens it, and the walker goes through", async () => {
    const page = await browser.newPage({ viewport: { width: 320, height: 200 } });
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    watchPage(page);
    // Frame times older than Play, as a loaded machine gives them (the first step must not go back in time).
    await lagAnimationFrames(page, 50);
    const files = served.fileUrls.map((u) => `wolf=${u}`).join('&');
    await page.goto(`${served.url}?${files}&map=E1L1&mode=walk&scale=0.05&debug=normals&layout=replace`);
    await waitForPage(page, () => window.lantern && !window.lantern.loading && /E1L1/.test(window.lantern.scene), undefined, 120_000, 'the map');
    // The start: the cell's middle, west of the door.
    expect(await x(page)).toBeCloseTo(29.5 * TILE, 0);
    await page.click('#play');
    // Play waits for the first frame's pipelines: 180 s, as every first frame's wait (a loaded CI machine took more than 60).
    await waitForPage(page, () => window.lantern.state === 'playing', undefined, 180_000, 'Play');

    // East until the closed door stops the walker: it may not enter the door's tile.
    await page.keyboard.down('KeyW');
    await withPageReport(page, 'the walker', () => expect.poll(() => x(page), { timeout: 120_000, interval: 200 }).toBeGreaterThan(32 * TILE - RADIUS - 2));
    await page.waitForTimeout(1500);
    await page.keyboard.up('KeyW');
    expect(await x(page)).toBeLessThan(32 * TILE);
    // E opens it (0.91 s); walking on, the walker goes through the door tile and out of its far side.
    await page.keyboard.press('KeyE');
    await page.keyboard.down('KeyW');
    await withPageReport(page, 'the walker', () => expect.poll(() => x(page), { timeout: 120_000, interval: 200 }).toBeGreaterThan(33 * TILE + RADIUS));
    await page.keyboard.up('KeyW');
    expect(errors).toEqual([]);
    await page.close();
  });
});
