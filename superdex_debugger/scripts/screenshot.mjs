#!/usr/bin/env node
// Development tool: a 1400x900 screenshot of the debugger page.
//
//   node scripts/screenshot.mjs URL OUT.png [--select NAME] [--frames] [--seek K] [--wait S]
//                               [--pause] [--check SIGNAL]
//
// --select clicks the tree row with that name, --frames turns the link frames on, --seek shows
// stored frame K, --pause sends the pause control first, --check ticks a signal's checkbox.
import { launchBrowser, parseArgs, waitFor } from '../tests/lib.mjs';

const { pos, opt } = parseArgs(process.argv.slice(2), ['frames', 'pause']);
const [url, out] = pos;
if (!url || !out) {
  console.error('usage: screenshot.mjs URL OUT.png [--select NAME] [--frames] [--seek K] [--wait S] [--pause] [--check SIGNAL]');
  process.exit(2);
}
const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.on('pageerror', (e) => console.error('page error:', e.message));
  await page.goto(url);
  await waitFor(page, () => window.superdex?.frameCount() > 0, null, 20000);
  await page.waitForTimeout(Number(opt.wait ?? 2) * 1000);
  if (opt.pause) await page.evaluate(() => window.superdex.control('pause'));
  if (opt.select) await page.locator('#tree .row .name', { hasText: opt.select }).first().click();
  if (opt.frames) await page.locator('[data-id="frames"]').check();
  if (opt.check) await page.locator(`#signal-list input[data-name*="${opt.check}"]`).first().check();
  if (opt.seek !== undefined) await page.evaluate((k) => window.superdex.seek(k), Number(opt.seek));
  await page.waitForTimeout(800);
  await page.screenshot({ path: out });
  await page.close();
} finally {
  await browser.close();
}
