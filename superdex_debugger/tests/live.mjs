// Live check of the debugger page against a running debug server (or the mock with --live).
//
//   node tests/live.mjs URL [--screenshot PATH] [--links base_link,link_1,link_2,ball]
//                           [--signal force_sensor] [--timeout S] [--settle S]
//
// Opens URL (1400x900) and measures: the 3D canvas has content, the given link names are in the
// scene tree, a chart of a signal containing the --signal text is drawn with > 5 points; then
// pause (status paused, and at most the step in flight ends after it: --settle, default 0.3 s,
// plus 1 s), step (status.step +1 exactly) and play
// (status.t increases). Prints one JSON object as the last line of stdout; exits 0 unless the
// browser could not run.
import { settledCanvasStats, isNonBlank, launchBrowser, parseArgs, report, sleep, waitFor } from './lib.mjs';

const { pos, opt } = parseArgs(process.argv.slice(2));
const url = pos[0];
const links = String(opt.links ?? 'base_link,link_1,link_2,ball').split(',').map((s) => s.trim()).filter(Boolean);
const signalText = opt.signal ?? 'force_sensor';
const timeoutMs = Number(opt.timeout ?? 20) * 1000;
// a pause takes effect after the step in flight: longer than one step of the simulation
const settleMs = Number(opt.settle ?? 0.3) * 1000;
const out = { ok: false, url };

if (!url) {
  report({ ...out, error: 'usage: live.mjs URL [--screenshot PATH] [--links a,b] [--signal TEXT]' });
  process.exit(2);
}

let browser;
try {
  browser = await launchBrowser();
} catch (e) {
  report({ ...out, error: `browser: ${e.message}` });
  process.exit(1);
}
const errors = [];
const status = (page) => page.evaluate(() => window.superdex.status());
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.on('pageerror', (e) => errors.push(String(e.message ?? e)));
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  await page.goto(url);
  out.hook = Boolean(await waitFor(page, () => typeof window.superdex === 'object', null, 10000));
  out.connected = Boolean(await waitFor(page, () => window.superdex.connected(), null, timeoutMs));
  // the session message may follow the connection by a moment
  out.sessionMode = (await waitFor(page, () => window.superdex.session()?.mode ?? null, null, timeoutMs)) ?? null;
  out.framesReceived = Boolean(await waitFor(page, () => window.superdex.frameCount() > 0, null, timeoutMs));

  // The 3D view draws something.
  await page.waitForTimeout(500);
  out.canvas = await settledCanvasStats(page, timeoutMs);
  out.drawCount = await page.evaluate(() => window.superdex.drawCount());
  out.canvasNonBlank = isNonBlank(out.canvas);

  // Every requested link is a row of the tree.
  await waitFor(page, (names) => {
    const shown = [...document.querySelectorAll('#tree .row .name')].map((e) => e.textContent);
    return names.every((n) => shown.includes(n));
  }, links, 5000);
  out.linksFound = await page.evaluate((names) => {
    const shown = [...document.querySelectorAll('#tree .row .name')].map((e) => e.textContent);
    return Object.fromEntries(names.map((n) => [n, shown.includes(n)]));
  }, links);
  out.treeHasLinks = links.length > 0 && Object.values(out.linksFound).every(Boolean);

  // A chart of the signal, with more than 5 points drawn.
  const chartInfo = (text) => {
    const c = [...document.querySelectorAll('#charts .chart')].find((e) => e.dataset.signal.includes(text) && e.querySelector('canvas'));
    return c ? { name: c.dataset.signal, points: Number(c.dataset.points) } : null;
  };
  await waitFor(page, (text) => {
    const c = [...document.querySelectorAll('#charts .chart')].find((e) => e.dataset.signal.includes(text) && e.querySelector('canvas'));
    return c && Number(c.dataset.points) > 5;
  }, signalText, timeoutMs);
  const chart = await page.evaluate(chartInfo, signalText);
  out.signalName = chart?.name ?? null;
  out.signalChartPoints = chart?.points ?? 0;
  out.signalPointCount = chart ? await page.evaluate((n) => window.superdex.signalPointCount(n), chart.name) : 0;
  out.plottedSignals = await page.evaluate(() => window.superdex.plottedSignals());
  out.signalNames = await page.evaluate(() => window.superdex.signalNames());
  out.signalPlotted = Boolean(chart && out.plottedSignals.includes(chart.name) && chart.points > 5);

  // Pause: the state becomes paused; the step in flight when the pause arrived may still end
  // (a step is never cut short), and no step after it: over the next settle + 1 s the step count
  // moves by at most one from its value at the acknowledgement.
  await page.evaluate(() => window.superdex.control('pause'));
  out.pausedState = Boolean(await waitFor(page, () => window.superdex.status()?.state === 'paused', null, 5000));
  out.stepAtPause = (await status(page))?.step ?? null;
  await sleep(settleMs);
  out.tPaused0 = (await status(page))?.t ?? null;
  await sleep(1000);
  const sp = await status(page);
  out.tPaused1 = sp?.t ?? null;
  out.stepPaused = sp?.step ?? null;
  out.pauseHolds = out.pausedState && sp?.state === 'paused' && out.stepAtPause !== null && out.stepPaused !== null &&
    out.stepPaused - out.stepAtPause <= 1;

  // Step: exactly one step.
  out.stepBefore = (await status(page))?.step ?? null;
  await page.evaluate(() => window.superdex.control('step'));
  await waitFor(page, (s0) => window.superdex.status()?.step !== s0, out.stepBefore, Math.max(5000, settleMs));
  await sleep(Math.max(500, settleMs));
  const ss = await status(page);
  out.stepAfter = ss?.step ?? null;
  out.stateAfterStep = ss?.state ?? null;
  out.stepAdvancesOne = out.stepBefore !== null && out.stepAfter === out.stepBefore + 1 && ss?.state === 'paused';

  // Play: t moves again.
  out.tPlay0 = (await status(page))?.t ?? null;
  const framesBeforePlay = await page.evaluate(() => window.superdex.frameCount());
  await page.evaluate(() => window.superdex.control('play'));
  await sleep(1000);
  await waitFor(page, (t0) => (window.superdex.status()?.t ?? -Infinity) > t0, out.tPlay0, Math.max(5000, settleMs));
  const sr = await status(page);
  out.tPlay1 = sr?.t ?? null;
  out.stateAfterPlay = sr?.state ?? null;
  out.playResumes = sr?.state === 'playing' && out.tPlay1 > out.tPlay0;
  out.framesBeforePlay = framesBeforePlay;
  out.frameCount = await page.evaluate(() => window.superdex.frameCount());
  out.currentFrameIndex = await page.evaluate(() => window.superdex.currentFrameIndex());

  if (opt.screenshot) {
    await page.waitForTimeout(500);
    await page.screenshot({ path: opt.screenshot });
    out.screenshot = opt.screenshot;
  }
  await page.close();
  out.ok = Boolean(out.connected && out.canvasNonBlank && out.treeHasLinks && out.signalPlotted && out.pauseHolds && out.stepAdvancesOne && out.playResumes);
} catch (e) {
  out.error = String(e?.message ?? e);
} finally {
  out.pageErrors = errors;
  await browser.close().catch(() => {});
}
report(out);
