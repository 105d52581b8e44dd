import * as THREE from 'three';
import type { Shape } from './protocol';

/** Side length of the finite quad drawn for an infinite plane, m. */
export const PLANE_SIZE = 8;

/** Flattens [[x,y,z], ...] or [x, y, z, ...] to a flat number array. */
function flat(a: number[][] | number[]): number[] {
  return Array.isArray(a[0]) ? (a as number[][]).flat() : (a as number[]);
}

/** What a collider is drawn with: geometry in the shape frame, and whether it is a plane. */
export interface ShapeGeometry {
  geometry: THREE.BufferGeometry;
  isPlane: boolean;
}

/**
 * Geometry of a collision shape in the shape's own frame (m), or null for unknown shapes.
 * Capsules lie along z; planes are a finite PLANE_SIZE quad centred at the plane point nearest
 * the origin (distance / |normal| along the unit normal).
 */
export function shapeGeometry(shape: Shape): ShapeGeometry | null {
  if (shape.sphere) {
    const r = shape.sphere.radius;
    const g = new THREE.SphereGeometry(r, 32, 20);
    const c = shape.sphere.center;
    if (c) g.translate(c[0], c[1], c[2]);
    return { geometry: g, isPlane: false };
  }
  if (shape.box) {
    const [x, y, z] = shape.box.halfExtents;
    return { geometry: new THREE.BoxGeometry(2 * x, 2 * y, 2 * z), isPlane: false };
  }
  if (shape.capsule) {
    const { radius, halfLength } = shape.capsule;
    const g = new THREE.CapsuleGeometry(radius, 2 * halfLength, 8, 24);
    // three.js capsules lie along y; the engine's along z.
    g.rotateX(Math.PI / 2);
    return { geometry: g, isPlane: false };
  }
  if (shape.plane) {
    const n = new THREE.Vector3(...shape.plane.normal);
    if (n.lengthSq() === 0) n.set(0, 0, 1);
    // {x : normal . x = distance} for a normal of any length: distance / |normal| along the unit normal
    const d = (shape.plane.distance ?? 0) / n.length();
    n.normalize();
    const g = new THREE.PlaneGeometry(PLANE_SIZE, PLANE_SIZE);
    // PlaneGeometry faces +z: turn it to the plane's normal, then move it along it by d.
    g.applyQuaternion(new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 0, 1), n));
    g.translate(n.x * d, n.y * d, n.z * d);
    return { geometry: g, isPlane: true };
  }
  if (shape.mesh) {
    const indexed = new THREE.BufferGeometry();
    indexed.setAttribute('position', new THREE.Float32BufferAttribute(flat(shape.mesh.vertices), 3));
    indexed.setIndex(flat(shape.mesh.triangles));
    // Unshared vertices give flat shading: collision meshes have sharp edges.
    const g = indexed.toNonIndexed();
    indexed.dispose();
    g.computeVertexNormals();
    return { geometry: g, isPlane: false };
  }
  return null;
}
