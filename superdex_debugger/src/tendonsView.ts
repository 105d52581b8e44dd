import * as THREE from 'three';
import type { TendonRoute } from './protocol';

/** Spatial tendons: each route's segments between its waypoints (orange), drawn over the bodies. */
export class TendonsView {
  readonly root = new THREE.Group();
  private readonly geo = new THREE.BufferGeometry();
  private readonly lines = new THREE.LineSegments(this.geo, new THREE.LineBasicMaterial({ color: '#ff9f1c', depthTest: false }));

  constructor() {
    this.root.name = 'tendons';
    this.lines.frustumCulled = false;
    this.lines.renderOrder = 10;
    this.root.add(this.lines);
  }

  /** Shows these routes (or none). */
  update(tendons: TendonRoute[] | undefined): void {
    const flat: number[] = [];
    for (const t of Array.isArray(tendons) ? tendons : []) if (Array.isArray(t?.s) && t.s.length % 6 === 0) flat.push(...t.s);
    this.geo.setAttribute('position', new THREE.BufferAttribute(new Float32Array(flat), 3));
    this.geo.computeBoundingSphere();
  }
}
