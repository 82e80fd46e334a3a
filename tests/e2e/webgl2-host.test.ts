/**
 * The WebGL2 host (src/webgl2/) in headless Chromium with WebGPU off, WebGL2 on SwiftShader: a
 * probe program (webgl2-host/probe.wgsl) translated by the build's plugin stands in for the path
 * tracer, so that uniforms written at the WGSL layout, an RGBA32UI texture through usampler2D, a
 * layer of an RGBA8 2D array, the RGBA32F ping-pong, the tone map (lib/color, translated), present
 * and the read-backs' row order are checked against values computed here.
 */
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import type { Browser } from 'playwright-core';
import { build } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { startViewServer, type ViewServer } from '../../src/cli/view-server.ts';
import { glslTranslation } from '../../scripts/glsl-translation.ts';
import { launchWebGl2Browser, watchPage } from './browser.ts';

const ROOT = resolve('.');
const HARNESS = resolve('tests/e2e/webgl2-host');
const W = 4, H = 3;

let dir: string;
let server: ViewServer;
let browser: Browser;

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-webgl2-host-'));
  const probe = { key: 'probe', module: 'probe', wgsl: readFileSync(join(HARNESS, 'probe.wgsl'), 'utf8'), vertexEntry: 'vs_probe', fragmentEntry: 'fs_probe' };
  await build({ root: HARNESS, configFile: false, base: './', logLevel: 'warn', plugins: [glslTranslation({ sourceRoot: ROOT, extra: [probe] })], build: { outDir: dir, emptyOutDir: true, target: 'es2022' } });
  server = await startViewServer({ appDir: dir, files: [], port: 0 });
  browser = await launchWebGl2Browser();
});

afterAll(async () => {
  await browser?.close();
  await server?.close();
  if (dir) rmSync(dir, { recursive: true, force: true });
});

const srgb = (c: number) => (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055);

describe('the WebGL2 host on SwiftShader, WebGPU off', () => {
  it('accumulates the probe through uniforms, integer and array textures, tone-maps, presents, and reads rows top first', async () => {
    const page = await browser.newPage({ viewport: { width: 64, height: 64 } });
    watchPage(page);
    await page.goto(server.url);
    await page.waitForFunction(() => 'probeHost' in window);
    const r = await page.evaluate(() => (window as unknown as { probeHost: () => Promise<{ sums: number[]; image: number[]; canvas: number[]; samples: number; compiles: { key: string; ms: number }[]; renderer: string; parallel: boolean; misfit: string; adapter: boolean }> }).probeHost());
    // navigator.gpu may exist on a secure page; with WebGPU off it gives no adapter.
    expect(r.adapter).toBe(false);
    expect(r.renderer).toMatch(/SwiftShader/i);
    expect(r.samples).toBe(3);
    expect(r.compiles.map((c) => c.key)).toEqual(['tonemap', 'probe']);
    for (const c of r.compiles) expect(c.ms).toBeGreaterThan(0);
    console.log(`WebGL2 compiles on ${r.renderer} (parallel compile: ${r.parallel}): ${r.compiles.map((c) => `${c.key} ${c.ms.toFixed(0)} ms`).join(', ')}`);
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const i = (y * W + x) * 4;
        // Three samples of (0.02 (x + 10 y) + 0.1, 0.02 · 7 + 0.05, 0.2 x + 0.01, 1): row 0 is the top row (y = 0).
        const mean = [0.02 * (x + 10 * y) + 0.1, 0.02 * 7 + 0.05, (51 * x) / 255 + 0.01];
        expect(r.sums.slice(i, i + 4).map((v) => +v.toFixed(4)), `sum at (${x}, ${y})`).toEqual([...mean.map((m) => +(3 * m).toFixed(4)), 3]);
        const expected = mean.map((m) => Math.round(255 * srgb(Math.min(1, m))));
        for (let c = 0; c < 3; c++) expect(Math.abs(r.image[i + c]! - expected[c]!), `image (${x}, ${y}) channel ${c}`).toBeLessThanOrEqual(1);
        // The canvas (4 × 3, the image's size) shows row 0 at the top: GL's readPixels starts at the bottom.
        const j = ((H - 1 - y) * W + x) * 4;
        expect(r.canvas.slice(j, j + 3), `canvas (${x}, ${y})`).toEqual(r.image.slice(i, i + 3));
      }
    }
    expect(r.misfit).toMatch(/^the scene 'probe' does not fit WebGL2's texture limits: too wide is \d+ × 1 texels, this GPU's WebGL2 allows \d+ × \d+$/);
    await page.close();
  });
});
