import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { clone as cloneSkinned } from 'three/examples/jsm/utils/SkeletonUtils.js';
import type { RenderModel, Vec3 } from './protocol';

/**
 * glTF render models of links (`links[i].renderModel` of an `actor` message): the whole .glb
 * file as base64. Each distinct file is decoded and parsed once (cached by its base64 text);
 * every link that shows it gets its own clone. The cache lives as long as the page: the
 * templates' geometries and textures are shared by the clones and never disposed.
 */

/** A render model checked for use: the base64 .glb, the scale (applied in the link frame) and its name. */
export interface RenderModelSpec {
  name: string;
  scale: Vec3;
  glb: string;
}

/** The usable part of a link's `renderModel` field, or null when it has none (or no .glb text). */
export function renderModelSpec(rm: RenderModel | undefined | null): RenderModelSpec | null {
  if (!rm || typeof rm !== 'object' || typeof rm.glb !== 'string' || rm.glb.length === 0) return null;
  const s = rm.scale;
  const scale: Vec3 = Array.isArray(s) && s.length === 3 && s.every((v) => typeof v === 'number' && Number.isFinite(v)) ? [s[0], s[1], s[2]] : [1, 1, 1];
  return { name: typeof rm.name === 'string' ? rm.name : '', scale, glb: rm.glb };
}

/** Decodes standard (or URL-safe) base64, whitespace allowed. Throws on invalid input. */
export function base64ToArrayBuffer(b64: string): ArrayBuffer {
  const clean = b64.replace(/\s+/g, '').replace(/-/g, '+').replace(/_/g, '/');
  const bin = atob(clean);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes.buffer;
}

/** A 1x1 white PNG: stands in for image files outside the .glb, which the page cannot fetch. */
const WHITE_PNG = 'data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4//8/AAX+Av4N70a4AAAAAElFTkSuQmCC';

/** Parsed templates by base64 text; null when the file could not be used (warned once). */
const cache = new Map<string, Promise<THREE.Object3D | null>>();

/** Parses run one at a time, so that the loader's console messages can be told apart. */
let parseQueue: Promise<unknown> = Promise.resolve();

/**
 * Runs `fn` with the console messages of three.js loaders ("THREE.GLTFLoader: Couldn't load
 * texture" is a console.error) collected into `into` instead of logged: the page reports a
 * model's problems as one console.warn. Other messages (the renderer's, the page's) pass through.
 */
async function collectingThreeMessages<T>(into: string[], fn: () => Promise<T>): Promise<T> {
  const { error, warn } = console;
  const capture =
    (orig: (...a: unknown[]) => void) =>
    (...args: unknown[]) => {
      if (typeof args[0] === 'string' && /^THREE\.\w*Loader\b/.test(args[0])) into.push(args.map((a) => (a instanceof Error ? a.message : String(a))).join(' '));
      else orig.apply(console, args);
    };
  console.error = capture(error);
  console.warn = capture(warn);
  try {
    return await fn();
  } finally {
    console.error = error;
    console.warn = warn;
  }
}

async function parse(glb: string, name: string): Promise<THREE.Object3D | null> {
  const label = name ? `"${name}"` : '(unnamed)';
  const notes: string[] = [];
  try {
    const data = base64ToArrayBuffer(glb);
    // Everything must be inside the .glb: the debug server serves no other file. Textures whose
    // image is another file are left out; any other URL (an external buffer, an image of a
    // texture extension) gets a stand-in, so that the parse fails or the texture is plain white.
    const external = (url: string) => !/^(data|blob):/i.test(url);
    const manager = new THREE.LoadingManager();
    manager.setURLModifier((url) => {
      if (!external(url)) return url;
      notes.push(`refers to ${url}, which is not in the .glb`);
      return /\.(png|jpe?g|webp|ktx2|avif)$/i.test(url) ? WHITE_PNG : 'data:application/octet-stream;base64,';
    });
    const loader = new GLTFLoader(manager);
    loader.register((parser) => ({
      name: 'superdex_external_images',
      loadTexture(index: number) {
        const image = parser.json.images?.[parser.json.textures?.[index]?.source];
        if (typeof image?.uri !== 'string' || !external(image.uri)) return null;
        notes.push(`texture ${index} left out: its image ${image.uri} is not in the .glb`);
        // GLTFLoader's assignTexture skips a null texture (the typings do not allow for it).
        return Promise.resolve(null) as unknown as Promise<THREE.Texture>;
      },
    }));
    const gltf = await collectingThreeMessages(notes, () => loader.parseAsync(data, ''));
    const root = gltf.scene ?? gltf.scenes?.[0];
    if (!root) throw new Error('no scene in the file');
    let drawable = false;
    root.traverse((o) => {
      const m = o as THREE.Mesh;
      if (m.isMesh) {
        m.castShadow = true;
        m.receiveShadow = true;
      }
      if (m.isMesh || (o as THREE.Line).isLine || (o as THREE.Points).isPoints) drawable = true;
    });
    if (!drawable) throw new Error('nothing to draw in the file');
    if (notes.length) console.warn(`superdex: render model ${label} loaded with problems: ${notes.join('; ')}`);
    return root;
  } catch (e) {
    const why = [(e as Error)?.message ?? String(e), ...notes].join('; ');
    console.warn(`superdex: render model ${label} could not be loaded, drawing the colliders instead: ${why}`);
    return null;
  }
}

/**
 * A new instance of the model in the .glb (base64), or null when it cannot be decoded or parsed
 * (one console.warn per distinct file). Meshes cast and receive shadows; materials are the
 * model's own, cloned per instance so that an instance can be highlighted alone.
 */
export async function instantiateRenderModel(spec: RenderModelSpec): Promise<THREE.Object3D | null> {
  let p = cache.get(spec.glb);
  if (!p) {
    p = parseQueue.then(() => parse(spec.glb, spec.name));
    parseQueue = p;
    cache.set(spec.glb, p);
  }
  const template = await p;
  if (!template) return null;
  // SkeletonUtils.clone also rebinds skinned meshes to the cloned bones.
  const inst = cloneSkinned(template);
  inst.traverse((o) => {
    const m = o as THREE.Mesh;
    if (!m.isMesh) return;
    m.material = Array.isArray(m.material) ? m.material.map((x) => x.clone()) : m.material.clone();
  });
  inst.name = spec.name || 'render model';
  inst.scale.set(spec.scale[0], spec.scale[1], spec.scale[2]);
  return inst;
}
