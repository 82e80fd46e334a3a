/**
 * Headless Chromium with WebGPU on SwiftShader (Debian's `chromium` package), driven by
 * playwright-core, and the production page (built once per run: global-setup.ts) served by
 * `lantern view`'s server; pageTestbed starts both for a test file, openWatchedPage opens a watched page.
 */
import { chromium, type Browser, type Page } from 'playwright-core';
import { afterAll, beforeAll, inject } from 'vitest';
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

/**
 * Chromium with WebGPU switched off (navigator.gpu undefined) and WebGL2 on SwiftShader through
 * ANGLE: what a browser without WebGPU gives the page, for the WebGL2 backend's tests. SwiftShader's
 * WebGL2 has EXT_color_buffer_float but not KHR_parallel_shader_compile (compiles block).
 */
export const CHROMIUM_WEBGL2_ARGS = [
  '--disable-features=WebGPU',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--no-sandbox',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
];

export async function launchWebGl2Browser(): Promise<Browser> {
  return chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_WEBGL2_ARGS, headless: true });
}

export interface ServedPage {
  readonly url: string;
  /** Addresses of the offered files, relative to the page (files/<n>/<name>). */
  readonly fileUrls: readonly string[];
  close(): Promise<void>;
}

/**
 * Serves the page (built once for the e2e project by tests/e2e/global-setup.ts), with `files`, on a
 * free local port through the same server `lantern view` uses.
 */
export async function servePage(files: readonly string[] = []): Promise<ServedPage> {
  const server = await startViewServer({ appDir: inject('lanternPage'), files, port: 0 });
  return {
    url: server.url,
    fileUrls: server.fileUrls,
    async close() {
      await server.close();
    },
  };
}

/** The served page and the browser of one test file (pageTestbed): set once its beforeAll has run. */
export interface PageTestbed {
  readonly browser: Browser;
  readonly served: ServedPage;
}

/** Serves the page (with `files`) and launches the browser before the file's tests, and closes both after them. */
export function pageTestbed(files: readonly string[] = []): PageTestbed {
  const bed: { browser?: Browser; served?: ServedPage } = {};
  beforeAll(async () => {
    bed.served = await servePage(files);
    bed.browser = await launchBrowser();
  });
  afterAll(async () => {
    await bed.browser?.close();
    await bed.served?.close();
  });
  return {
    get browser() {
      if (!bed.browser) throw new Error('pageTestbed: the browser is launched in beforeAll');
      return bed.browser;
    },
    get served() {
      if (!bed.served) throw new Error('pageTestbed: the page is served in beforeAll');
      return bed.served;
    },
  };
}

/** Opens `url` in a new page of `viewport`, watched (watchPage), collecting its uncaught errors. */
export async function openWatchedPage(browser: Browser, url: string, viewport: { readonly width: number; readonly height: number }): Promise<{ page: Page; errors: string[] }> {
  const page = await browser.newPage({ viewport });
  const errors: string[] = [];
  page.on('pageerror', (e) => errors.push(e.message));
  watchPage(page);
  await page.goto(url);
  return { page, errors };
}

/** Waits until the page has loaded a scene (window.lantern set, nothing loading, a scene named). */
export async function waitForScene(page: Page, what: string): Promise<void> {
  await waitForPage(page, () => window.lantern && !window.lantern.loading && window.lantern.scene !== '', undefined, 60_000, what);
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

/** The last lines a page printed (console and uncaught errors), kept per page for reports on a timeout. */
const pageLogs = new WeakMap<Page, string[]>();
const LOG_LINES = 40;

/** The longest a Playwright action (click, fill, press) on a watched page waits; page.evaluate has no limit of its own. */
export const ACTION_TIMEOUT_MS = 120_000;

/**
 * Keeps the page's console output and uncaught errors (the last 40 lines) so that a wait that times
 * out can say what the page was doing (waitForPage). Call it before `goto`.
 */
export function watchPage(page: Page): void {
  if (pageLogs.has(page)) return;
  const log: string[] = [];
  pageLogs.set(page, log);
  // No action (a click, a fill) may wait forever for its element: a step that cannot happen fails
  // with its name instead of running into the test's own limit without a word.
  page.setDefaultTimeout(ACTION_TIMEOUT_MS);
  const keep = (line: string) => {
    log.push(`${(performance.now() / 1000).toFixed(1)} s ${line}`);
    if (log.length > LOG_LINES) log.shift();
  };
  page.on('console', (m) => keep(`console.${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => keep(`pageerror: ${e.stack ?? e.message}`));
  page.on('crash', () => keep('the page crashed'));
}

/** The page's state as the test hook and the page show it, for a failure report. */
export async function pageState(page: Page): Promise<string> {
  try {
    const state = await page.evaluate(() => {
      const l = window.lantern;
      const hook = l
        ? { state: l.state, samples: l.samples, scene: l.scene, loading: l.loading, sceneLoads: l.sceneLoads, firstFrameMs: l.firstFrameMs, kernel: l.kernel, gpuResources: l.gpuResources }
        : 'window.lantern is not set';
      const play = document.getElementById('play') as HTMLButtonElement | null;
      const message = document.getElementById('message');
      return {
        lantern: hook,
        hidden: document.hidden,
        visibilityState: document.visibilityState,
        play: play ? { text: play.textContent, disabled: play.disabled } : 'no #play',
        message: message && !message.hidden ? `${message.dataset.kind ?? ''}: ${message.textContent ?? ''}` : '',
        canvas: { ...(document.getElementById('view')?.dataset ?? {}) },
      };
    });
    return JSON.stringify(state, null, 1);
  } catch (e) {
    return `(the page's state could not be read: ${(e as Error).message})`;
  }
}

/** What the page is doing now, for a failure's message: its state (pageState) and its last console lines (watchPage). */
export async function pageReport(page: Page): Promise<string> {
  const log = pageLogs.get(page);
  const lines = log ? (log.length > 0 ? log.join('\n') : '(nothing printed)') : '(not watched: call watchPage before goto)';
  return `the page now:\n${await pageState(page)}\nits last console lines:\n${lines}`;
}

/** Runs `wait` (a waitForFunction, an expect.poll); a failure is rethrown with the page's report (pageReport) appended. */
export async function withPageReport<T>(page: Page, what: string, wait: () => Promise<T>): Promise<T> {
  try {
    return await wait();
  } catch (e) {
    throw new Error(`${(e as Error).message.split('\n')[0]}\nwaiting for ${what}; ${await pageReport(page)}`, { cause: e });
  }
}

/** page.waitForFunction, and on a timeout (or any failure) an error that carries the page's report (pageReport). */
export async function waitForPage<Arg extends string | number | boolean | undefined>(page: Page, fn: (arg: Arg) => unknown, arg: Arg, timeout: number, what = 'the page'): Promise<void> {
  await withPageReport(page, what, () => page.waitForFunction(fn as (arg: unknown) => unknown, arg as unknown, { timeout }));
}

/**
 * Waits until the viewer holds `samples` samples, failing at once (with the page's state and console)
 * if it stops with an error instead of waiting out the timeout.
 */
export async function waitForSamples(page: Page, samples: number, timeout: number): Promise<void> {
  await waitForPage(page, (n) => window.lantern.samples >= n || window.lantern.state === 'failed', samples, timeout, `${samples} samples`);
  if ((await page.evaluate(() => window.lantern.state)) === 'failed') throw new Error(`the viewer failed while waiting for ${samples} samples; ${await pageReport(page)}`);
}

/**
 * Makes every animation frame's time `ms` older than the browser gives it, before the page's scripts
 * run: what a main thread busy past a frame boundary sees (the frame's time precedes work done just
 * before the request), deterministically. Frames keep their spacing.
 */
export async function lagAnimationFrames(page: Page, ms: number): Promise<void> {
  await page.addInitScript((lag) => {
    const request = window.requestAnimationFrame.bind(window);
    window.requestAnimationFrame = (callback) => request((time) => callback(time - lag));
  }, ms);
}
