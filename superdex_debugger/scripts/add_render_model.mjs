#!/usr/bin/env node
// Development tool: copies a recording and gives one link a glTF render model, to try the page's
// render-model drawing without the engine.
//
//   node scripts/add_render_model.mjs IN.jsonl OUT.jsonl [--actor NAME] [--link NAME[,NAME...]]
//        [--glb FILE | --shape box|sphere] [--size M] [--color R,G,B] [--metallic X]
//        [--texture] [--scale SX,SY,SZ] [--name NAME] [--write-glb FILE] [--corrupt]
//
// Without --glb it builds a small .glb (one mesh with POSITION/NORMAL[/TEXCOORD_0] and indices,
// a material with baseColorFactor; --texture adds an embedded PNG checkerboard): a box of half
// size --size (default 0.02 m) or a sphere of that radius. --corrupt sends bytes that are not a
// .glb (the page must fall back to the colliders). Defaults: actor example_bot_2dof, link ball.
// Every listed link gets the same file (the page parses it once).
import fs from 'node:fs';
import zlib from 'node:zlib';

const argv = process.argv.slice(2);
const pos = [];
const opt = {};
for (let i = 0; i < argv.length; i++) {
  const a = argv[i];
  if (a === '--texture' || a === '--corrupt') opt[a.slice(2)] = true;
  else if (a.startsWith('--')) opt[a.slice(2)] = argv[++i];
  else pos.push(a);
}
const [input, output] = pos;
if (!input || !output) {
  console.error('usage: add_render_model.mjs IN.jsonl OUT.jsonl [--actor NAME] [--link NAME] [--glb FILE | --shape box|sphere] [--size M] [--color R,G,B] [--texture] [--scale SX,SY,SZ] [--corrupt]');
  process.exit(2);
}
const actorName = opt.actor ?? 'example_bot_2dof';
const linkNames = (opt.link ?? 'ball').split(',');
const linkName = linkNames[0];
const size = Number(opt.size ?? 0.02);
const color = (opt.color ?? '1,0.25,0.1').split(',').map(Number);
const scale = (opt.scale ?? '1,1,1').split(',').map(Number);

// ---------- a minimal PNG (8-bit RGB) ----------
function crc32(buf) {
  let c = ~0;
  for (const b of buf) {
    c ^= b;
    for (let k = 0; k < 8; k++) c = (c >>> 1) ^ (0xedb88320 & -(c & 1));
  }
  return ~c >>> 0;
}
function png(w, h, pixel) {
  const raw = Buffer.alloc((3 * w + 1) * h);
  for (let y = 0; y < h; y++) {
    raw[y * (3 * w + 1)] = 0;
    for (let x = 0; x < w; x++) raw.set(pixel(x, y), y * (3 * w + 1) + 1 + 3 * x);
  }
  const chunk = (type, data) => {
    const len = Buffer.alloc(4);
    len.writeUInt32BE(data.length);
    const td = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(crc32(td));
    return Buffer.concat([len, td, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(w, 0);
  ihdr.writeUInt32BE(h, 4);
  ihdr.set([8, 2, 0, 0, 0], 8);
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr), chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

// ---------- geometry ----------
function box(s) {
  const pos = [];
  const nrm = [];
  const uv = [];
  const idx = [];
  // For each axis and sign, a quad of 4 vertices facing outwards.
  for (let axis = 0; axis < 3; axis++) {
    for (const sign of [1, -1]) {
      const u = (axis + 1) % 3;
      const v = (axis + 2) % 3;
      const base = pos.length / 3;
      for (const [a, b] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        const p = [0, 0, 0];
        p[axis] = sign * s;
        p[u] = a * s * sign;
        p[v] = b * s;
        const n = [0, 0, 0];
        n[axis] = sign;
        pos.push(...p);
        nrm.push(...n);
        uv.push((a + 1) / 2, (b + 1) / 2);
      }
      idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
  }
  return { pos, nrm, uv, idx };
}
function sphere(r, seg = 24, rings = 16) {
  const pos = [];
  const nrm = [];
  const uv = [];
  const idx = [];
  for (let i = 0; i <= rings; i++) {
    const th = (Math.PI * i) / rings;
    for (let j = 0; j <= seg; j++) {
      const ph = (2 * Math.PI * j) / seg;
      const n = [Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)];
      nrm.push(...n);
      pos.push(...n.map((x) => x * r));
      uv.push(j / seg, i / rings);
    }
  }
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < seg; j++) {
      const a = i * (seg + 1) + j;
      const b = a + seg + 1;
      idx.push(a, b, a + 1, a + 1, b, b + 1);
    }
  }
  return { pos, nrm, uv, idx };
}

// ---------- .glb ----------
function makeGlb() {
  const g = opt.shape === 'sphere' ? sphere(size) : box(size);
  const parts = [];
  let offset = 0;
  const views = [];
  const add = (buf, target) => {
    const pad = (4 - (offset % 4)) % 4;
    if (pad) {
      parts.push(Buffer.alloc(pad));
      offset += pad;
    }
    views.push({ buffer: 0, byteOffset: offset, byteLength: buf.length, ...(target ? { target } : {}) });
    parts.push(buf);
    offset += buf.length;
    return views.length - 1;
  };
  const f32 = (a) => Buffer.from(new Float32Array(a).buffer);
  const min = [0, 1, 2].map((k) => Math.min(...g.pos.filter((_, i) => i % 3 === k)));
  const max = [0, 1, 2].map((k) => Math.max(...g.pos.filter((_, i) => i % 3 === k)));
  const n = g.pos.length / 3;
  const accessors = [
    { bufferView: add(f32(g.pos), 34962), componentType: 5126, count: n, type: 'VEC3', min, max },
    { bufferView: add(f32(g.nrm), 34962), componentType: 5126, count: n, type: 'VEC3' },
    { bufferView: add(Buffer.from(new Uint16Array(g.idx).buffer), 34963), componentType: 5123, count: g.idx.length, type: 'SCALAR' },
  ];
  const attributes = { POSITION: 0, NORMAL: 1 };
  const pbr = { baseColorFactor: [...color, 1], metallicFactor: Number(opt.metallic ?? 0), roughnessFactor: 0.55 };
  const json = { asset: { version: '2.0', generator: 'superdex_debugger/scripts/add_render_model.mjs' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0, name: 'model' }] };
  if (opt.texture) {
    accessors.push({ bufferView: add(f32(g.uv), 34962), componentType: 5126, count: n, type: 'VEC2' });
    attributes.TEXCOORD_0 = 3;
    const img = png(16, 16, (x, y) => (((x >> 2) + (y >> 2)) % 2 ? [255, 255, 255] : [40, 60, 200]));
    json.images = [{ bufferView: add(img), mimeType: 'image/png' }];
    json.samplers = [{ magFilter: 9728, minFilter: 9728 }];
    json.textures = [{ source: 0, sampler: 0 }];
    pbr.baseColorTexture = { index: 0 };
  }
  json.meshes = [{ name: 'model', primitives: [{ attributes, indices: 2, material: 0 }] }];
  json.materials = [{ name: 'model', pbrMetallicRoughness: pbr }];
  json.accessors = accessors;
  json.bufferViews = views;
  let bin = Buffer.concat(parts);
  bin = Buffer.concat([bin, Buffer.alloc((4 - (bin.length % 4)) % 4)]);
  json.buffers = [{ byteLength: bin.length }];
  let js = Buffer.from(JSON.stringify(json), 'utf8');
  js = Buffer.concat([js, Buffer.alloc((4 - (js.length % 4)) % 4, 0x20)]);
  const header = Buffer.alloc(12);
  header.writeUInt32LE(0x46546c67, 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + js.length + 8 + bin.length, 8);
  const ch = (len, type) => {
    const b = Buffer.alloc(8);
    b.writeUInt32LE(len, 0);
    b.writeUInt32LE(type, 4);
    return b;
  };
  return Buffer.concat([header, ch(js.length, 0x4e4f534a), js, ch(bin.length, 0x004e4942), bin]);
}

const glb = opt.glb ? fs.readFileSync(opt.glb) : opt.corrupt ? Buffer.from('this is not a glb file, just some bytes') : makeGlb();
if (opt['write-glb']) fs.writeFileSync(opt['write-glb'], glb);
const renderModel = { name: opt.name ?? (opt.glb ? opt.glb.split('/').at(-1) : `${linkName}.glb`), scale, glb: glb.toString('base64') };

let found = 0;
const out = fs
  .readFileSync(input, 'utf8')
  .split('\n')
  .map((line) => {
    if (!line.includes('"actor"')) return line;
    let o;
    try {
      o = JSON.parse(line);
    } catch {
      return line;
    }
    if (o?.type !== 'actor' || o.name !== actorName || !Array.isArray(o.links)) return line;
    const ls = o.links.filter((x) => linkNames.includes(x.name));
    if (!ls.length) return line;
    for (const l of ls) l.renderModel = renderModel;
    found += ls.length;
    return JSON.stringify(o);
  });
fs.writeFileSync(output, out.join('\n'));
console.error(`render model ${renderModel.name} (${glb.length} bytes) on ${found} link(s) named ${linkNames.join(', ')} of ${actorName}`);
if (!found) process.exit(1);
