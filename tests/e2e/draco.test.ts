/**
 * A Draco-compressed glTF (KHR_draco_mesh_compression) opened in the built page: the decoder starts in
 * the scene worker, and the model shows the triangles and the image of its uncompressed twin.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser, Page } from 'playwright-core';
import { dracoModel, type DracoModel } from '../fixtures/draco-model.ts';
import { launchBrowser, servePage, waitForPage, waitForSamples, watchPage, type ServedPage } from './browser.ts';

let browser: Browser;
let served: ServedPage;
let model: DracoModel;

beforeAll(async () => {
  model = await dracoModel();
  served = await servePage();
  browser = await launchBrowser();
});

afterAll(async () => {
  await browser?.close();
  await served?.close();
});

type Image = { width: number; height: number; rgba: number[] };

/** Opens `bytes` as `name` through the file input and waits until it is shown and `samples` are in. */
async function openModel(page: Page, name: string, bytes: Uint8Array, samples: number): Promise<Image> {
  const loads = await page.evaluate(() => window.lantern.sceneLoads);
  await page.setInputFiles('#open-file', { name, mimeType: 'model/gltf-binary', buffer: Buffer.from(bytes) });
  await waitForPage(page, (n) => window.lantern.sceneLoads > n && !window.lantern.loading, loads, 120_000, `${name} loaded`);
  expect(await page.evaluate(() => window.lantern.scene)).toBe(name.replace(/\.glb$/, ''));
  await waitForSamples(page, samples, 120_000);
  return page.evaluate(() => window.lantern.readImage());
}

/** The Numbers pane's scene line: "name\nN triangles · M BVH nodes". */
const sceneMonitor = (page: Page) => page.locator('.tp-lblv').filter({ has: page.locator('.tp-lblv_l', { hasText: /^scene$/ }) }).locator('textarea').inputValue();

/** Pixels where red is well above blue: the orange torus. */
function orangePixels(img: Image): number {
  let n = 0;
  for (let i = 0; i < img.rgba.length; i += 4) if (img.rgba[i]! > 2 * img.rgba[i + 2]! + 20) n++;
  return n;
}

describe('a Draco-compressed glTF in the page', () => {
  it('decodes in the scene worker and renders like the uncompressed model', async () => {
    const page = await browser.newPage({ viewport: { width: 640, height: 400 } });
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    watchPage(page);
    await page.goto(`${served.url}?scene=furnace&scale=0.1`);
    await waitForPage(page, () => window.lantern && !window.lantern.loading && window.lantern.scene !== '', undefined, 60_000, 'the furnace loaded');
    await page.click('#play');

    const plain = await openModel(page, 'torus.glb', model.plain, 4);
    const draco = await openModel(page, 'torus-draco.glb', model.draco, 4);
    expect(await page.locator('#message').getAttribute('data-kind')).not.toBe('error');
    expect(await sceneMonitor(page)).toMatch(new RegExp(`^torus-draco\\n${model.triangles.toLocaleString('en')} triangles`));

    expect([draco.width, draco.height]).toEqual([plain.width, plain.height]);
    const pixels = plain.width * plain.height;
    expect(orangePixels(plain)).toBeGreaterThan(0.1 * pixels);
    expect(orangePixels(draco)).toBeGreaterThan(0.1 * pixels);
    // Not background only: much of the frame is sky.
    expect(orangePixels(draco)).toBeLessThan(0.9 * pixels);
    // The same image up to the quantized positions (and the noise of 4 samples).
    let diff = 0;
    for (let i = 0; i < plain.rgba.length; i++) diff += Math.abs(plain.rgba[i]! - draco.rgba[i]!);
    expect(diff / plain.rgba.length).toBeLessThan(4);
    expect(errors).toEqual([]);
    await page.close();
  });
});
