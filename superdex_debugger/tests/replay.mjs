// Replay check of the debugger page against the recording it replays.
//
//   node tests/replay.mjs URL RECORDING.jsonl [--screenshot PATH] [--link-handle H] [--timeout S]
//
// Opens URL (1400x900), waits for window.superdex.replayEnded(), then compares the stored frames
// of the first scene with the file's `frame` lines of that scene: the count, and links[H] of the
// frames at indices 0, middle and last (max abs difference). Prints one JSON object as the last
// line of stdout; exits 0 unless the browser could not run. `renderModelCount` is the page's count
// of links drawn with their glTF render model (waits for `renderModelsDeclared`, the
// links of the first scene's actors that have a `renderModel` in the file; as long as the
// timeout allows: a loaded machine decodes the models slowly).
import fs from 'node:fs';
import { settledCanvasStats, isNonBlank, launchBrowser, parseArgs, report, waitFor } from './lib.mjs';

const { pos, opt } = parseArgs(process.argv.slice(2));
const [url, recording] = pos;
const timeoutMs = Number(opt.timeout ?? 60) * 1000;
const out = { ok: false, url, recording };

if (!url || !recording) {
  report({ ...out, error: 'usage: replay.mjs URL RECORDING.jsonl [--screenshot PATH] [--link-handle H]' });
  process.exit(2);
}

// The file's frames, per scene, in order; links with a render model per actor still present.
const fileFrames = [];
let firstScene = null;
const modelLinks = new Map();
for (const line of fs.readFileSync(recording, 'utf8').split('\n')) {
  if (!line.trim()) continue;
  let o;
  try {
    o = JSON.parse(line);
  } catch {
    continue;
  }
  if (o?.type === 'actor') {
    const n = Array.isArray(o.links) ? o.links.filter((l) => typeof l?.renderModel?.glb === 'string' && l.renderModel.glb.length > 0).length : 0;
    modelLinks.set(`${o.scene}:${o.handle}`, { scene: o.scene, n });
  } else if (o?.type === 'destroy') modelLinks.delete(`${o.scene}:${o.handle}`);
  if (o?.type !== 'frame') continue;
  firstScene ??= o.scene;
  fileFrames.push(o);
}
const sceneFrames = fileFrames.filter((f) => f.scene === firstScene);
out.fileFrames = fileFrames.length;
out.fileFramesFirstScene = sceneFrames.length;
out.renderModelsDeclared = [...modelLinks.values()].filter((m) => m.scene === firstScene).reduce((a, m) => a + m.n, 0);

let browser;
try {
  browser = await launchBrowser();
} catch (e) {
  report({ ...out, error: `browser: ${e.message}` });
  process.exit(1);
}
const errors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.on('pageerror', (e) => errors.push(String(e.message ?? e)));
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  await page.goto(url);
  out.hook = Boolean(await waitFor(page, () => typeof window.superdex === 'object', null, 10000));
  out.connected = Boolean(await waitFor(page, () => window.superdex.connected(), null, 10000));
  out.replayEnded = Boolean(await waitFor(page, () => window.superdex.replayEnded(), null, timeoutMs));
  // the session message may follow the connection by a moment
  out.sessionMode = (await waitFor(page, () => window.superdex.session()?.mode ?? null, null, timeoutMs)) ?? null;
  out.endFrames = await page.evaluate(() => window.superdex.replayTotal());
  out.frameCount = await page.evaluate(() => window.superdex.frameCount());
  // The page keeps at most 20000 frames per scene: the newest ones.
  const kept = sceneFrames.slice(-20000);
  out.expectedFrameCount = kept.length;
  out.frameCountMatches = out.frameCount === kept.length;

  const h = opt['link-handle'] ?? Object.keys(kept[0]?.links ?? {}).at(-1);
  out.linkHandle = h === undefined ? null : Number(h);
  const idx = [...new Set([0, Math.floor((kept.length - 1) / 2), kept.length - 1])].filter((k) => k >= 0);
  out.indices = idx;
  let maxDiff = 0;
  let compared = 0;
  const diffs = [];
  for (const k of idx) {
    const got = await page.evaluate(([k, h]) => window.superdex.frame(k)?.links?.[h] ?? null, [k, String(h)]);
    const want = kept[k]?.links?.[String(h)] ?? null;
    let d;
    if (!got || !want || got.length !== want.length) d = Infinity;
    else d = Math.max(...want.map((v, i) => Math.abs(v - got[i])));
    diffs.push({ k, diff: Number.isFinite(d) ? d : null, t: kept[k]?.t ?? null });
    maxDiff = Math.max(maxDiff, d);
    compared++;
  }
  out.linkDiffs = diffs;
  out.maxAbsDiff = Number.isFinite(maxDiff) ? maxDiff : null;
  out.linksMatch = compared > 0 && Number.isFinite(maxDiff) && maxDiff <= 1e-9;

  // Seeking shows the chosen frame.
  const mid = idx[Math.floor(idx.length / 2)] ?? 0;
  await page.evaluate((k) => window.superdex.seek(k), mid);
  out.seekWorks = Boolean(await waitFor(page, (k) => window.superdex.currentFrameIndex() === k, mid, 10000));

  // The actors drawn at the first and the last frame (destroyed ones only up to their last frame).
  const shownAt = async (k) => {
    await page.evaluate((k) => window.superdex.seek(k), k);
    await waitFor(page, (k) => window.superdex.currentFrameIndex() === k, k, 10000);
    await page.waitForTimeout(100);
    return page.evaluate(() => window.superdex.shownActors());
  };
  out.shownActorsFirst = await shownAt(0);
  out.shownActorsLast = await shownAt(kept.length - 1);
  out.actorNames = await page.evaluate(() => window.superdex.actorNames());
  // Render models load asynchronously; a model that cannot be loaded is not counted.
  const modelCount = () => (typeof window.superdex.renderModelCount === 'function' ? window.superdex.renderModelCount() : null);
  if (out.renderModelsDeclared > 0) await waitFor(page, (n) => window.superdex.renderModelCount?.() >= n, out.renderModelsDeclared, timeoutMs);
  out.renderModelCount = await page.evaluate(modelCount);
  out.canvas = await settledCanvasStats(page, timeoutMs);
  out.drawCount = await page.evaluate(() => window.superdex.drawCount());
  out.upAxis = await page.evaluate(() => window.superdex.upAxis());
  out.canvasNonBlank = isNonBlank(out.canvas);
  if (opt.screenshot) {
    await page.waitForTimeout(300);
    await page.screenshot({ path: opt.screenshot });
    out.screenshot = opt.screenshot;
  }
  await page.close();
  out.ok = out.replayEnded && out.frameCountMatches && out.linksMatch;
} catch (e) {
  out.error = String(e?.message ?? e);
} finally {
  out.pageErrors = errors;
  await browser.close().catch(() => {});
}
report(out);
