import { it } from 'vitest';
import { launchBrowser, servePage, waitForPage, watchPage } from './browser.ts';
it('measures', async () => {
  const served = await servePage();
  const browser = await launchBrowser();
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  watchPage(page);
  await page.goto(`${served.url}?scene=cornell`);
  await waitForPage(page, () => window.lantern && !window.lantern.loading && window.lantern.scene !== '', undefined, 60_000, 'scene');
  await page.click('#play');
  const t0 = Date.now();
  for (let i = 0; i < 40; i++) {
    await page.waitForTimeout(1500);
    const s = await page.evaluate(() => ({ b: window.lantern.budget, f: window.lantern.frame, samples: window.lantern.samples, status: document.getElementById('stats')?.textContent }));
    console.log(((Date.now() - t0) / 1000).toFixed(1), JSON.stringify(s));
  }
  // Click pause timing
  const c = Date.now();
  await page.click('#play');
  console.log('pause click ms', Date.now() - c);
  await browser.close();
  await served.close();
}, 300_000);
