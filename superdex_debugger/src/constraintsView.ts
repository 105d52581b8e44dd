import * as THREE from 'three';
import type { ConstraintMarker } from './protocol';

/**
 * Constraints: a segment from each constraint's point on its first actor to its target or its
 * point on the second actor (teal), with a small sphere at each end; the segment's length is the
 * constraint's stretch, so a stiff constraint shows as a dot that grows when it gives. Drawn over
 * the bodies (joints sit inside them).
 */
export class ConstraintsView {
  readonly root = new THREE.Group();
  /** Radius of an end marker, m. */
  pointRadius = 0.004;
  private readonly lineGeo = new THREE.BufferGeometry();
  private readonly lines = new THREE.LineSegments(this.lineGeo, new THREE.LineBasicMaterial({ color: '#2ec4b6', depthTest: false }));
  private capacity = 0;
  private ends!: THREE.InstancedMesh;
  private readonly endGeo = new THREE.SphereGeometry(1, 10, 8);
  private readonly endMat = new THREE.MeshBasicMaterial({ color: '#2ec4b6', depthTest: false });

  constructor() {
    this.root.name = 'constraints';
    this.lines.frustumCulled = false;
    this.lines.renderOrder = 10;
    this.root.add(this.lines);
    this.grow(64);
  }

  private grow(n: number): void {
    if (this.ends) { this.ends.removeFromParent(); this.ends.dispose(); }
    this.capacity = n;
    this.ends = new THREE.InstancedMesh(this.endGeo, this.endMat, n);
    this.ends.count = 0;
    this.ends.frustumCulled = false;
    this.ends.renderOrder = 10;
    this.root.add(this.ends);
  }

  /** Shows these constraints (or none). */
  update(constraints: ConstraintMarker[] | undefined): void {
    const list = (Array.isArray(constraints) ? constraints : []).filter((c) => Array.isArray(c?.a) && Array.isArray(c?.b));
    if (2 * list.length > this.capacity) this.grow(Math.max(2 * list.length, this.capacity * 2));
    const positions = new Float32Array(6 * list.length);
    const m = new THREE.Matrix4();
    const q = new THREE.Quaternion();
    const s = new THREE.Vector3().setScalar(this.pointRadius);
    const p = new THREE.Vector3();
    list.forEach((c, i) => {
      positions.set([c.a[0], c.a[1], c.a[2], c.b[0], c.b[1], c.b[2]], 6 * i);
      this.ends.setMatrixAt(2 * i, m.compose(p.set(c.a[0], c.a[1], c.a[2]), q, s));
      this.ends.setMatrixAt(2 * i + 1, m.compose(p.set(c.b[0], c.b[1], c.b[2]), q, s));
    });
    this.lineGeo.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    this.lineGeo.computeBoundingSphere();
    this.ends.count = 2 * list.length;
    this.ends.instanceMatrix.needsUpdate = true;
  }
}
