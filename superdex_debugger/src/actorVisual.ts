import * as THREE from 'three';
import { GROUND_COLOR } from './colors';
import { applyPose, isPose } from './pose';
import type { ActorMsg, FrameMsg } from './protocol';
import { shapeGeometry } from './shapes';

const WHITE = new THREE.Color('#ffffff');

/** What a click on a mesh selects. */
export interface PickInfo {
  actor: number;
  link?: number;
}

/**
 * The three.js objects of one actor: a group per link placed at world_from_link, holding the
 * link's colliders at link_from_shape and an axes helper; or, for a soft body, one mesh whose
 * vertices are the soft nodes (world frame, m).
 */
export class ActorVisual {
  readonly root = new THREE.Group();
  readonly color: THREE.Color;
  private readonly linkGroups = new Map<number, THREE.Group>();
  /** One material per link handle (soft bodies: keyed by the actor handle). */
  private readonly materials = new Map<number, THREE.MeshPhongMaterial>();
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
    this.materials.set(key, m);
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
        group.add(mesh);
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
    const glow = this.color.clone().lerp(WHITE, 0.45);
    for (const [key, m] of this.materials) {
      const k = !actorSelected ? 0 : link === undefined ? 0.2 : key === link ? 0.38 : 0;
      m.emissive.copy(glow).multiplyScalar(k);
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
    this.root.removeFromParent();
    for (const d of this.disposables) d.dispose();
  }
}
