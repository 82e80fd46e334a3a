/**
 * Headless Chromium with WebGPU on SwiftShader (Debian's `chromium` package), driven by
 * playwright-core, and the production page built fresh and served by `lantern view`'s server.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium, type Browser, type Page } from 'playwright-core';
import { build } from 'vite';
import { startViewServer } from '../../src/cli/view-server.ts';

export const CHROMIUM = process.env.LANTERN_CHROMIUM ?? '/usr/bin/chromium';

// --use-vulkan=swiftshader matters: without it, the first frame presented to a WebGPU canvas loses
// the device ("a valid external Instance reference no longer exists") in headless Chromium 156.
export const CHROMIUM_ARGS = [
  '--enable-unsafe-webgpu',
  '--enable-features=Vulkan',
  '--use-vulkan=swiftshader',
  '--use-angle=swiftshader',
  '--use-webgpu-adapter=swiftshader',
  '--no-sandbox',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];

export async function launchBrowser(): Promise<Browser> {
  return chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS, headless: true });
}

export interface ServedPage {
  readonly url: string;
  /** Addresses of the offered files, relative to the page (files/<n>/<name>). */
  readonly fileUrls: readonly string[];
  close(): Promise<void>;
}

/**
 * Builds the page into a temporary folder and serves it, with `files`, on a free local port through
 * the same server `lantern view` uses.
 */
export async function servePage(files: readonly string[] = []): Promise<ServedPage> {
  const outDir = mkdtempSync(join(tmpdir(), 'lantern-page-'));
  await build({ logLevel: 'warn', build: { outDir, emptyOutDir: true } });
  const server = await startViewServer({ appDir: outDir, files, port: 0 });
  return {
    url: server.url,
    fileUrls: server.fileUrls,
    async close() {
      await server.close();
      rmSync(outDir, { recursive: true, force: true });
    },
  };
}

/** Drops files on the page as the browser delivers a drop: a DataTransfer of File objects on dragenter and drop events. */
export async function dropFiles(page: Page, files: readonly { name: string; bytes: number[] }[]): Promise<void> {
  await page.evaluate((list) => {
    const data = new DataTransfer();
    for (const f of list) data.items.add(new File([new Uint8Array(f.bytes)], f.name));
    window.dispatchEvent(new DragEvent('dragenter', { dataTransfer: data, cancelable: true }));
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: data, cancelable: true }));
  }, files);
}
