import { Emitter } from './emitter';
import { Ring } from './ring';
import { SignalStore } from './signals';
import type {
  ActorMsg,
  EndMsg,
  FrameMsg,
  HeaderMsg,
  SessionMsg,
  StatusMsg,
  Vec3,
} from './protocol';

/** Frames kept per scene; older ones are dropped. */
export const MAX_FRAMES_PER_SCENE = 20000;

/** Everything known about one scene: its description and the frames received. */
export interface SceneState {
  handle: number;
  name: string;
  /** Gravity, m/s^2, world frame (if described). */
  gravity?: Vec3;
  /** Live actors by actor handle, in order of description. */
  actors: Map<number, ActorMsg>;
  /** Link handle -> actor handle, for the live actors. */
  linkOwner: Map<number, number>;
  /** Destroyed actors by handle, with the absolute index of the last frame they were in (a
   * replay shows them up to that frame). */
  retired: Map<number, { actor: ActorMsg; lastFrame: number }>;
  /** Frames as received (never modified). */
  frames: Ring<FrameMsg>;
  /** Absolute index of the first frame since simulated time last went backwards (a restore). */
  epochStart: number;
  signals: SignalStore;
  /** What each signal measures ("sensor", "actuator", "velocity", "effort", "contact", "user"). */
  signalKinds: Map<string, string>;
}

interface StoreEvents extends Record<string, unknown> {
  session: SessionMsg;
  header: HeaderMsg;
  status: StatusMsg;
  /** Scenes or actors were added, changed or removed. */
  structure: SceneState;
  frame: SceneState;
  /** New signal names appeared in a scene. */
  signals: { scene: SceneState; names: string[] };
  end: EndMsg;
}

const isNum = (v: unknown): v is number => typeof v === 'number' && Number.isFinite(v);

/** The page's model of the session, fed with parsed server messages. */
export class DebugStore extends Emitter<StoreEvents> {
  session: SessionMsg | null = null;
  header: HeaderMsg | null = null;
  status: StatusMsg | null = null;
  end: EndMsg | null = null;
  /** Scenes by handle, in order of first appearance. */
  readonly scenes = new Map<number, SceneState>();

  /** Applies one parsed message; ignores unknown types and malformed messages. */
  handle(msg: unknown): void {
    if (!msg || typeof msg !== 'object') return;
    const m = msg as { type?: unknown } & Record<string, unknown>;
    switch (m.type) {
      case 'session':
        this.session = m as unknown as SessionMsg;
        this.emit('session', this.session);
        break;
      case 'header':
        this.header = m as unknown as HeaderMsg;
        this.emit('header', this.header);
        break;
      case 'status':
        if (isNum(m.t) && isNum(m.step)) {
          this.status = m as unknown as StatusMsg;
          this.emit('status', this.status);
        }
        break;
      case 'end':
        this.end = m as unknown as EndMsg;
        this.emit('end', this.end);
        break;
      case 'scene':
        if (isNum(m.scene)) {
          const s = this.sceneFor(m.scene);
          if (typeof m.name === 'string') s.name = m.name;
          if (Array.isArray(m.gravity)) s.gravity = m.gravity as Vec3;
          this.emit('structure', s);
        }
        break;
      case 'actor':
        if (isNum(m.scene) && isNum(m.handle)) this.addActor(m as unknown as ActorMsg);
        break;
      case 'destroy':
        if (isNum(m.scene) && isNum(m.handle)) this.destroyActor(m.scene, m.handle);
        break;
      case 'frame':
        if (isNum(m.scene) && isNum(m.t)) this.addFrame(m as unknown as FrameMsg);
        break;
      case 'signals':
        if (isNum(m.scene) && m.kinds && typeof m.kinds === 'object') {
          const s = this.sceneFor(m.scene);
          const names: string[] = [];
          for (const [name, kind] of Object.entries(m.kinds as Record<string, unknown>)) {
            if (typeof kind !== 'string') continue;
            s.signalKinds.set(name, kind);
            names.push(name);
          }
          if (names.length) this.emit('signals', { scene: s, names });
        }
        break;
    }
  }

  /** The scene with this handle, created (named "scene N") if not described yet. */
  sceneFor(handle: number): SceneState {
    let s = this.scenes.get(handle);
    if (!s) {
      s = {
        handle,
        name: `scene ${handle}`,
        actors: new Map(),
        linkOwner: new Map(),
        retired: new Map(),
        frames: new Ring<FrameMsg>(MAX_FRAMES_PER_SCENE),
        epochStart: 0,
        signals: new SignalStore(MAX_FRAMES_PER_SCENE),
        signalKinds: new Map(),
      };
      this.scenes.set(handle, s);
    }
    return s;
  }

  /** The first scene seen, if any. */
  firstScene(): SceneState | undefined {
    return this.scenes.values().next().value;
  }

  /** The actor that owns a body handle (an actor handle or one of its link handles). */
  ownerOf(scene: SceneState, body: number): ActorMsg | undefined {
    const a = scene.actors.get(body);
    if (a) return a;
    const owner = scene.linkOwner.get(body);
    return owner === undefined ? undefined : scene.actors.get(owner);
  }

  private addActor(actor: ActorMsg): void {
    const s = this.sceneFor(actor.scene);
    // A re-described actor replaces the previous description.
    if (s.actors.has(actor.handle)) this.forgetLinks(s, actor.handle);
    s.actors.set(actor.handle, actor);
    for (const l of actor.links ?? []) if (isNum(l.handle)) s.linkOwner.set(l.handle, actor.handle);
    this.emit('structure', s);
  }

  private destroyActor(scene: number, handle: number): void {
    const s = this.scenes.get(scene);
    if (!s || !s.actors.has(handle)) return;
    this.forgetLinks(s, handle);
    s.retired.set(handle, { actor: s.actors.get(handle)!, lastFrame: s.frames.end - 1 });
    s.actors.delete(handle);
    this.emit('structure', s);
  }

  /** The actors a frame shows: the live ones and those destroyed after it (absolute index). */
  actorsAt(scene: SceneState, frame: number): ActorMsg[] {
    const out = [...scene.actors.values()];
    for (const r of scene.retired.values()) if (frame >= 0 && frame <= r.lastFrame) out.push(r.actor);
    return out;
  }

  private forgetLinks(s: SceneState, actor: number): void {
    for (const [link, owner] of s.linkOwner) if (owner === actor) s.linkOwner.delete(link);
  }

  private addFrame(frame: FrameMsg): void {
    const s = this.sceneFor(frame.scene);
    const prev = s.frames.last();
    // Time going backwards (a restore) starts a new epoch: the plots start again from there.
    if (prev && frame.t < prev.t) {
      s.epochStart = s.frames.end;
      s.signals.series.clear();
    }
    s.frames.push(frame);
    const added = s.signals.add(frame);
    if (added.length) this.emit('signals', { scene: s, names: added });
    this.emit('frame', s);
  }
}
