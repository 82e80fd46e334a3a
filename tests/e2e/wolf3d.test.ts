/**
 * Wolfenstein 3D and the hybrid recipe in the page (headless Chromium, WebGPU on SwiftShader): the
 * shareware files dropped together open E1L1 (files written by the test's own writer stand in when
 * the shareware package is absent); the recipe switches to hybrid from the panel and frames go on
 * (the GPU pass list shows the raster pass); a truncated GAMEMAPS is a one-line error while the
 * level keeps rendering (tests/e2e/wolf3d-doors.test.ts walks through a door). Renders are tiny.
 */
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser, Page } from 'playwright-core';
import { testGameFiles } from '../../src/loaders/wolf3d/test-files.ts';
import { dropFiles, lagAnimationFrames, launchBrowser, servePage, waitForPage, waitForSamples, watchPage, type ServedPage } from './browser.ts';

// LANTERN_WOLF3D_SHAREWARE=none runs with the written files even where the shareware is present (as CI does).
const SHAREWARE = process.env.LANTERN_WOLF3D_SHAREWARE === 'none' ? undefined : ['../shared/assets/wolf3d-shareware', '/work/shared/assets/wolf3d-shareware'].map((d) => join(import.meta.dirname, '../..', d)).concat('/work/shared/assets/wolf3d-shareware').find((d) => existsSync(join(d, 'GAMEMAPS.WL1')));
if (!SHAREWARE) console.warn('the Wolfenstein 3D shareware files are absent: the page tests use files written by the test instead');

/** The three files, as the page receives them dropped together. */
function gameFiles(): { name: string; bytes: number[] }[] {
  if (SHAREWARE) return ['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'].map((name) => ({ name, bytes: [...readFileSync(join(SHAREWARE, name))] }));
  const t = testGameFiles();
  return [t.maphead, t.gamemaps, t.vswap].map((f) => ({ name: f.name, bytes: [...f.bytes] }));
}

let browser: Browser;
let served: ServedPage;

beforeAll(async () => {
  served = await servePage([]);
  browser = await launchBrowser();
});

afterAll(async () => {
  await browser?.close();
  await served?.close();
});

async function open(query: string): Promise<{ page: Page; errors: string[] }> {
  const page = await browser.newPage({ viewport: { width: 480, height: 300 } });
  const errors: string[] = [];
  page.on('pageerror', (e) => errors.push(e.message));
  watchPage(page);
  // Frame times older than Play, as a loaded CI machine gives them: the level's first step must not
  // go back in time (a negative dt once failed the viewer: CI's wolf3d timeout).
  await lagAnimationFrames(page, 50);
  await page.goto(`${served.url}?${query}`);
  await waitForPage(page, () => window.lantern && !window.lantern.loading && window.lantern.scene !== '', undefined, 60_000, 'the first scene');
  return { page, errors };
}

async function playUntil(page: Page, samples: number): Promise<void> {
  if ((await page.evaluate(() => window.lantern.state)) !== 'playing') await page.click('#play');
  await waitForSamples(page, samples, 180_000);
}

const messageText = (page: Page) => page.locator('#message').textContent();

describe('Wolfenstein 3D and the hybrid recipe in the page', () => {
  it('opens the game files dropped together, switches to the hybrid recipe from the panel, and keeps the level through a truncated GAMEMAPS', async () => {
    const { page, errors } = await open('scene=cornell&scale=0.05');
    const loads = await page.evaluate(() => window.lantern.sceneLoads);
    const files = gameFiles();
    await dropFiles(page, files);
    await waitForPage(page, (n) => window.lantern.sceneLoads > n && !window.lantern.loading, loads, 120_000, 'the dropped game');
    expect(await page.evaluate(() => window.lantern.scene)).toMatch(/E1L1/);
    await playUntil(page, 1);

    // The recipe, from the panel's list; frames go on and the pass list shows the raster pass.
    await page.locator('.tp-lblv', { hasText: 'recipe' }).locator('select').selectOption('hybrid');
    await expect.poll(() => page.evaluate(() => window.lantern.link), { timeout: 120_000 }).toMatch(/recipe=hybrid/);
    // Compiling the recipe's pipelines takes a while on SwiftShader; the frames before it are the path tracer's.
    const passes = () => page.locator('.tp-lblv', { hasText: 'GPU passes' }).locator('textarea').inputValue();
    await expect.poll(passes, { timeout: 180_000, interval: 500 }).toMatch(/raster|no timestamp queries/);
    const frames = await page.evaluate(() => window.lantern.samples);
    await playUntil(page, frames + 2);

    // A truncated GAMEMAPS: one line naming the file, and the level keeps rendering.
    const before = await page.evaluate(() => window.lantern.sceneLoads);
    const truncated = files.map((f) => (/GAMEMAPS/i.test(f.name) ? { name: f.name, bytes: f.bytes.slice(0, Math.floor(f.bytes.length / 3)) } : f));
    await dropFiles(page, truncated);
    await expect.poll(() => messageText(page), { timeout: 60_000 }).toMatch(/GAMEMAPS/);
    const message = (await messageText(page)) ?? '';
    expect(message.trim().split('\n')).toHaveLength(1);
    expect(await page.locator('#message').getAttribute('data-kind')).toBe('error');
    expect(await page.evaluate(() => window.lantern.sceneLoads)).toBe(before);
    expect(await page.evaluate(() => window.lantern.scene)).toMatch(/E1L1/);
    const now = await page.evaluate(() => window.lantern.samples);
    await playUntil(page, now + 2);
    expect(errors).toEqual([]);
    await page.close();
  });
});
