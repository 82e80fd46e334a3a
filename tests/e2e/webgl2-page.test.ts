/**
 * The page on the WebGL2 backend (issue #30) in headless Chromium with WebGPU off (SwiftShader's
 * WebGL2 through ANGLE): the backend is chosen and said, the fragment path tracer compiles and
 * converges, and its estimate matches the WebGPU compute kernel's (the same page in a Chromium with
 * WebGPU on SwiftShader) at equal settings: channel means within 1 %, the median of 8×8 block means
 * within 3 %. The white furnace gives 5.0 within 1 %. Images are tiny (scale 0.1 of 640×400).
 */
import type { Browser, Page } from 'playwright-core';
import { furnaceRadiance } from '../../src/loaders/builtin/furnace.ts';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launchBrowser, launchWebGl2Browser, openWatchedPage, servePage, waitForPage, waitForSamples, type ServedPage } from './browser.ts';

let webgl2: Browser;
let webgpu: Browser;
let served: ServedPage;
const VIEWPORT = { width: 640, height: 400 };
const PROGRESSIVE = 'temporal=0&denoise=0&scale=0.1';

beforeAll(async () => {
  served = await servePage();
  [webgl2, webgpu] = await Promise.all([launchWebGl2Browser(), launchBrowser()]);
});

afterAll(async () => {
  await webgl2?.close();
  await webgpu?.close();
  await served?.close();
});

interface Radiance {
  samples: number;
  width: number;
  height: number;
  rgb: number[];
}

/** Opens `query`, plays until `samples`, pauses and reads the estimate. */
async function render(browser: Browser, query: string, samples: number): Promise<{ page: Page; errors: string[]; radiance: Radiance; ms: number; firstFrameMs: number }> {
  const { page, errors } = await openWatchedPage(browser, `${served.url}?${query}`, VIEWPORT);
  await waitForPage(page, () => window.lantern && !window.lantern.loading && window.lantern.scene !== '' && !(document.getElementById('play') as HTMLButtonElement).disabled, undefined, 60_000, 'the scene loaded and Play enabled');
  const started = Date.now();
  await page.click('#play');
  await waitForSamples(page, samples, 240_000);
  const ms = Date.now() - started;
  await page.click('#play');
  await expect.poll(() => page.evaluate(() => window.lantern.state)).toBe('paused');
  const radiance = await page.evaluate(() => window.lantern.readRadiance());
  const firstFrameMs = (await page.evaluate(() => window.lantern.firstFrameMs)) ?? NaN;
  return { page, errors, radiance, ms, firstFrameMs };
}

function channelMeans(r: Radiance): [number, number, number] {
  const m = [0, 0, 0];
  for (let i = 0; i < r.rgb.length; i++) m[i % 3]! += r.rgb[i]!;
  const n = r.width * r.height;
  return [m[0]! / n, m[1]! / n, m[2]! / n];
}

/** The median over 8×8 blocks of |a − b| / b of the blocks' mean luminance (blocks b lights). */
function blockMedianDifference(a: Radiance, b: Radiance, block = 8): number {
  const lum = (r: Radiance, i: number) => 0.2126 * r.rgb[i * 3]! + 0.7152 * r.rgb[i * 3 + 1]! + 0.0722 * r.rgb[i * 3 + 2]!;
  const diffs: number[] = [];
  for (let by = 0; by + block <= a.height; by += block) {
    for (let bx = 0; bx + block <= a.width; bx += block) {
      let sa = 0, sb = 0;
      for (let y = by; y < by + block; y++) for (let x = bx; x < bx + block; x++) {
        sa += lum(a, y * a.width + x);
        sb += lum(b, y * b.width + x);
      }
      if (sb > 0) diffs.push(Math.abs(sa - sb) / sb);
    }
  }
  diffs.sort((p, q) => p - q);
  return diffs[Math.floor(diffs.length / 2)]!;
}

describe('the page on WebGL2 (WebGPU off, SwiftShader)', () => {
  it('chooses WebGL2 without WebGPU, says why, and converges the Cornell box to the WebGPU compute kernel\'s image', async () => {
    const samples = 64;
    const gl = await render(webgl2, `scene=cornell&${PROGRESSIVE}&spf=4`, samples);
    const backend = await gl.page.evaluate(() => window.lantern.backend);
    expect(backend.kind).toBe('webgl2');
    expect(backend.description).toBe('WebGL2 (fragment path tracer): WebGPU not available (no adapter)');
    expect(await gl.page.locator('#stats').textContent()).toContain('WebGL2');
    const gpu = await render(webgpu, `scene=cornell&${PROGRESSIVE}&spf=4`, samples);
    expect(await gpu.page.evaluate(() => window.lantern.backend.kind)).toBe('webgpu');
    expect([gl.radiance.width, gl.radiance.height]).toEqual([gpu.radiance.width, gpu.radiance.height]);
    const a = channelMeans(gl.radiance), b = channelMeans(gpu.radiance);
    const median = blockMedianDifference(gl.radiance, gpu.radiance);
    // After the first frame (compiles and the first draw), milliseconds a sample of the whole image.
    const perSample = (r: { ms: number; firstFrameMs: number; radiance: Radiance }) => ((r.ms - r.firstFrameMs) / r.radiance.samples).toFixed(1);
    console.log(`Cornell ${gl.radiance.width}×${gl.radiance.height}: WebGL2 ${gl.radiance.samples} spp in ${gl.ms} ms (first frame ${gl.firstFrameMs.toFixed(0)} ms, then ${perSample(gl)} ms/spp), means ${a.map((v) => v.toFixed(4))}; WebGPU ${gpu.radiance.samples} spp in ${gpu.ms} ms (first frame ${gpu.firstFrameMs.toFixed(0)} ms, then ${perSample(gpu)} ms/spp), means ${b.map((v) => v.toFixed(4))}; block median ${(100 * median).toFixed(2)} %; compiles ${backend.compiles.map((c) => `${c.key} ${c.ms.toFixed(0)} ms`).join(', ')}`);
    for (let c = 0; c < 3; c++) expect(Math.abs(a[c]! - b[c]!) / b[c]!, `channel ${c}`).toBeLessThan(0.01);
    expect(median).toBeLessThan(0.03);
    expect(gl.errors).toEqual([]);
    expect(gpu.errors).toEqual([]);
    await gl.page.close();
    await gpu.page.close();
  });

  it('renders the white furnace at 5.0 within 1 %, forced by backend=webgl2', async () => {
    // 64 bounces: the partial sum Σ 0.8^k is 5 to 6 digits (8, the default, stops at 4.33).
    const gl = await render(webgl2, `scene=furnace&${PROGRESSIVE}&spf=4&bounces=64&backend=webgl2`, 64);
    expect(furnaceRadiance(64)).toBeCloseTo(5, 4);
    expect((await gl.page.evaluate(() => window.lantern.backend)).description).toBe('WebGL2 (fragment path tracer): forced by backend=webgl2');
    const means = channelMeans(gl.radiance);
    console.log(`furnace on WebGL2: ${gl.radiance.samples} spp, means ${means.map((v) => v.toFixed(4))}`);
    for (const m of means) expect(Math.abs(m - 5) / 5).toBeLessThan(0.01);
    expect(gl.errors).toEqual([]);
    await gl.page.close();
  });
});
