import * as THREE from 'three';
import { GROUND_COLOR } from './colors';
import { applyPose, isPose } from './pose';
import type { ActorMsg, FrameMsg } from './protocol';
import { instantiateRenderModel, renderModelSpec } from './renderModels';
import { shapeGeometry } from './shapes';

const WHITE = new THREE.Color('#ffffff');

/** Opacity of the colliders drawn over a render model. */
const GHOST_OPACITY = 0.25;

/** A material that the selection lights up, with what it looked like unselected. */
interface Glowable {
  /** Link handle (soft bodies: the actor handle). */
  key: number;
  material: THREE.Material;
  /** Materials with an emissive colour (Phong, standard, ...). */
  emissive?: THREE.Color;
  emissiveMap?: THREE.Texture | null;
  /** Unlit materials: their colour is lightened instead. */
  color?: THREE.Color;
  /** Scales the glow (render models keep more of their own colours). */
  strength: number;
}

/** Glow of render-model materials relative to the colliders'. */
const MODEL_GLOW = 0.35;

/** Strength of the environment map given to render models' physically based materials. */
const MODEL_ENV_INTENSITY = 0.5;

/** A link's collider meshes, and its render model once loaded. */
interface LinkParts {
  colliders: THREE.Mesh[];
  /** Material of the (non-plane) colliders drawn over the loaded model. */
  ghost?: THREE.MeshPhongMaterial;
  model?: THREE.Object3D;
}

/** What a click on a mesh selects. */
export interface PickInfo {
  actor: number;
  link?: number;
}

/**
 * The three.js objects of one actor: a group per link placed at world_from_link, holding the
 * link's colliders at link_from_shape and an axes helper; or, for a soft body, one mesh whose
 * vertices are the soft nodes (world frame, m).
 *
 * A link with a `renderModel` shows the glTF model (in the link frame, scaled) instead of its
 * colliders once the model has loaded; until then, or if it cannot be loaded, the colliders.
 * With `setCollidersOverModels(true)` the colliders are also drawn, semi-transparent, over it.
 */
export class ActorVisual {
  readonly root = new THREE.Group();
  readonly color: THREE.Color;
  /** Called when something changed asynchronously (a render model was added). */
  onChange: () => void = () => {};
  /** Environment map for render models' physically based materials that have none. */
  modelEnvironment: (() => THREE.Texture | null) | null = null;
  private readonly linkGroups = new Map<number, THREE.Group>();
  private readonly parts = new Map<number, LinkParts>();
  /** Materials lit up by the selection. */
  private readonly glow: Glowable[] = [];
  private highlight: { actorSelected: boolean; link?: number } = { actorSelected: false };
  private collidersOverModels = false;
  private disposed = false;
  private readonly axes: THREE.AxesHelper[] = [];
  private readonly disposables: { dispose(): void }[] = [];
  private soft?: { geometry: THREE.BufferGeometry; nodes: number };
  /** Meshes that count for the camera fit (planes excluded). */
  private readonly solid: THREE.Object3D[] = [];

  constructor(readonly desc: ActorMsg, color: string) {
    this.color = new THREE.Color(color);
    this.root.name = desc.name ?? `actor ${desc.handle}`;
    if (desc.kind === 'soft') this.buildSoft();
    else this.buildLinks();
  }

  // Phong and Lambert shading: close to physically based for this use, and several times cheaper
  // per pixel on software WebGL.
  private material(key: number, color: THREE.Color | string, opts: THREE.MeshPhongMaterialParameters = {}) {
    // Double-sided: mesh colliders do not always have a consistent winding.
    const m = new THREE.MeshPhongMaterial({ color, shininess: 40, specular: '#2a2a2a', side: THREE.DoubleSide, ...opts });
    this.glow.push({ key, material: m, emissive: m.emissive.clone(), strength: 1 });
    this.disposables.push(m);
    return m;
  }

  private buildLinks(): void {
    for (const link of this.desc.links ?? []) {
      const group = new THREE.Group();
      group.name = link.name ?? `link ${link.handle}`;
      this.linkGroups.set(link.handle, group);
      this.root.add(group);
      const mat = this.material(link.handle, this.color);
      const parts: LinkParts = { colliders: [] };
      this.parts.set(link.handle, parts);
      let groundMat: THREE.MeshLambertMaterial | undefined;
      for (const col of link.colliders ?? []) {
        const sg = shapeGeometry(col.shape);
        if (!sg) continue;
        this.disposables.push(sg.geometry);
        if (sg.isPlane) {
          groundMat ??= new THREE.MeshLambertMaterial({
            color: new THREE.Color(GROUND_COLOR).lerp(this.color, 0.08),
            side: THREE.DoubleSide,
            // Keep the ground behind the grid lines drawn at the same height.
            polygonOffset: true,
            polygonOffsetFactor: 1,
            polygonOffsetUnits: 1,
          });
          this.disposables.push(groundMat);
        }
        const mesh = new THREE.Mesh(sg.geometry, sg.isPlane ? groundMat : mat);
        if (isPose(col.linkFromShape)) applyPose(mesh, col.linkFromShape);
        mesh.castShadow = !sg.isPlane;
        mesh.receiveShadow = true;
        mesh.userData.pick = { actor: this.desc.handle, link: link.handle } satisfies PickInfo;
        mesh.userData.isPlane = sg.isPlane;
        if (!sg.isPlane) this.solid.push(mesh);
        parts.colliders.push(mesh);
        group.add(mesh);
      }
      const spec = renderModelSpec(link.renderModel);
      if (spec) {
        instantiateRenderModel(spec).then(
          (model) => model && this.addModel(link.handle, model),
          // Not expected (failures resolve to null); never let it reach the console as an error.
          (e) => console.warn('superdex: render model', e),
        );
      }
      const ax = new THREE.AxesHelper(1);
      ax.scale.setScalar(0.05);
      ax.visible = false;
      // Axes stay readable through the geometry they belong to.
      (ax.material as THREE.LineBasicMaterial).depthTest = false;
      ax.renderOrder = 10;
      this.axes.push(ax);
      this.disposables.push(ax.geometry, ax.material as THREE.Material);
      group.add(ax);
    }
  }

  /** Shows a loaded render model in its link group, in place of the colliders. */
  private addModel(handle: number, model: THREE.Object3D): void {
    const group = this.linkGroups.get(handle);
    const parts = this.parts.get(handle);
    if (this.disposed || !group || !parts) {
      disposeInstance(model);
      return;
    }
    const pick = { actor: this.desc.handle, link: handle } satisfies PickInfo;
    model.traverse((o) => {
      const mesh = o as THREE.Mesh;
      if (!mesh.isMesh) return;
      mesh.userData.pick = pick;
      for (const m of Array.isArray(mesh.material) ? mesh.material : [mesh.material]) {
        const std = m as THREE.MeshStandardMaterial;
        if (std.isMeshStandardMaterial && !std.envMap) {
          const env = this.modelEnvironment?.() ?? null;
          if (env) {
            std.envMap = env;
            std.envMapIntensity *= MODEL_ENV_INTENSITY;
          }
        }
        const em = (m as THREE.MeshStandardMaterial).emissive;
        const col = (m as THREE.MeshBasicMaterial).color;
        if (em?.isColor) this.glow.push({ key: handle, material: m, emissive: em.clone(), emissiveMap: (m as THREE.MeshStandardMaterial).emissiveMap, strength: MODEL_GLOW });
        else if (col?.isColor) this.glow.push({ key: handle, material: m, color: col.clone(), strength: MODEL_GLOW });
      }
    });
    parts.model = model;
    // The colliders, when drawn over the model: see-through, drawn after it and in front of it
    // (a collider is often inside its model), no shadows.
    // Planes keep the depth test: drawn in front of everything they would cover the view.
    const ghost = (depthTest: boolean) => {
      const m = new THREE.MeshPhongMaterial({
        color: this.color,
        transparent: true,
        opacity: GHOST_OPACITY,
        depthWrite: false,
        depthTest,
        shininess: 20,
        side: THREE.DoubleSide,
      });
      this.glow.push({ key: handle, material: m, emissive: m.emissive.clone(), strength: 1 });
      this.disposables.push(m);
      return m;
    };
    let planeGhost: THREE.MeshPhongMaterial | undefined;
    for (const c of parts.colliders) {
      if (c.userData.isPlane) c.material = planeGhost ??= ghost(true);
      else c.material = parts.ghost ??= ghost(false);
      c.castShadow = false;
      c.receiveShadow = false;
      c.renderOrder = 5;
    }
    this.solid.push(model);
    group.add(model);
    this.updateColliderVisibility();
    this.applyHighlight();
    this.onChange();
  }

  /** Colliders of links with a loaded render model are drawn only when asked for. */
  private updateColliderVisibility(): void {
    for (const p of this.parts.values()) {
      if (!p.model) continue;
      for (const c of p.colliders) c.visible = this.collidersOverModels;
    }
  }

  /** Also draws the colliders of links that show a render model (semi-transparent, over it). */
  setCollidersOverModels(v: boolean): void {
    this.collidersOverModels = v;
    this.updateColliderVisibility();
  }

  /** Links whose render model has loaded and is shown. */
  renderModelCount(): number {
    let n = 0;
    for (const p of this.parts.values()) if (p.model) n++;
    return n;
  }

  /** True if some link of the actor declares a render model (loaded or not). */
  get hasRenderModels(): boolean {
    return (this.desc.links ?? []).some((l) => renderModelSpec(l.renderModel) !== null);
  }

  private buildSoft(): void {
    const nodes = this.desc.nodes ?? [];
    const tris = this.desc.surfaceTriangles ?? [];
    const g = new THREE.BufferGeometry();
    const pos = new Float32Array(nodes.length * 3);
    nodes.forEach((p, i) => pos.set([p[0], p[1], p[2]], 3 * i));
    g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    g.setIndex(tris.flat());
    g.computeVertexNormals();
    this.soft = { geometry: g, nodes: nodes.length };
    this.disposables.push(g);
    const mat = this.material(this.desc.handle, this.color, { shininess: 15, side: THREE.DoubleSide });
    const mesh = new THREE.Mesh(g, mat);
    mesh.castShadow = true;
    mesh.receiveShadow = true;
    mesh.frustumCulled = false;
    mesh.userData.pick = { actor: this.desc.handle } satisfies PickInfo;
    this.solid.push(mesh);
    this.root.add(mesh);
  }

  /** Moves links to the frame's world_from_link poses and soft nodes to its positions. Missing entries keep the last shown state. */
  applyFrame(frame: FrameMsg | undefined): void {
    if (!frame) return;
    if (this.soft) {
      const flatPos = frame.soft?.[String(this.desc.handle)];
      if (Array.isArray(flatPos) && flatPos.length === this.soft.nodes * 3) {
        const attr = this.soft.geometry.getAttribute('position') as THREE.BufferAttribute;
        (attr.array as Float32Array).set(flatPos);
        attr.needsUpdate = true;
        this.soft.geometry.computeVertexNormals();
        this.soft.geometry.computeBoundingSphere();
        this.soft.geometry.computeBoundingBox();
      }
      return;
    }
    const links = frame.links;
    if (!links) return;
    for (const [handle, group] of this.linkGroups) {
      const p = links[String(handle)];
      if (isPose(p)) applyPose(group, p);
    }
  }

  /** Highlights the whole actor when selected, and one of its links more strongly (a light glow). */
  setHighlight(actorSelected: boolean, link?: number): void {
    this.highlight = { actorSelected, link };
    this.applyHighlight();
  }

  private applyHighlight(): void {
    const { actorSelected, link } = this.highlight;
    const glow = this.color.clone().lerp(WHITE, 0.45);
    for (const g of this.glow) {
      const k = (!actorSelected ? 0 : link === undefined ? 0.2 : g.key === link ? 0.38 : 0) * g.strength;
      const m = g.material as THREE.MeshStandardMaterial;
      if (g.emissive) {
        m.emissive.copy(glow).multiplyScalar(k).add(g.emissive);
        // The emissive colour multiplies an emissive texture: drop it while lit up.
        if (g.emissiveMap) {
          const map = k > 0 ? null : g.emissiveMap;
          if (m.emissiveMap !== map) {
            m.emissiveMap = map;
            m.needsUpdate = true;
          }
        }
      } else if (g.color) {
        m.color.copy(g.color).lerp(WHITE, k);
      }
    }
  }

  setFramesVisible(v: boolean): void {
    for (const a of this.axes) a.visible = v;
  }

  /** Length of each axis of the link frames, m. */
  setFrameSize(size: number): void {
    for (const a of this.axes) a.scale.setScalar(size);
  }

  /** World pose of a link group as currently shown. */
  linkObject(link: number): THREE.Object3D | undefined {
    return this.linkGroups.get(link);
  }

  /** Grows `box` by the world bounds of everything but planes. */
  expandBox(box: THREE.Box3): void {
    this.root.updateMatrixWorld(true);
    for (const o of this.solid) box.expandByObject(o);
  }

  dispose(): void {
    this.disposed = true;
    this.root.removeFromParent();
    for (const d of this.disposables) d.dispose();
    for (const p of this.parts.values()) if (p.model) disposeInstance(p.model);
  }
}

/** Disposes the per-instance materials of a render model (geometries and textures are shared with the cached template). */
function disposeInstance(model: THREE.Object3D): void {
  model.traverse((o) => {
    const mesh = o as THREE.Mesh;
    if (!mesh.isMesh) return;
    for (const m of Array.isArray(mesh.material) ? mesh.material : [mesh.material]) m.dispose();
  });
}
