#!/usr/bin/env node
// Development stand-in for the engine's debug server: serves dist/ under /TOKEN/ and plays a
// recording over the WebSocket at /TOKEN/ws, as a replay (default) or as a fake live run.
//
//   node scripts/mock_server.mjs RECORDING.jsonl [--port N] [--token HEX] [--live]
//                                [--fabricate | --no-fabricate] [--axes FLU|RUB]
//
// Prints the page URL (http://127.0.0.1:PORT/TOKEN/) as the first line on stdout.
// Replay: session (mode "replay"), every line of the file in batches, then {"type":"end"}.
// Live: session (mode "live"), the descriptions, then frames at up to 60 Hz with `status`
// messages; honours pause / play / fast / step / restore. Frames loop at the end of the file
// with continuing t and step. `step` here advances one recorded frame.
// Status messages carry an extra `sentAt` (ms since the epoch) to measure the page's lag;
// MOCK_DEBUG=1 logs the control messages received.
// --fabricate (default in live) adds `signals`, `joints`, `numDofs` and link `joint` fields
// when the recording lacks them, derived from the recorded poses and contacts.
import crypto from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';

const here = path.dirname(fileURLToPath(import.meta.url));
const distDir = path.resolve(here, '..', 'dist');

function parseArgs(argv) {
  const o = { file: null, port: 0, token: crypto.randomBytes(16).toString('hex'), live: false, fabricate: null, axes: 'FLU' };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === '--port') o.port = Number(argv[++i]);
    else if (a === '--token') o.token = argv[++i];
    else if (a === '--live') o.live = true;
    else if (a === '--fabricate') o.fabricate = true;
    else if (a === '--no-fabricate') o.fabricate = false;
    else if (a === '--axes') o.axes = argv[++i];
    else if (!o.file) o.file = a;
    else throw new Error(`unexpected argument ${a}`);
  }
  if (!o.file) throw new Error('usage: mock_server.mjs RECORDING.jsonl [--port N] [--token HEX] [--live] [--fabricate|--no-fabricate] [--axes FLU|RUB]');
  if (o.fabricate === null) o.fabricate = o.live;
  return o;
}

const opts = parseArgs(process.argv.slice(2));

// ---------- the recording ----------
const rawLines = fs.readFileSync(opts.file, 'utf8').split('\n').filter((l) => l.trim().length > 0);
const parsed = rawLines.map((l) => {
  try {
    return JSON.parse(l);
  } catch {
    return null;
  }
});

/** Rotation angle (rad) of quaternion [x,y,z,w], signed by its largest axis component. */
function signedAngle(q) {
  const [x, y, z, w] = q;
  const s = Math.hypot(x, y, z);
  const axis = [x, y, z].reduce((best, v) => (Math.abs(v) > Math.abs(best) ? v : best), 0);
  return 2 * Math.atan2(s, w) * (axis < 0 ? -1 : 1) * (w < 0 ? -1 : 1);
}
const qmulConj = (a, b) => {
  // conj(a) * b for quaternions [x,y,z,w].
  const [ax, ay, az, aw] = [-a[0], -a[1], -a[2], a[3]];
  const [bx, by, bz, bw] = b;
  return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz];
};

/** Adds joints/signals/numDofs/joint fields derived from poses and contacts (only where absent). */
function fabricate(objs) {
  const actors = objs.filter((o) => o?.type === 'actor');
  const frames = objs.filter((o) => o?.type === 'frame');
  const relAngles = (a, f) =>
    a.links.map((l) => {
      const p = l.parent >= 0 ? f.links?.[a.links[l.parent].handle] : null;
      const c = f.links?.[l.handle];
      return p && c ? signedAngle(qmulConj(p.slice(3), c.slice(3))) : 0;
    });
  for (const a of actors) {
    if (a.kind !== 'articulated' || !Array.isArray(a.links)) continue;
    // A joint is revolute if its relative angle changes over the recording, else hard.
    const lo = a.links.map(() => Infinity);
    const hi = a.links.map(() => -Infinity);
    for (const f of frames) {
      relAngles(a, f).forEach((v, i) => {
        lo[i] = Math.min(lo[i], v);
        hi[i] = Math.max(hi[i], v);
      });
    }
    let offset = 0;
    a.links.forEach((l, i) => {
      const moving = l.parent >= 0 && hi[i] - lo[i] > 1e-4;
      l.joint ??= { type: moving ? 'revolute' : 'hard', dofs: moving ? 1 : 0, offset };
      offset += l.joint.dofs;
    });
    a.numDofs ??= offset;
  }
  let prev = null;
  for (const f of frames) {
    const signals = {};
    const joints = {};
    for (const a of actors) {
      const name = a.name ?? `actor${a.handle}`;
      const force = (bodies) => {
        const s = [0, 0, 0];
        for (const c of f.contacts ?? []) {
          const k = (bodies.has(c.a) ? 1 : 0) - (bodies.has(c.b) ? 1 : 0);
          for (let j = 0; j < 3; j++) s[j] += k * c.f[j];
        }
        return s.map((v) => Number(v.toPrecision(7)));
      };
      if (a.kind === 'soft') signals[`${name}.contact_force`] = force(new Set([a.handle]));
      if (a.kind !== 'articulated') continue;
      const ang = relAngles(a, f);
      const q = [];
      const qd = [];
      a.links.forEach((l, i) => {
        if (!l.joint || l.joint.dofs !== 1) return;
        const v = prev ? (ang[i] - relAngles(a, prev)[i]) / Math.max(f.t - prev.t, 1e-9) : 0;
        q.push(Number(ang[i].toPrecision(7)));
        qd.push(Number(v.toPrecision(7)));
        signals[`${name}.${l.name}.velocity`] = qd[qd.length - 1];
      });
      joints[a.handle] = { q, qd };
      const last = a.links[a.links.length - 1];
      const fe = force(new Set([last.handle]));
      signals[`${name}.${last.name}.contact_force`] = fe;
      signals[`${name}.force_sensor`] = fe;
    }
    f.joints ??= joints;
    f.signals ??= signals;
    prev = f;
  }
}

if (opts.fabricate) fabricate(parsed);
const lines = opts.fabricate ? parsed.map((o, i) => (o ? JSON.stringify(o) : rawLines[i])) : rawLines;
const frameCount = parsed.filter((o) => o?.type === 'frame').length;

// ---------- HTTP ----------
const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.css': 'text/css', '.svg': 'image/svg+xml', '.png': 'image/png', '.json': 'application/json', '.ico': 'image/x-icon', '.woff2': 'font/woff2' };
let port = opts.port;

function originOk(req) {
  const o = req.headers.origin;
  return !o || o === `http://127.0.0.1:${port}` || o === `http://localhost:${port}`;
}

const server = http.createServer((req, res) => {
  const url = new URL(req.url, 'http://x');
  const prefix = `/${opts.token}`;
  if (!originOk(req) || (url.pathname !== prefix && !url.pathname.startsWith(prefix + '/'))) {
    res.writeHead(403).end('forbidden');
    return;
  }
  if (url.pathname === prefix) {
    res.writeHead(302, { Location: prefix + '/' }).end();
    return;
  }
  const rel = decodeURIComponent(url.pathname.slice(prefix.length + 1)) || 'index.html';
  const file = path.resolve(distDir, rel);
  if (rel.split('/').includes('..') || !file.startsWith(distDir + path.sep) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
    res.writeHead(404).end('not found');
    return;
  }
  res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] ?? 'application/octet-stream', 'Cache-Control': 'no-store' });
  fs.createReadStream(file).pipe(res);
});

const wss = new WebSocketServer({ noServer: true });
server.on('upgrade', (req, socket, head) => {
  const url = new URL(req.url, 'http://x');
  if (!originOk(req) || url.pathname !== `/${opts.token}/ws`) {
    socket.end('HTTP/1.1 403 Forbidden\r\n\r\n');
    return;
  }
  wss.handleUpgrade(req, socket, head, (ws) => (opts.live ? serveLive(ws) : serveReplay(ws)));
});

const send = (ws, text) => new Promise((resolve) => ws.send(text, () => resolve()));

// ---------- replay ----------
async function serveReplay(ws) {
  const session = { type: 'session', mode: 'replay', version: 1, axes: opts.axes, source: path.basename(opts.file) };
  await send(ws, JSON.stringify(session));
  // Batches of many lines, bounded in bytes.
  let batch = [];
  let bytes = 0;
  for (const l of lines) {
    batch.push(l);
    bytes += l.length;
    if (batch.length >= 200 || bytes > 1 << 20) {
      if (ws.readyState !== ws.OPEN) return;
      await send(ws, batch.join('\n'));
      batch = [];
      bytes = 0;
    }
  }
  if (batch.length) await send(ws, batch.join('\n'));
  await send(ws, JSON.stringify({ type: 'end', frames: frameCount }));
}

// ---------- live ----------
function serveLive(ws) {
  const objs = lines.map((l) => {
    try {
      return JSON.parse(l);
    } catch {
      return null;
    }
  });
  const frameIdx = objs.map((o, i) => (o?.type === 'frame' ? i : -1)).filter((i) => i >= 0);
  if (!frameIdx.length) {
    ws.close();
    return;
  }
  const t0 = objs[frameIdx[0]].t;
  const period = objs[frameIdx.at(-1)].t - t0 + (frameIdx.length > 1 ? objs[frameIdx[1]].t - t0 : 0.02);
  const st = { state: 'playing', speed: 'realtime', k: -1, sent: -1, lastStatus: 0, clock: null };
  let lineCursor = 0; // next file line to send

  const frameAt = (k) => {
    const n = frameIdx.length;
    const loop = Math.floor(k / n);
    const f = { ...objs[frameIdx[k % n]] };
    f.t = Number((f.t + loop * period).toPrecision(10));
    f.step = k + 1;
    return f;
  };
  /** The description lines between the last sent frame and frame k, then frame k, as one message. */
  const message = (k) => {
    const n = frameIdx.length;
    const i = frameIdx[k % n];
    // A new connection, a restore or a new loop over the file describes the actors again.
    if (st.sent < 0 || Math.floor(k / n) !== Math.floor(st.sent / n)) lineCursor = 0;
    const out = [];
    for (; lineCursor < i; lineCursor++) {
      const o = objs[lineCursor];
      if (o?.type === 'frame' || (o?.type === 'header' && st.sent >= 0)) continue;
      out.push(lines[lineCursor]);
    }
    lineCursor = i + 1;
    out.push(JSON.stringify(frameAt(k)));
    return out.join('\n');
  };
  const status = () => JSON.stringify({ type: 'status', state: st.state, speed: st.speed, t: st.k >= 0 ? frameAt(st.k).t : 0, step: st.k + 1, sentAt: Date.now() });
  const sendStatus = () => {
    st.lastStatus = Date.now();
    if (ws.readyState === ws.OPEN) ws.send(status());
  };
  const advanceTo = (k) => {
    // Skip frames while the page has not taken the previous ones.
    if (ws.readyState !== ws.OPEN || ws.bufferedAmount > 256 << 10) return;
    st.k = k;
    ws.send(message(k));
    st.sent = k;
  };

  ws.send(JSON.stringify({ type: 'session', mode: 'live', version: 1, axes: opts.axes, source: '' }));
  advanceTo(0);
  sendStatus();
  st.clock = { wall: Date.now(), k: 0 };

  const timer = setInterval(() => {
    if (ws.readyState !== ws.OPEN) return;
    if (st.state === 'playing') {
      let target;
      if (st.speed === 'fast') target = st.k + 4;
      else {
        // Real time: the newest frame whose t is not ahead of the wall clock since play.
        const elapsed = (Date.now() - st.clock.wall) / 1000;
        const tNow = frameAt(st.clock.k).t + elapsed;
        target = st.k;
        while (frameAt(target + 1).t <= tNow) target++;
      }
      if (target > st.k) advanceTo(target);
    }
    if (Date.now() - st.lastStatus >= 1000 || st.state === 'playing') sendStatus();
  }, 1000 / 60);

  ws.on('message', (data) => {
    if (process.env.MOCK_DEBUG) console.error('control', String(data));
    let m;
    try {
      m = JSON.parse(String(data));
    } catch {
      return;
    }
    if (m?.type !== 'control') return;
    switch (m.action) {
      case 'pause':
        st.state = 'paused';
        break;
      case 'play':
      case 'fast':
        st.state = 'playing';
        st.speed = m.action === 'fast' ? 'fast' : 'realtime';
        st.clock = { wall: Date.now(), k: st.k };
        break;
      case 'step':
        if (st.state === 'paused') advanceTo(st.k + 1);
        break;
      case 'restore':
        st.state = 'paused';
        st.sent = -1;
        advanceTo(0);
        break;
      default:
        return;
    }
    sendStatus();
  });
  ws.on('close', () => clearInterval(timer));
}

server.listen(opts.port, '127.0.0.1', () => {
  port = server.address().port;
  console.log(`http://127.0.0.1:${port}/${opts.token}/`);
  console.error(`mock debug server: ${opts.live ? 'live' : 'replay'} of ${opts.file} (${frameCount} frames)`);
});
