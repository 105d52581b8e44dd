import type { Contact, Vec3 } from './protocol';

/** Total contact force on a set of bodies, N, world frame, and the number of contacts involved. */
export interface ContactSum {
  force: Vec3;
  count: number;
}

/**
 * Sums the contact forces acting on `bodies` (actor or link handles): +f for contacts whose a is
 * in the set, -f for those whose b is (f is the force on a; b receives -f).
 */
export function contactForceOn(contacts: Contact[] | undefined, bodies: Set<number>): ContactSum {
  const force: Vec3 = [0, 0, 0];
  let count = 0;
  for (const c of contacts ?? []) {
    if (!Array.isArray(c?.f)) continue;
    const sa = bodies.has(c.a) ? 1 : 0;
    const sb = bodies.has(c.b) ? 1 : 0;
    if (!sa && !sb) continue;
    count++;
    const k = sa - sb;
    force[0] += k * c.f[0];
    force[1] += k * c.f[1];
    force[2] += k * c.f[2];
  }
  return { force, count };
}
