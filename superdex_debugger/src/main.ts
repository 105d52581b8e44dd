import 'uplot/dist/uPlot.min.css';
import './style.css';
import { ActorTree } from './actorTree';
import { STATIC_COLOR, actorColor } from './colors';
import { Connection, webSocketUrl } from './connection';
import { Toolbar } from './controls';
import { Playback } from './playback';
import { PlotsPanel } from './plots';
import { PropertiesPanel } from './properties';
import type { ActorMsg, Axes, ControlAction, FrameMsg } from './protocol';
import { SceneView } from './sceneView';
import { type Selection, sameSelection } from './selection';
import { DebugStore, type SceneState } from './store';
import { installHook } from './testHook';
import { Timeline } from './timeline';

/** Minimum time between two refreshes of the property panel, ms. */
const PROPS_REFRESH_MS = 50;

const $ = <T extends HTMLElement>(sel: string) => document.querySelector<T>(sel)!;

/** Wires the store, the connection and the panels; one render pass per animation frame. */
class App {
  readonly store = new DebugStore();
  readonly conn = new Connection(webSocketUrl());
  readonly view = new SceneView($('#view'));
  readonly playback = new Playback();
  readonly tree: ActorTree;
  readonly props = new PropertiesPanel($('#props'), this.store);
  readonly plots = new PlotsPanel($('#signal-list'), $('#charts'), $<HTMLInputElement>('#signal-filter'), $<HTMLSelectElement>('#plot-window'));
  readonly timeline: Timeline;
  readonly toolbar: Toolbar;

  selection: Selection | null = null;
  /** Handle of the scene shown in the view, plots and timeline. */
  shownScene: number | undefined;
  private sessionAxes: Axes = 'FLU';
  private shownAxes: Axes | undefined;
  /** Absolute index (see Ring) of the shown frame in the shown scene, -1 for none. */
  currentAbs = -1;
  /** Live: show the newest frame as it arrives. */
  following = true;
  private readonly colors = new Map<string, string>();
  private colorCount = 0;
  private structureDirty = true;
  private dataDirty = true;
  private shownFrame: FrameMsg | undefined;
  private propsDirty = true;
  private lastProps = 0;

  constructor() {
    this.tree = new ActorTree($('#tree'), this.store, (a) => this.colorOf(a), (s) => this.select(s));
    this.timeline = new Timeline($('#timeline'), {
      seek: (k) => this.seek(k),
      togglePlay: () => this.togglePlayback(),
      setRate: (r) => this.playback.setRate(r, this.frames(), this.currentIndex(), performance.now()),
      follow: () => this.setFollowing(true),
    });
    this.toolbar = new Toolbar($('#toolbar'), {
      control: (a) => this.control(a),
      setFramesVisible: (v) => this.view.setFramesVisible(v),
      setContactsVisible: (v) => this.view.setContactsVisible(v),
      setConstraintsVisible: (v) => this.view.setConstraintsVisible(v),
      setTendonsVisible: (v) => this.view.setTendonsVisible(v),
      setCollidersVisible: (v) => this.view.setCollidersVisible(v),
      setForceScale: (s) => this.view.setForceScale(s),
    });
    this.view.onPick = (p) => {
      if (this.shownScene === undefined) return;
      this.select(p ? { scene: this.shownScene, actor: p.actor, link: p.link } : { scene: this.shownScene });
    };
    this.plots.onSeekTime = (t) => this.seekTime(t);

    const st = this.store;
    st.on('session', (s) => {
      this.toolbar.setSession(s);
      this.sessionAxes = s.axes === 'RUB' ? 'RUB' : 'FLU';
      this.applyAxes();
      this.following = s.mode !== 'replay';
      document.title = `SuperDex Debugger${s.source ? ` — ${s.source}` : ''}`;
      this.dataDirty = true;
    });
    st.on('status', (s) => this.toolbar.setStatus(s));
    st.on('structure', () => (this.structureDirty = true));
    st.on('frame', (s) => {
      if (s.handle === this.shownScene || this.shownScene === undefined) this.dataDirty = true;
    });
    st.on('signals', ({ scene, names }) => {
      if (scene.handle === this.shownScene) this.plots.addNames(names);
    });
    st.on('end', () => (this.dataDirty = true));
    this.conn.on('state', (s) => this.toolbar.setConnection(s));
    this.conn.on('message', (m) => st.handle(m));
    this.installKeys();
    this.installHook();
    this.conn.open();
    requestAnimationFrame((t) => this.tick(t));
  }

  private get replay(): boolean {
    return this.store.session?.mode === 'replay';
  }

  /** The actor's colour: a palette colour per actor, neutral for static ones. */
  colorOf(a: ActorMsg): string {
    const key = `${a.scene}:${a.handle}`;
    let c = this.colors.get(key);
    if (!c) {
      c = a.kind === 'static' ? STATIC_COLOR : actorColor(this.colorCount++);
      this.colors.set(key, c);
    }
    return c;
  }

  scene(): SceneState | undefined {
    return this.shownScene !== undefined ? this.store.scenes.get(this.shownScene) : undefined;
  }

  frames() {
    return this.scene()?.frames;
  }

  /** Index of the shown frame among the stored frames (0 = oldest), -1 if none. */
  currentIndex(): number {
    const f = this.frames();
    if (!f || f.length === 0) return -1;
    return Math.min(Math.max(this.currentAbs - f.start, 0), f.length - 1);
  }

  seek(k: number): void {
    const f = this.frames();
    if (!f || f.length === 0) return;
    k = Math.min(Math.max(Math.round(k), 0), f.length - 1);
    this.playback.stop();
    this.currentAbs = f.start + k;
    if (!this.replay) this.following = k === f.length - 1;
    this.dataDirty = true;
  }

  /** Shows the last frame at or before time t (s), in the current epoch. */
  private seekTime(t: number): void {
    const f = this.frames();
    if (!f || f.length === 0) return;
    let lo = Math.max(0, this.scene()!.epochStart - f.start);
    let hi = f.length - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (f.get(mid)!.t <= t) lo = mid;
      else hi = mid - 1;
    }
    this.seek(lo);
  }

  private setFollowing(v: boolean): void {
    this.following = v && !this.replay;
    this.dataDirty = true;
  }

  private togglePlayback(): void {
    const f = this.frames();
    if (!f) return;
    if (this.playback.playing) this.playback.stop();
    else this.currentAbs = f.start + this.playback.play(f, this.currentIndex(), performance.now());
    this.dataDirty = true;
  }

  control(action: ControlAction | string): void {
    this.conn.control(action);
    if (action === 'play' || action === 'fast') this.setFollowing(true);
  }

  select(s: Selection | null): void {
    if (sameSelection(s, this.selection)) return;
    this.selection = s;
    this.tree.setSelection(s);
    this.view.setSelection(s?.actor, s?.link);
    if (s && s.scene !== this.shownScene) this.showScene(s.scene);
    this.propsDirty = true;
  }

  /** The session's axis convention, unless the shown scene's gravity points down y (SuperDex's
   * default, (0, -9.8, 0)): such a scene is shown Y up. */
  private applyAxes(): void {
    const g = this.scene()?.gravity;
    const yDown = !!g && g[1] < 0 && Math.abs(g[1]) > Math.abs(g[0]) && Math.abs(g[1]) > Math.abs(g[2]);
    const axes: Axes = yDown ? 'RUB' : this.sessionAxes;
    if (axes === this.shownAxes) return;
    this.shownAxes = axes;
    this.view.setAxes(axes);
  }

  private showScene(handle: number | undefined): void {
    this.shownScene = handle;
    const scene = this.scene();
    this.applyAxes();
    this.view.refit();
    this.plots.setScene(scene);
    this.currentAbs = scene && scene.frames.length ? (this.replay ? scene.frames.start : scene.frames.end - 1) : -1;
    this.view.setActors(scene ? this.store.actorsAt(scene, this.currentAbs) : [], (a) => this.colorOf(a));
    this.shownFrame = undefined;
    this.dataDirty = true;
  }

  private tick(now: number): void {
    requestAnimationFrame((t) => this.tick(t));
    if (this.structureDirty) {
      this.structureDirty = false;
      this.tree.render();
      if (this.shownScene === undefined || !this.store.scenes.has(this.shownScene)) {
        const first = this.store.firstScene();
        if (first) this.select({ scene: first.handle });
      }
      const scene = this.scene();
      if (scene) this.view.setActors(this.store.actorsAt(scene, this.currentAbs), (a) => this.colorOf(a));
      this.toolbar.setHasRenderModels(this.view.hasRenderModels());
      // A destroyed actor cannot stay selected.
      const sel = this.selection;
      if (sel?.actor !== undefined && !scene?.actors.has(sel.actor)) this.select({ scene: sel.scene });
      this.propsDirty = true;
    }
    const frames = this.frames();
    if (frames && frames.length) {
      if (this.playback.playing) {
        const k = this.playback.tick(frames, this.currentIndex(), now);
        this.currentAbs = frames.start + k;
        this.dataDirty = true;
      } else if (this.following) {
        this.currentAbs = frames.end - 1;
      } else if (this.currentAbs < frames.start) {
        this.currentAbs = frames.start;
      }
    }
    const frame = frames?.get(this.currentIndex());
    if (frame !== this.shownFrame) {
      this.shownFrame = frame;
      // actors destroyed later in the run are shown up to their last frame
      const scene = this.scene();
      if (scene?.retired.size) this.view.setActors(this.store.actorsAt(scene, this.currentAbs), (a) => this.colorOf(a));
      this.view.applyFrame(frame);
      this.propsDirty = true;
      this.dataDirty = true;
    }
    if (this.propsDirty && now - this.lastProps >= PROPS_REFRESH_MS) {
      this.propsDirty = false;
      this.lastProps = now;
      this.props.show(this.selection, this.scene(), frame);
    }
    if (this.dataDirty) {
      this.dataDirty = false;
      const scene = this.scene();
      const first = scene && frames ? frames.getAbs(Math.max(scene.epochStart, frames.start)) : undefined;
      const last = frames?.last();
      this.plots.update({ cursor: frame?.t ?? null, tFirst: first?.t ?? 0, tLast: last?.t ?? 1, following: this.following }, now);
      this.timeline.update({
        mode: this.store.session?.mode ?? null,
        count: frames?.length ?? 0,
        index: this.currentIndex(),
        t: frame?.t ?? null,
        tLast: last?.t ?? null,
        playing: this.playback.playing,
        following: this.following,
        total: this.store.end?.frames ?? null,
      });
    }
  }

  private installKeys(): void {
    window.addEventListener('keydown', (e) => {
      const tag = (e.target as HTMLElement).tagName;
      if (tag === 'INPUT' && (e.target as HTMLInputElement).type === 'text') return;
      if (tag === 'SELECT') return;
      if (e.key === ' ') {
        e.preventDefault();
        if (this.replay) this.togglePlayback();
        else this.control(this.store.status?.state === 'paused' ? 'play' : 'pause');
      } else if (e.key === 'ArrowRight') {
        if (!this.replay && this.following && this.store.status?.state === 'paused') this.control('step');
        else this.seek(this.currentIndex() + 1);
      } else if (e.key === 'ArrowLeft') {
        this.seek(this.currentIndex() - 1);
      }
    });
  }

  private installHook(): void {
    const sceneOf = (h?: number) => (h === undefined ? this.store.firstScene() : this.store.scenes.get(h));
    installHook({
      connected: () => this.conn.state === 'connected',
      session: () => this.store.session,
      status: () => this.store.status,
      frameCount: (h) => sceneOf(h)?.frames.length ?? 0,
      frame: (k, h) => sceneOf(h)?.frames.get(k),
      currentFrameIndex: () => this.currentIndex(),
      seek: (k) => this.seek(k),
      actorNames: () => this.tree.names(),
      signalNames: () => [...new Set([...this.store.scenes.values()].flatMap((s) => [...s.signals.series.keys()]))],
      signalPointCount: (name) => [...this.store.scenes.values()].reduce((n, s) => n + (s.signals.series.get(name)?.t.length ?? 0), 0),
      plottedSignals: () => this.plots.plotted(),
      control: (a) => this.control(a),
      replayEnded: () => this.store.end !== null,
      replayTotal: () => this.store.end?.frames ?? null,
      scenes: () => [...this.store.scenes.keys()],
      renderModelCount: () => this.view.renderModelCount(),
      drawCount: () => this.view.drawCount(),
      shownActors: () => this.view.shownActors(),
      upAxis: () => this.view.upAxis(),
    });
  }
}

new App();
