import * as THREE from 'three';
import type { Pose } from './protocol';

/** The identity pose [0, 0, 0, 0, 0, 0, 1]. */
export const IDENTITY_POSE: Pose = [0, 0, 0, 0, 0, 0, 1];

/** True if `p` looks like a pose: 7 finite numbers. */
export function isPose(p: unknown): p is Pose {
  return Array.isArray(p) && p.length >= 7 && p.slice(0, 7).every((v) => typeof v === 'number' && Number.isFinite(v));
}

/** Sets an object's local position (m) and orientation from a pose [px, py, pz, qx, qy, qz, qw]. */
export function applyPose(obj: THREE.Object3D, pose: Pose): void {
  obj.position.set(pose[0], pose[1], pose[2]);
  obj.quaternion.set(pose[3], pose[4], pose[5], pose[6]);
  // Guard against unnormalised quaternions (rounded to 7 digits in recordings).
  obj.quaternion.normalize();
}
