import { contactForceOn } from './contactForces';
import { esc, num, vec } from './format';
import { isPose } from './pose';
import { renderModelSpec } from './renderModels';
import type { ActorMsg, FrameMsg, LinkDesc } from './protocol';
import type { Selection } from './selection';
import type { DebugStore, SceneState } from './store';

type Row = [label: string, value: string, unit?: string];

/** Total mass of an actor's links, kg, or undefined when no link has a mass. */
function actorMass(a: ActorMsg): number | undefined {
  const masses = (a.links ?? []).map((l) => l.mass).filter((m): m is number => typeof m === 'number');
  return masses.length ? masses.reduce((s, m) => s + m, 0) : undefined;
}

/** Magnitude of a 3-vector. */
const norm = (v: number[]) => Math.hypot(v[0], v[1], v[2]);

/**
 * The property panel of the selection at the shown frame: kind, handle, mass, DOFs, world
 * pose of a link (m, quaternion [x, y, z, w]), joint q/qd, and the total contact force (N, world).
 */
export class PropertiesPanel {
  constructor(private readonly el: HTMLElement, private readonly store: DebugStore) {}

  show(sel: Selection | null, scene: SceneState | undefined, frame: FrameMsg | undefined): void {
    if (!sel || !scene) {
      this.el.innerHTML = '<div class="empty">Select a scene, actor or link.</div>';
      return;
    }
    const actor = sel.actor !== undefined ? scene.actors.get(sel.actor) : undefined;
    const link = actor && sel.link !== undefined ? actor.links?.find((l) => l.handle === sel.link) : undefined;
    let title: string;
    let sections: [string, Row[]][];
    if (link && actor) {
      title = link.name ?? `link ${link.handle}`;
      sections = this.linkSections(actor, link, frame);
    } else if (actor) {
      title = actor.name ?? `actor ${actor.handle}`;
      sections = this.actorSections(actor, frame);
    } else {
      title = scene.name;
      sections = this.sceneSections(scene, frame);
    }
    // One table for all sections, so that the value column lines up.
    const html = [`<div class="prop-title">${esc(title)}</div><table class="props">`];
    for (const [name, rows] of sections) {
      if (!rows.length) continue;
      html.push(`<tr class="sec"><td colspan="2">${esc(name)}</td></tr>`);
      for (const [k, v, u] of rows) html.push(`<tr><th>${esc(k)}</th><td>${v}${u ? ` <span class="unit">${esc(u)}</span>` : ''}</td></tr>`);
    }
    html.push('</table>');
    this.el.innerHTML = html.join('');
  }

  private sceneSections(scene: SceneState, frame: FrameMsg | undefined): [string, Row[]][] {
    const rows: Row[] = [
      ['handle', String(scene.handle)],
      ['actors', String(scene.actors.size)],
      ['gravity', scene.gravity ? vec(scene.gravity, 2) : '–', 'm/s²'],
      ['frames stored', String(scene.frames.length)],
    ];
    const fi = this.store.header?.frameInterval;
    if (typeof fi === 'number') rows.push(['frame interval', num(fi, 4), 's']);
    const fr: Row[] = frame
      ? [
          ['t', num(frame.t, 4), 's'],
          ['step', String(frame.step)],
          ['contacts', String(frame.contacts?.length ?? 0)],
        ]
      : [];
    return [
      ['Scene', rows],
      ['Frame', fr],
    ];
  }

  private actorSections(a: ActorMsg, frame: FrameMsg | undefined): [string, Row[]][] {
    const mass = actorMass(a);
    const rows: Row[] = [
      ['kind', esc(a.kind)],
      ['handle', String(a.handle)],
      ['mass', mass !== undefined ? num(mass, 4) : '–', mass !== undefined ? 'kg' : undefined],
      ['numDofs', a.numDofs !== undefined ? String(a.numDofs) : '–'],
    ];
    if (a.links) rows.push(['links', String(a.links.length)]);
    if (a.kind === 'soft') {
      rows.push(['nodes', String(a.nodes?.length ?? 0)], ['surface triangles', String(a.surfaceTriangles?.length ?? 0)]);
    }
    const state: Row[] = [];
    const soft = frame?.soft?.[String(a.handle)];
    if (Array.isArray(soft) && soft.length >= 3) {
      // Centroid of the nodes, a cheap summary of where the soft body is.
      const c = [0, 0, 0];
      for (let i = 0; i < soft.length; i += 3) for (let k = 0; k < 3; k++) c[k] += soft[i + k];
      const n = soft.length / 3;
      state.push(['node centroid', vec(c.map((x) => x / n)), 'm']);
    }
    const js = frame?.joints?.[String(a.handle)];
    if (js) {
      state.push(['q', vec(js.q, 4)], ['qd', vec(js.qd, 4)]);
    }
    const bodies = new Set<number>([a.handle, ...(a.links ?? []).map((l) => l.handle)]);
    const contact = contactRows(frame, bodies);
    return [
      ['Actor', rows],
      ['State', state],
      ['Contact (world)', contact],
    ];
  }

  private linkSections(a: ActorMsg, l: LinkDesc, frame: FrameMsg | undefined): [string, Row[]][] {
    const parent = l.parent >= 0 ? a.links?.[l.parent] : undefined;
    const rows: Row[] = [
      ['actor', esc(a.name ?? String(a.handle))],
      ['handle', String(l.handle)],
      ['parent', parent ? esc(parent.name ?? String(parent.handle)) : '–'],
      ['mass', typeof l.mass === 'number' ? num(l.mass, 4) : '–', typeof l.mass === 'number' ? 'kg' : undefined],
    ];
    if (l.joint) rows.push(['joint', `${esc(l.joint.type)} (${l.joint.dofs} dof @ ${l.joint.offset})`]);
    const rm = renderModelSpec(l.renderModel);
    if (rm) rows.push(['render model', `${esc(rm.name || '(unnamed)')}${rm.scale.every((v) => v === 1) ? '' : ` (scale ${vec(rm.scale)})`}`]);
    const pose: Row[] = [];
    const p = frame?.links?.[String(l.handle)];
    if (isPose(p)) {
      pose.push(['position', vec(p.slice(0, 3)), 'm'], ['quaternion', vec(p.slice(3, 7)), 'xyzw']);
    } else if (a.kind === 'static') {
      pose.push(['position', vec([0, 0, 0]), 'm'], ['quaternion', vec([0, 0, 0, 1]), 'xyzw']);
    } else if (frame) {
      pose.push(['pose', 'not in this frame']);
    }
    const joint: Row[] = [];
    const js = frame?.joints?.[String(a.handle)];
    if (js && l.joint && l.joint.dofs > 0) {
      const { offset, dofs } = l.joint;
      const qd = js.qd?.slice(offset, offset + dofs);
      // q has the same layout as qd only when the actor has no quaternion joints.
      const q = js.q?.length === js.qd?.length ? js.q.slice(offset, offset + dofs) : undefined;
      // the engine spells joint types as the bot files do ("Revolute")
      const type = l.joint.type.toLowerCase();
      const unit = type === 'prismatic' ? ['m', 'm/s'] : type === 'revolute' ? ['rad', 'rad/s'] : [undefined, undefined];
      if (q) joint.push(['q', vec(q), unit[0]]);
      if (qd) joint.push(['qd', vec(qd), unit[1]]);
    }
    const contact = contactRows(frame, new Set([l.handle]));
    return [
      ['Link', rows],
      ['World pose', pose],
      ['Joint', joint],
      ['Contact (world)', contact],
    ];
  }
}

/** Rows of the total contact force (world) on `bodies` in `frame`; none without a frame. */
function contactRows(frame: FrameMsg | undefined, bodies: Set<number>): Row[] {
  if (!frame) return [];
  const cf = contactForceOn(frame.contacts, bodies);
  return [
    ['force', vec(cf.force, 3), 'N'],
    ['|force|', num(norm(cf.force), 3), 'N'],
    ['contacts', String(cf.count)],
  ];
}
