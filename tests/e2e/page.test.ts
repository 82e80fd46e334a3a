/**
 * The viewer in headless Chromium (WebGPU on SwiftShader), driven as a user drives it: Play,
 * keyboard, the settings panel, the file input, the map picker. Renders are tiny (a fraction of the
 * canvas through the `scale` parameter) so SwiftShader frames stay short.
 */
import { cpSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser, Page } from 'playwright-core';
import { decodePng } from '../../src/image/png.ts';
import { squareRoomsWad } from '../../src/loaders/doom/test-wad.ts';
import { dropFiles, launchBrowser, openWatchedPage, servePage, waitForPage, waitForSamples, type ServedPage } from './browser.ts';

let browser: Browser;
let served: ServedPage;
let dir: string;
/** Two maps: MAP01 a 256-unit room, MAP02 a 512-unit room. */
const ROOMS = squareRoomsWad([{ name: 'MAP01' }, { name: 'MAP02', size: 512 }]);
const VIEWPORT = { width: 640, height: 400 };

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-page-files-'));
  writeFileSync(join(dir, 'rooms.wad'), ROOMS);
  served = await servePage([join(dir, 'rooms.wad')]);
  browser = await launchBrowser();
});

afterAll(async () => {
  await browser?.close();
  await served?.close();
  rmSync(dir, { recursive: true, force: true });
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

/**
 * The progressive recipe, for the tests of what is not the real-time chain (input, files, links,
 * lighting, the lens): a page in the real-time chain compiles three megakernels and
 * the denoiser (about 20 s of a 2-core machine on SwiftShader), a progressive one the path tracer
 * alone. The first test and the real-time chain's own test open in the default recipe.
 */
const PROGRESSIVE = 'temporal=0&denoise=0';

/** Opens the page, collecting page errors; `query` without the leading '?'. */
async function open(query: string): Promise<{ page: Page; errors: string[] }> {
  const opened = await openWatchedPage(browser, `${served.url}?${query}`, VIEWPORT);
  await waitLoaded(opened.page);
  return opened;
}

/** Pixels of the rendered image, from the status line ("… · 17×14 · adapter"). */
async function renderPixels(page: Page): Promise<number> {
  const status = await page.evaluate(() => document.body.innerText);
  const m = /(\d+)×(\d+) · /.exec(status);
  if (!m) throw new Error(`no image size in the status line: ${status.slice(0, 200)}`);
  return Number(m[1]) * Number(m[2]);
}

async function waitLoaded(page: Page, scene?: string): Promise<void> {
  await waitForPage(page, (s) => window.lantern && !window.lantern.loading && window.lantern.scene !== '' && (!s || window.lantern.scene === s), scene, 60_000, `the scene ${scene ?? ''} loaded`);
}

async function playUntil(page: Page, samples: number): Promise<void> {
  if ((await page.evaluate(() => window.lantern.state)) !== 'playing') await page.click('#play');
  await waitForSamples(page, samples, 120_000);
}

/** The glTF sample models shared between worktrees (../shared/assets/gltf): tests that need them skip without them. */
const GLTF_ASSETS = join(import.meta.dirname, '../../../shared/assets/gltf');
const SHARED_GLTF = existsSync(GLTF_ASSETS) ? GLTF_ASSETS : '/work/shared/assets/gltf';
const asset = (path: string) => join(SHARED_GLTF, path);
const hasAssets = (...paths: string[]) => {
  const missing = paths.filter((p) => !existsSync(asset(p)));
  if (missing.length > 0) console.warn(`skipped: no ${missing.join(', ')} under ${SHARED_GLTF}`);
  return missing.length === 0;
};

/** Mean absolute difference per channel between two images of the same size. */
function imageDifference(a: { data: Uint8Array }, b: { data: Uint8Array }): number {
  let sum = 0;
  for (let i = 0; i < a.data.length; i++) sum += Math.abs(a.data[i]! - b.data[i]!);
  return sum / a.data.length;
}

/** Renders a few samples, pauses and returns the settled image. */
async function settledImage(page: Page, samples: number) {
  await playUntil(page, samples);
  await page.click('#play');
  await expect.poll(() => page.evaluate(() => window.lantern.state)).toBe('paused');
  return canvasImage(page);
}

/** Waits until a scene other than `before` is shown and loaded. */
async function waitNewScene(page: Page, before: number): Promise<void> {
  await waitForPage(page, (n) => window.lantern.sceneLoads > n && !window.lantern.loading, before, 120_000, 'a new scene');
}

const canvasImage = async (page: Page) => decodePng(await page.locator('#view').screenshot());
const messageText = (page: Page) => page.locator('#message').textContent();

describe('the page', () => {
  it('shows the Cornell box after Play, and nothing runs before', async () => {
    // A render at 1/8 of the canvas keeps SwiftShader frames short.
    const { page, errors } = await open('scale=0.125');
    expect(await page.evaluate(() => window.lantern.state)).toBe('idle');
    // No GPU work before Play: no device, nothing allocated, nothing accumulated.
    await page.waitForTimeout(300);
    expect(await page.evaluate(() => window.lantern.samples)).toBe(0);
    expect(await page.evaluate(() => window.lantern.gpuResources.buffers)).toBe(0);
    expect(await page.locator('#view').getAttribute('data-state')).toBe('idle');
    expect(await page.evaluate(() => window.lantern.firstFrameMs)).toBeUndefined();
    expect(await page.locator('#view').getAttribute('data-first-frame-ms')).toBeNull();

    await playUntil(page, 8);
    // The default recipe is the real-time chain: its frame kernels and the denoiser are compiled (and
    // the progressive path tracer, which adds to the estimate while the view is still).
    const pipelines = await page.evaluate(() => window.lantern.pipelines);
    console.log(`a Cornell box page in the real-time chain compiled ${pipelines.length} pipelines: ${pipelines.map((p) => p.split(' ')[0]).join(', ')}`);
    for (const entry of ['path-trace-frame:frame_gbuffer', 'path-trace-frame:path_trace_frame', 'temporal:temporal_accumulate', 'path-trace:path_trace']) expect(pipelines.some((p) => p.startsWith(`passes/${entry} `) || p === `passes/${entry}`), entry).toBe(true);
    // Play to first frame: reported once the first frame is done, in the hook, on the canvas and in the GPU panel.
    const firstFrameMs = await page.evaluate(() => window.lantern.firstFrameMs);
    expect(firstFrameMs).toBeGreaterThan(0);
    expect(Number(await page.locator('#view').getAttribute('data-first-frame-ms'))).toBeCloseTo(firstFrameMs!, 0);
    await expect.poll(() => page.getByText('Play to first frame').count()).toBe(1);
    // The renderer's idle specialisation is off on SwiftShader (its compile would take minutes of the page's CPU).
    await page.waitForTimeout(1200);
    expect(await page.evaluate(() => window.lantern.kernel)).toBe('generic');
    await page.click('#play'); // pause, so the screenshot sees a settled frame
    await expect.poll(() => page.evaluate(() => window.lantern.state)).toBe('paused');

    const img = await canvasImage(page);
    const left = meanRgb(img, 0.03, 0.12, 0.3, 0.7);
    const right = meanRgb(img, 0.88, 0.97, 0.3, 0.7);
    const centre = meanRgb(img, 0.3, 0.7, 0.3, 0.7);
    expect(left[0]).toBeGreaterThan(2 * left[1]);
    expect(right[1]).toBeGreaterThan(1.5 * right[0]);
    expect(centre[0] + centre[1] + centre[2]).toBeGreaterThan(60);
    expect(errors).toEqual([]);
    expect(await page.locator('#message').isHidden()).toBe(true);
    await page.close();
  });

  it('says plainly when an unknown scene is asked for, and still offers the built-ins', async () => {
    const { page } = await open('scene=nope');
    await expect.poll(() => messageText(page)).toMatch(/unknown scene 'nope'/);
    expect(await page.locator('#scene').inputValue()).toBe('cornell');
    await page.close();
  });

  it('moves the camera with the keyboard, and restarts accumulation on a settings change', async () => {
    const { page, errors } = await open(`scene=cornell&scale=0.1&${PROGRESSIVE}`);
    await playUntil(page, 4);
    const before = await page.evaluate(() => window.lantern.camera!);
    const imageBefore = await canvasImage(page);
    await page.keyboard.down('KeyW');
    await page.waitForTimeout(700);
    await page.keyboard.up('KeyW');
    await page.keyboard.down('ArrowRight');
    await page.waitForTimeout(300);
    await page.keyboard.up('ArrowRight');
    const after = await page.evaluate(() => window.lantern.camera!);
    // The Cornell camera looks along +z: W moves toward the box, the right arrow turns right.
    expect(after.position[2]).toBeGreaterThan(before.position[2] + 50);
    expect(after.yaw).toBeGreaterThan(before.yaw + 0.2);
    await playUntil(page, 3);
    const imageAfter = await canvasImage(page);
    let changed = 0;
    for (let i = 0; i < imageBefore.data.length; i++) changed += Math.abs(imageBefore.data[i]! - imageAfter.data[i]!);
    expect(changed / imageBefore.data.length).toBeGreaterThan(5);

    // A settings change through the panel starts a new estimate.
    await playUntil(page, 20);
    const bounces = page.locator('.tp-lblv', { hasText: 'max bounces' }).locator('input');
    await bounces.fill('2');
    await bounces.press('Enter');
    await expect.poll(() => page.evaluate(() => window.lantern.samples), { timeout: 10_000, interval: 50 }).toBeLessThan(15);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('opens a WAD through the file input, offers its maps, renders the one picked and walks in it', async () => {
    const { page, errors } = await open(`scene=furnace&scale=0.1&${PROGRESSIVE}`);
    await page.setInputFiles('#open-file', { name: 'rooms.wad', mimeType: 'application/octet-stream', buffer: Buffer.from(ROOMS) });
    await waitLoaded(page, 'MAP01');
    expect(await page.locator('#map-picker').isVisible()).toBe(true);
    expect(await page.locator('#map option').allTextContents()).toEqual(['MAP01', 'MAP02']);
    await page.selectOption('#map', 'MAP02');
    await waitLoaded(page, 'MAP02');
    await playUntil(page, 4);
    // The player start (the room's centre) at eye height, in walk mode.
    expect(await page.evaluate(() => window.lantern.camera!.position)).toEqual([256, 41, -256]);
    const img = await canvasImage(page);
    const [r, g, b] = meanRgb(img, 0.3, 0.7, 0.3, 0.7);
    expect(r + g + b).toBeGreaterThan(30);
    // Walking into the wall for a while: stopped one player radius (16) inside the room, at eye height.
    await page.keyboard.down('KeyW');
    await page.waitForTimeout(2500);
    await page.keyboard.up('KeyW');
    const [x, y, z] = await page.evaluate(() => window.lantern.camera!.position);
    expect(y).toBeCloseTo(41, 3);
    for (const v of [x, -z]) {
      expect(v).toBeGreaterThanOrEqual(16 - 1e-3);
      expect(v).toBeLessThanOrEqual(512 - 16 + 1e-3);
    }
    expect(Math.min(x, -z, 512 - x, 512 + z)).toBeLessThan(17);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('answers a garbage file with a readable error and keeps rendering', async () => {
    const { page, errors } = await open(`scene=cornell&scale=0.1&${PROGRESSIVE}`);
    await playUntil(page, 2);
    const garbage = Buffer.from(Array.from({ length: 3000 }, (_, i) => (i * 7919) & 0xff));
    await page.setInputFiles('#open-file', { name: 'garbage.wad', mimeType: 'application/octet-stream', buffer: garbage });
    await expect.poll(() => messageText(page), { timeout: 20_000 }).toMatch(/garbage\.wad/);
    expect(await page.locator('#message').getAttribute('data-kind')).toBe('error');
    await page.setInputFiles('#open-file', { name: 'notes.txt', mimeType: 'text/plain', buffer: Buffer.from('hello') });
    await expect.poll(() => messageText(page)).toMatch(/cannot open 'notes\.txt'.*WAD/);
    // Still the Cornell box, still accumulating.
    expect(await page.evaluate(() => window.lantern.scene)).toBe('cornell');
    expect(await page.locator('#scene').inputValue()).toBe('cornell');
    const samples = await page.evaluate(() => window.lantern.samples);
    await playUntil(page, samples + 2);
    expect(await page.evaluate(() => window.lantern.state)).toBe('playing');
    expect(errors).toEqual([]);
    await page.close();
  });

  it('gives back every GPU buffer over 20 scene loads', async () => {
    // Progressive (the real-time chain's buffers would follow the image size too: resource-count.test.ts covers the renderer's).
    const { page, errors } = await open(`scene=cornell&scale=0.05&${PROGRESSIVE}`);
    await playUntil(page, 1);
    await page.click('#play');
    // A WAD's map once first: what the renderer makes once, on first need, for every later scene
    // alike (the automatic exposure's pass and state, made for the first Doom map) is not a load's.
    const loadWad = async () => {
      await page.setInputFiles('#open-file', { name: 'rooms.wad', mimeType: 'application/octet-stream', buffer: Buffer.from(ROOMS) });
      await waitLoaded(page, 'MAP01');
      await page.selectOption('#scene', 'cornell');
      await waitLoaded(page, 'cornell');
    };
    await loadWad();
    // Let the frame in flight finish: its read-back buffer lives until the read completes.
    await page.waitForTimeout(500);
    const start = await page.evaluate(() => window.lantern.gpuResources);
    const startPixels = await renderPixels(page);
    expect(start.buffers).toBeGreaterThan(5);
    for (let i = 0; i < 20; i++) {
      const name = i % 2 === 0 ? 'furnace' : 'cornell';
      await page.selectOption('#scene', name);
      await waitLoaded(page, name);
    }
    // Loads of a WAD's maps too.
    await loadWad();
    // The image may have changed size with the page's layout (a message line more or less above the
    // canvas): its accumulation buffer (16 bytes a pixel) and output texture (4) follow, nothing else.
    const end = await page.evaluate(() => window.lantern.gpuResources);
    const endPixels = await renderPixels(page);
    expect(end).toEqual({ ...start, bytes: start.bytes + 20 * (endPixels - startPixels) });
    expect(errors).toEqual([]);
    await page.close();
  });

  it('recreates a lost GPU device and goes on; stops while the tab is hidden', async () => {
    const { page, errors } = await open('scene=cornell&scale=0.05');
    await playUntil(page, 3);
    await page.evaluate(() => window.lantern.simulateDeviceLoss());
    await expect.poll(() => messageText(page), { timeout: 60_000 }).toMatch(/Recovered from a lost GPU device/);
    await playUntil(page, 3);
    expect(await page.evaluate(() => window.lantern.state)).toBe('playing');

    await page.evaluate(() => {
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => true });
      document.dispatchEvent(new Event('visibilitychange'));
    });
    await page.waitForTimeout(300);
    const hidden = await page.evaluate(() => window.lantern.samples);
    await page.waitForTimeout(700);
    expect(await page.evaluate(() => window.lantern.samples)).toBe(hidden);
    await page.evaluate(() => {
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => false });
      document.dispatchEvent(new Event('visibilitychange'));
    });
    await playUntil(page, hidden + 2);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('starts in the real-time denoised chain, keeps it while the camera moves, converges when still, and goes progressive from the panel', async () => {
    const { page, errors } = await open('scene=cornell&scale=0.1');
    await playUntil(page, 2);
    expect(await page.evaluate(() => window.lantern.display)).toBe('frame');
    expect(await page.evaluate(() => window.lantern.link)).toMatch(/temporal=1&denoise=1/);
    await page.keyboard.down('KeyA');
    await page.waitForTimeout(300);
    await page.keyboard.up('KeyA');
    const frames = await page.evaluate(() => window.lantern.samples);
    await playUntil(page, frames + 3);
    // Still: the exact progressive estimate takes over once it holds 64 samples per pixel.
    await page.waitForFunction(() => window.lantern.display === 'converged', undefined, { timeout: 120_000 });
    expect(await page.evaluate(() => window.lantern.samples)).toBeGreaterThanOrEqual(64);
    await page.click('#play');
    const img = await canvasImage(page);
    // The camera stepped left: the red wall is in from the left edge.
    const left = meanRgb(img, 0.17, 0.27, 0.3, 0.7);
    const right = meanRgb(img, 0.88, 0.97, 0.3, 0.7);
    expect(left[0]).toBeGreaterThan(1.5 * left[1]);
    expect(right[1]).toBeGreaterThan(1.2 * right[0]);
    await page.click('#play');
    // A move hands back to the real-time frames.
    await page.keyboard.down('KeyD');
    await page.waitForTimeout(300);
    await page.keyboard.up('KeyD');
    await expect.poll(() => page.evaluate(() => window.lantern.display), { timeout: 40_000 }).toBe('frame');

    // Both filters off from the panel: progressive accumulation, restarted.
    await page.locator('.tp-lblv', { hasText: 'temporal' }).locator('.tp-ckbv_w').click();
    await page.locator('.tp-lblv', { hasText: 'spatial' }).locator('.tp-ckbv_w').click();
    await expect.poll(() => page.evaluate(() => window.lantern.display), { timeout: 40_000 }).toBe('progressive');
    expect(await page.evaluate(() => window.lantern.link)).toMatch(/temporal=0&denoise=0/);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('shows a BVH debug view with its legend, chosen from the panel', async () => {
    // In the default recipe: the real-time chain is compiled only once a layout shows the image.
    const { page, errors } = await open('scene=bvh-teaching&scale=0.1&debug=heat-nodes');
    await playUntil(page, 0);
    await page.waitForFunction(() => !document.getElementById('legend')!.hidden, undefined, { timeout: 60_000 });
    expect(await page.locator('#legend .label').textContent()).toMatch(/node/i);
    const max = Number((await page.locator('#legend .max').textContent())!.split(' ')[0]);
    expect(max).toBeGreaterThan(3);
    // 'replace' shows the counts only: nothing is path traced.
    expect(await page.evaluate(() => window.lantern.samples)).toBe(0);
    await page.locator('.tp-fldv_b', { hasText: 'Debug views' }).click();
    expect((await page.evaluate(() => window.lantern.pipelines)).filter((p) => p.startsWith('passes/path-trace-frame'))).toEqual([]);
    await page.locator('.tp-lblv', { hasText: 'layout' }).locator('select').selectOption('side-by-side');
    await playUntil(page, 2);
    expect(await page.evaluate(() => window.lantern.display)).toBe('frame');
    await page.locator('.tp-lblv', { hasText: /^view/ }).locator('select').selectOption('none');
    await expect.poll(() => page.locator('#legend').isHidden()).toBe(true);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('opens a served WAD map from a link, and a copied link restores the camera and settings', async () => {
    const { page, errors } = await open(`wad=${served.fileUrls[0]}&map=MAP02&skill=4&scale=0.05&bounces=3&${PROGRESSIVE}`);
    expect(await page.evaluate(() => window.lantern.scene)).toBe('MAP02');
    await page.keyboard.down('KeyD');
    await page.waitForTimeout(300);
    await page.keyboard.up('KeyD');
    // Movement happens in frames, so play a little.
    await playUntil(page, 2);
    await page.keyboard.down('KeyA');
    await page.waitForTimeout(200);
    await page.keyboard.up('KeyA');
    await page.click('#play');
    const camera = await page.evaluate(() => window.lantern.camera!);
    const link = await page.evaluate(() => window.lantern.link);
    expect(link).toMatch(/bounces=3/);
    // Doom's skill level stays with the files in the page's own link.
    expect(link).toMatch(/[?&]skill=4(&|$)/);
    const second = await browser.newPage({ viewport: VIEWPORT });
    await second.goto(link);
    await waitLoaded(second, 'MAP02');
    const restored = await second.evaluate(() => window.lantern.camera!);
    for (let i = 0; i < 3; i++) expect(restored.position[i]).toBeCloseTo(camera.position[i]!, 2);
    expect(restored.yaw).toBeCloseTo(camera.yaw, 3);
    expect(errors).toEqual([]);
    await second.close();
    await page.close();
  });

  it('opens a .glb through the file input: the model renders', async () => {
    if (!hasAssets('Duck/glTF-Binary/Duck.glb')) return;
    const { page, errors } = await open(`scene=furnace&scale=0.1&${PROGRESSIVE}`);
    const before = await settledImage(page, 2);
    const loads = await page.evaluate(() => window.lantern.sceneLoads);
    await page.setInputFiles('#open-file', asset('Duck/glTF-Binary/Duck.glb'));
    await waitNewScene(page, loads);
    expect(await page.locator('#scene option:checked').textContent()).toBe('Duck.glb');
    // No light of its own: the default sky, said as information (it was a warning).
    expect(await page.locator('#message').getAttribute('data-kind')).toBe('info');
    expect(await messageText(page)).toBe('Duck: the model has no light of its own; a default sky lights it');
    expect(await page.evaluate(() => window.lantern.scene)).not.toBe('furnace');
    const after = await settledImage(page, 2);
    const [r, g, b] = meanRgb(after, 0, 1, 0, 1);
    expect(r + g + b).toBeGreaterThan(15);
    expect(imageDifference(before, after)).toBeGreaterThan(5);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('opens a picked folder: a .gltf finds its .bin and a texture in a subfolder by relative path, not a decoy of the same name', async () => {
    if (!hasAssets('Duck/glTF/Duck.gltf')) return;
    const folder = join(dir, 'duck-folder');
    mkdirSync(join(folder, 'textures'), { recursive: true });
    mkdirSync(join(folder, 'decoy'), { recursive: true });
    const gltf = JSON.parse(readFileSync(asset('Duck/glTF/Duck.gltf'), 'utf8')) as { images: { uri: string }[] };
    gltf.images = gltf.images.map((i) => ({ ...i, uri: `textures/${i.uri}` }));
    writeFileSync(join(folder, 'Duck.gltf'), JSON.stringify(gltf));
    cpSync(asset('Duck/glTF/Duck0.bin'), join(folder, 'Duck0.bin'));
    cpSync(asset('Duck/glTF/DuckCM.png'), join(folder, 'textures/DuckCM.png'));
    // A file of the same name that is not an image: picking it would give a texture warning.
    writeFileSync(join(folder, 'decoy/DuckCM.png'), 'not a png');
    const { page, errors } = await open(`scene=furnace&scale=0.1&${PROGRESSIVE}`);
    const loads = await page.evaluate(() => window.lantern.sceneLoads);
    await page.setInputFiles('#open-folder', folder);
    await waitNewScene(page, loads);
    expect(await page.locator('#scene option:checked').textContent()).toBe('Duck.gltf');
    expect((await messageText(page)) ?? '').not.toMatch(/DuckCM/);
    const img = await settledImage(page, 2);
    const [r, g, b] = meanRgb(img, 0, 1, 0, 1);
    expect(r + g + b).toBeGreaterThan(15);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('opens a .gltf, its .bin and its texture dropped together on the page', async () => {
    if (!hasAssets('Duck/glTF/Duck.gltf')) return;
    const files = readdirSync(asset('Duck/glTF')).map((name) => ({ name, bytes: [...readFileSync(asset(`Duck/glTF/${name}`))] }));
    const { page, errors } = await open(`scene=furnace&scale=0.1&${PROGRESSIVE}`);
    const before = await settledImage(page, 2);
    const loads = await page.evaluate(() => window.lantern.sceneLoads);
    // A drop as the browser delivers it: a DataTransfer of File objects on a drop event.
    await dropFiles(page, files);
    await waitNewScene(page, loads);
    expect(await page.locator('#drop-zone').isHidden()).toBe(true);
    expect(await page.locator('#scene option:checked').textContent()).toBe('Duck.gltf');
    expect((await messageText(page)) ?? '').not.toMatch(/DuckCM|Duck0/);
    const after = await settledImage(page, 2);
    expect(imageDifference(before, after)).toBeGreaterThan(5);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('names a texture missing from a picked glTF folder, once, and renders the model', async () => {
    if (!hasAssets('Lantern/glTF/Lantern.gltf')) return;
    const missing = 'Lantern_baseColor.png';
    if (existsSync(asset(`Lantern/glTF/${missing}`))) {
      console.warn(`skipped: ${missing} is not missing any more`);
      return;
    }
    const { page, errors } = await open(`scene=furnace&scale=0.1&${PROGRESSIVE}`);
    const loads = await page.evaluate(() => window.lantern.sceneLoads);
    await page.setInputFiles('#open-folder', asset('Lantern/glTF'));
    await waitNewScene(page, loads);
    const text = (await messageText(page)) ?? '';
    expect(text).toContain(missing);
    expect(text.split(missing).length - 1).toBe(1);
    expect(await page.locator('#message').getAttribute('data-kind')).toBe('warning');
    // How it is lit is a line of information above the warnings, not one of them.
    expect(await page.locator('#message .note').textContent()).toMatch(/^Lantern: its emitters give [\d.]+ % of the light of a default sky; a default sky lights it$/);
    expect(await page.locator('#message details').textContent()).not.toMatch(/sky/);
    const img = await settledImage(page, 2);
    const [r, g, b] = meanRgb(img, 0, 1, 0, 1);
    expect(r + g + b).toBeGreaterThan(10);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('relights the scene with the sky from the panel without reloading it, and a link restores the sky', async () => {
    // The spheres stand in the open, so the sky shows and lights them.
    const { page, errors } = await open(`scene=materials&scale=0.1&${PROGRESSIVE}`);
    await settledImage(page, 1);
    const loads = await page.evaluate(() => window.lantern.sceneLoads);
    await page.locator('.tp-lblv', { hasText: 'light from' }).locator('select').selectOption({ label: 'sun and sky' });
    await expect.poll(() => page.evaluate(() => window.lantern.link)).toMatch(/sky=35%2C45%2C3/);
    // Applied: the scene is lit by the panel's sky (its own has the sun at azimuth 40).
    await expect.poll(() => page.evaluate(() => window.lantern.environment), { timeout: 30_000 }).toMatchObject({ kind: 'sky', sunElevationDeg: 35, sunAzimuthDeg: 45 });
    const high = await settledImage(page, 2);
    const elevation = page.locator('.tp-lblv', { hasText: 'sun elevation' }).locator('input');
    await elevation.fill('3');
    await elevation.press('Enter');
    await expect.poll(() => page.evaluate(() => window.lantern.link)).toMatch(/sky=3%2C45%2C3/);
    await expect.poll(() => page.evaluate(() => window.lantern.environment), { timeout: 30_000 }).toMatchObject({ kind: 'sky', sunElevationDeg: 3 });
    // A sun 3° above the horizon: a darker, redder sky than at 35°.
    const grazing = await settledImage(page, 2);
    expect(imageDifference(high, grazing)).toBeGreaterThan(3);
    // The same scene all along: relit, not loaded again.
    expect(await page.evaluate(() => window.lantern.sceneLoads)).toBe(loads);

    const second = await browser.newPage({ viewport: VIEWPORT });
    await second.goto(await page.evaluate(() => window.lantern.link));
    await waitLoaded(second, 'materials');
    expect(await second.locator('.tp-lblv', { hasText: 'light from' }).locator('select option:checked').textContent()).toBe('sun and sky');
    expect(await second.locator('.tp-lblv', { hasText: 'sun elevation' }).locator('input').inputValue()).toMatch(/^3(\.0+)?$/);
    const restored = await settledImage(second, 2);
    expect(imageDifference(grazing, restored)).toBeLessThan(imageDifference(high, grazing));
    expect(errors).toEqual([]);
    await second.close();
    await page.close();
  });

  it('opens with the lens a link gives, changes it from the panel (the image changes, the link follows)', async () => {
    const { page, errors } = await open(`scene=cornell&scale=0.05&aperture=30&focus=150&${PROGRESSIVE}`);
    expect(await page.evaluate(() => window.lantern.lens)).toEqual({ apertureRadius: 30, focusDistance: 150 });
    const aperture = page.locator('.tp-lblv', { hasText: 'aperture radius' }).locator('input');
    expect(Number(await aperture.inputValue())).toBe(30);
    expect(await page.locator('.tp-lblv', { hasText: 'f-number' }).locator('input, textarea').first().inputValue()).toMatch(/^f\/0\.5\d/);
    // Focused 150 mm in front of the camera, far before the box: every edge is smeared.
    const blurred = await settledImage(page, 4);
    await aperture.fill('0');
    await aperture.press('Enter');
    await expect.poll(() => page.evaluate(() => window.lantern.lens)).toEqual({ apertureRadius: 0, focusDistance: 150 });
    const sharp = await settledImage(page, 4);
    expect(imageDifference(blurred, sharp)).toBeGreaterThan(2);
    // The button focuses on what lies at the image centre: the back wall, beyond the box's opening 800 mm away.
    await page.getByRole('button', { name: 'Focus on the image centre' }).click();
    await expect.poll(() => page.evaluate(() => window.lantern.lens?.focusDistance ?? 0)).toBeGreaterThan(800);
    expect(await page.evaluate(() => window.lantern.link)).toMatch(/aperture=0&focus=1\d{3}/);
    expect(errors).toEqual([]);
    await page.close();
  });

  it('lights the scene with an HDR map opened from the panel', async () => {
    // A flat (uncompressed) Radiance file, 4 × 2, every pixel RGBE (128, 0, 0, 130): radiance (2, 0, 0).
    const header = Buffer.from('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n', 'latin1');
    const red = Buffer.from(Array.from({ length: 8 }, () => [128, 0, 0, 130]).flat());
    const { page, errors } = await open(`scene=materials&scale=0.1&${PROGRESSIVE}`);
    await page.setInputFiles('#open-environment', { name: 'red.hdr', mimeType: 'application/octet-stream', buffer: Buffer.concat([header, red]) });
    await expect.poll(() => page.evaluate(() => window.lantern.environment), { timeout: 30_000 }).toMatchObject({ kind: 'map', name: 'red.hdr' });
    expect(await page.locator('.tp-lblv', { hasText: 'light from' }).locator('select option:checked').textContent()).toBe('HDR map');
    const img = await settledImage(page, 2);
    const [r, g, b] = meanRgb(img, 0, 1, 0, 1);
    expect(r).toBeGreaterThan(2 * (g + b) / 2);
    expect(r).toBeGreaterThan(10);
    // A file that is not an HDR image: an error naming it, the map stays.
    await page.setInputFiles('#open-environment', { name: 'notes.hdr', mimeType: 'text/plain', buffer: Buffer.from('hello') });
    await expect.poll(() => messageText(page)).toMatch(/notes\.hdr/);
    expect(await page.evaluate(() => window.lantern.environment)).toMatchObject({ kind: 'map', name: 'red.hdr' });
    expect(errors).toEqual([]);
    await page.close();
  });
});
