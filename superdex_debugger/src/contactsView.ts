import * as THREE from 'three';
import type { Contact } from './protocol';

const UP = new THREE.Vector3(0, 1, 0);

/**
 * Contact points (small spheres at `p`) and force arrows (from `p` along `f`, the force on body
 * a), drawn with instanced meshes. Arrow length = |f| * scale (m per N), clamped to maxLength.
 */
export class ContactsView {
  readonly root = new THREE.Group();
  /** Arrow length per newton, m/N. */
  scale = 0.02;
  /** Longest arrow drawn, m. */
  maxLength = 0.5;
  /** Radius of a contact point, m. */
  pointRadius = 0.004;
  private capacity = 0;
  private points!: THREE.InstancedMesh;
  private shafts!: THREE.InstancedMesh;
  private heads!: THREE.InstancedMesh;
  private readonly pointGeo = new THREE.SphereGeometry(1, 10, 8);
  // Unit cylinder and cone along +y, with their base at the origin.
  private readonly shaftGeo = new THREE.CylinderGeometry(1, 1, 1, 8).translate(0, 0.5, 0);
  private readonly headGeo = new THREE.ConeGeometry(1, 1, 12).translate(0, 0.5, 0);
  private readonly pointMat = new THREE.MeshBasicMaterial({ color: '#ffd166' });
  private readonly arrowMat = new THREE.MeshPhongMaterial({ color: '#ff5d73', emissive: '#5a1420', shininess: 60 });

  constructor() {
    this.root.name = 'contacts';
    this.grow(256);
  }

  private grow(n: number): void {
    for (const m of [this.points, this.shafts, this.heads]) if (m) { m.removeFromParent(); m.dispose(); }
    this.capacity = n;
    this.points = new THREE.InstancedMesh(this.pointGeo, this.pointMat, n);
    this.shafts = new THREE.InstancedMesh(this.shaftGeo, this.arrowMat, n);
    this.heads = new THREE.InstancedMesh(this.headGeo, this.arrowMat, n);
    for (const m of [this.points, this.shafts, this.heads]) {
      m.count = 0;
      m.frustumCulled = false;
      this.root.add(m);
    }
  }

  /** Shows these contacts (or none). */
  update(contacts: Contact[] | undefined): void {
    const list = Array.isArray(contacts) ? contacts : [];
    if (list.length > this.capacity) this.grow(Math.max(list.length, this.capacity * 2));
    const m = new THREE.Matrix4();
    const q = new THREE.Quaternion();
    const p = new THREE.Vector3();
    const dir = new THREE.Vector3();
    const s = new THREE.Vector3();
    let np = 0;
    let na = 0;
    const r = this.pointRadius;
    for (const c of list) {
      if (!Array.isArray(c?.p)) continue;
      p.set(c.p[0], c.p[1], c.p[2]);
      m.compose(p, q.identity(), s.setScalar(r));
      this.points.setMatrixAt(np++, m);
      if (!Array.isArray(c.f)) continue;
      dir.set(c.f[0], c.f[1], c.f[2]);
      const mag = dir.length();
      const len = Math.min(mag * this.scale, this.maxLength);
      if (len < r) continue;
      dir.divideScalar(mag);
      q.setFromUnitVectors(UP, dir);
      const head = Math.min(len * 0.35, r * 5);
      m.compose(p, q, s.set(r * 0.4, len - head, r * 0.4));
      this.shafts.setMatrixAt(na, m);
      m.compose(p.clone().addScaledVector(dir, len - head), q, s.set(r * 1.3, head, r * 1.3));
      this.heads.setMatrixAt(na, m);
      na++;
    }
    this.points.count = np;
    this.shafts.count = na;
    this.heads.count = na;
    for (const im of [this.points, this.shafts, this.heads]) im.instanceMatrix.needsUpdate = true;
  }
}
