// Shared helpers of the page test scripts: launching Debian's chromium through playwright-core,
// argument parsing, polling the page's window.superdex hook, and measuring the 3D canvas.
import { chromium } from 'playwright-core';

/** Chromium binary (Debian package). SUPERDEX_CHROMIUM overrides it. */
export const CHROMIUM = process.env.SUPERDEX_CHROMIUM || '/usr/bin/chromium';

/** Headless chromium with software WebGL (SwiftShader). */
export async function launchBrowser() {
  return chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--no-sandbox', '--use-gl=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--disable-dev-shm-usage'],
  });
}

/** Splits argv into positional arguments and --name value / --flag options. */
export function parseArgs(argv, flags = []) {
  const pos = [];
  const opt = {};
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a.startsWith('--')) {
      const name = a.slice(2);
      if (flags.includes(name)) opt[name] = true;
      else opt[name] = argv[++i];
    } else pos.push(a);
  }
  return { pos, opt };
}

/** Polls `fn` (evaluated in the page, with `arg`) until it returns a truthy value or timeoutMs passes; returns the last value. */
export async function waitFor(page, fn, arg, timeoutMs, intervalMs = 100) {
  const end = Date.now() + timeoutMs;
  let v;
  for (;;) {
    try {
      v = await page.evaluate(fn, arg);
    } catch {
      v = undefined;
    }
    if (v || Date.now() >= end) return v;
    await page.waitForTimeout(intervalMs);
  }
}

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

/**
 * Statistics of the pixels of the 3D view's own canvas (not the page background behind it):
 * the fraction of drawn (non-transparent) pixels, the standard deviation of their luminance and
 * the number of distinct colours (4 bits per channel), and whether its WebGL context is lost.
 * Reads the WebGL canvas through a 2D copy.
 */
export async function canvasStats(page, selector = '#view canvas') {
  return page.evaluate((sel) => {
    const src = document.querySelector(sel);
    if (!src || !src.width || !src.height) return { width: 0, height: 0, drawnFraction: 0, lumaStd: 0, distinctColors: 0 };
    // whether the WebGL context is lost at this reading (its canvas then reads as empty)
    const gl = src.getContext('webgl2') ?? src.getContext('webgl');
    const contextLost = gl ? gl.isContextLost() : null;
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    let sum = 0;
    let sum2 = 0;
    const colors = new Set();
    for (let i = 0; i < d.length; i += 4) {
      if (d[i + 3] < 8) continue;
      n++;
      const l = 0.2126 * d[i] + 0.7152 * d[i + 1] + 0.0722 * d[i + 2];
      sum += l;
      sum2 += l * l;
      colors.add(((d[i] >> 4) << 8) | ((d[i + 1] >> 4) << 4) | (d[i + 2] >> 4));
    }
    const mean = n ? sum / n : 0;
    return {
      width: c.width,
      height: c.height,
      drawnFraction: n / (c.width * c.height),
      lumaStd: n ? Math.sqrt(Math.max(sum2 / n - mean * mean, 0)) : 0,
      distinctColors: colors.size,
      contextLost,
    };
  }, selector);
}

/** A canvas has real content: some pixels drawn, with variance and several colours. */
export function isNonBlank(s) {
  return s.drawnFraction > 0.01 && s.lumaStd > 3 && s.distinctColors >= 8;
}

/**
 * Canvas statistics once the view shows content, or the last ones after timeoutMs: a render
 * loop may be between a resize and its next draw at the moment of one reading.
 */
export async function settledCanvasStats(page, timeoutMs = 5000, selector = '#view canvas') {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const s = await canvasStats(page, selector);
    if (isNonBlank(s) || Date.now() >= end) return s;
    await page.waitForTimeout(100);
  }
}

/** Prints the result object as one JSON line (the last line of stdout). */
export function report(obj) {
  process.stdout.write(JSON.stringify(obj) + '\n');
}
