import { SignalChart } from './chart';
import { esc } from './format';
import type { SceneState } from './store';

/**
 * Signals plotted by default, most wanted first: sensor readings, actuator efforts, joint
 * velocities (kinds from the `signals` messages; by name for recordings without them).
 */
const DEFAULT_KINDS = ['sensor', 'actuator', 'velocity'];
const FALLBACK_PATTERN = /sensor|\.effort|\.velocity/;
/** At most this many signals are selected automatically. */
const MAX_DEFAULT = 6;
/** Minimum time between two data refreshes of the charts, ms (the cursor moves every frame). */
const DATA_REFRESH_MS = 100;

/** What the charts should show: the time window (s) and the cursor. */
export interface PlotView {
  /** Time of the shown frame, s (the cursor). */
  cursor: number | null;
  /** Time range of the stored frames, s. */
  tFirst: number;
  tLast: number;
  /** True while the view follows the newest frame. */
  following: boolean;
}

/**
 * The signal list (checkboxes, filter) and one chart per checked signal of the shown scene.
 * The x axis is simulated time; the window is the whole timeline or the last/centred N seconds.
 */
export class PlotsPanel {
  private scene: SceneState | undefined;
  private readonly checked = new Set<string>();
  /** Names the user has toggled: defaults no longer apply to them. */
  private readonly touched = new Set<string>();
  private readonly charts = new Map<string, SignalChart>();
  private readonly seenLength = new Map<string, number>();
  private windowSeconds = 0;
  private filter = '';
  private lastRefresh = 0;
  private listDirty = true;
  private xRange: [number, number] = [0, 1];
  /** Called when a chart is clicked, with the time (s). */
  onSeekTime: (t: number) => void = () => {};

  constructor(
    private readonly listEl: HTMLElement,
    private readonly chartsEl: HTMLElement,
    filterEl: HTMLInputElement,
    windowEl: HTMLSelectElement,
  ) {
    filterEl.addEventListener('input', () => {
      this.filter = filterEl.value.trim().toLowerCase();
      this.renderList();
    });
    windowEl.addEventListener('change', () => {
      this.windowSeconds = Number(windowEl.value);
      this.lastRefresh = 0;
    });
    listEl.addEventListener('change', (e) => {
      const box = e.target as HTMLInputElement;
      const name = box.dataset.name;
      if (!name) return;
      this.touched.add(name);
      if (box.checked) this.checked.add(name);
      else this.checked.delete(name);
      this.syncCharts();
    });
    new ResizeObserver(() => {
      for (const c of this.charts.values()) c.resize(this.chartWidth());
    }).observe(chartsEl);
  }

  /** Switches to another scene's signals. */
  setScene(scene: SceneState | undefined): void {
    if (scene === this.scene) return;
    for (const c of this.charts.values()) c.destroy();
    this.charts.clear();
    this.seenLength.clear();
    this.scene = scene;
    this.checked.clear();
    this.touched.clear();
    this.addNames(scene ? [...scene.signals.series.keys()] : []);
    this.syncCharts();
  }

  /**
   * New signal names or kinds: the default selection is chosen again among the names the user has
   * not toggled, the most wanted kinds first, at most MAX_DEFAULT.
   */
  addNames(_names: string[]): void {
    const scene = this.scene;
    if (scene) {
      const rank = (name: string): number => {
        const kind = scene.signalKinds.get(name);
        if (kind !== undefined) {
          const i = DEFAULT_KINDS.indexOf(kind);
          return i < 0 ? Infinity : i;
        }
        return FALLBACK_PATTERN.test(name) ? DEFAULT_KINDS.length : Infinity;
      };
      const names = new Set([...scene.signals.series.keys(), ...scene.signalKinds.keys()]);
      const candidates = [...names]
        .filter((n) => !this.touched.has(n) && rank(n) < Infinity)
        .sort((a, b) => rank(a) - rank(b) || a.localeCompare(b));
      const chosenByUser = [...this.checked].filter((n) => this.touched.has(n));
      this.checked.clear();
      for (const n of chosenByUser) this.checked.add(n);
      for (const n of candidates.slice(0, Math.max(0, MAX_DEFAULT - chosenByUser.length))) this.checked.add(n);
    }
    this.listDirty = true;
    this.syncCharts();
  }

  /** Names of the signals drawn in charts, in order. */
  plotted(): string[] {
    return [...this.charts.keys()];
  }

  private chartWidth(): number {
    return Math.max(120, this.chartsEl.clientWidth - 16);
  }

  private syncCharts(): void {
    const names = this.scene ? [...this.scene.signals.series.keys()].filter((n) => this.checked.has(n)).sort() : [];
    for (const [n, c] of this.charts) {
      if (!names.includes(n)) {
        c.destroy();
        this.charts.delete(n);
        this.seenLength.delete(n);
      }
    }
    for (const n of names) {
      if (this.charts.has(n)) continue;
      const c = new SignalChart(n, this.chartWidth());
      c.onSeekTime = (t) => this.onSeekTime(t);
      this.charts.set(n, c);
    }
    // Keep the DOM order alphabetical.
    for (const n of names) this.chartsEl.appendChild(this.charts.get(n)!.el);
    this.chartsEl.classList.toggle('empty-charts', names.length === 0);
    this.chartsEl.dataset.hint = this.scene?.signals.series.size ? 'Check a signal to plot it.' : 'Charts appear when frames carry signals.';
    this.lastRefresh = 0;
    this.listDirty = true;
  }

  private renderList(): void {
    this.listDirty = false;
    const names = this.scene ? [...this.scene.signals.series.keys()].sort() : [];
    if (!names.length) {
      this.listEl.innerHTML = '<div class="empty">No signals received yet.</div>';
      return;
    }
    const shown = names.filter((n) => !this.filter || n.toLowerCase().includes(this.filter));
    this.listEl.innerHTML = shown
      .map((n) => `<label class="sig" title="${esc(n)}"><input type="checkbox" data-name="${esc(n)}" ${this.checked.has(n) ? 'checked' : ''}><span>${esc(n)}</span></label>`)
      .join('');
  }

  /** Redraws: data at most every DATA_REFRESH_MS, the cursor every call. */
  update(view: PlotView, now: number): void {
    if (this.listDirty) this.renderList();
    if (!this.scene) return;
    const refresh = now - this.lastRefresh >= DATA_REFRESH_MS;
    if (refresh) this.lastRefresh = now;
    // The window moves with the data refreshes only, so that a live stream redraws at a bounded rate.
    if (refresh) this.xRange = this.window(view);
    const [xMin, xMax] = this.xRange;
    for (const [name, chart] of this.charts) {
      const s = this.scene.signals.series.get(name);
      if (!s) {
        // Cleared by a restore: show it empty until new points arrive.
        this.seenLength.delete(name);
        continue;
      }
      const changed = refresh && this.seenLength.get(name) !== s.t.length;
      if (changed) this.seenLength.set(name, s.t.length);
      const value = view.cursor !== null ? this.scene.signals.valueAt(name, view.cursor) : undefined;
      chart.update(s, xMin, xMax, view.cursor, value, changed);
    }
  }

  /** The x range: all stored time, or N seconds ending at the newest frame (following) or centred on the cursor. */
  private window(v: PlotView): [number, number] {
    const w = this.windowSeconds;
    if (!w || v.tLast - v.tFirst <= w) return [v.tFirst, v.tLast];
    if (v.following || v.cursor === null) return [v.tLast - w, v.tLast];
    const lo = Math.min(Math.max(v.cursor - w / 2, v.tFirst), v.tLast - w);
    return [lo, lo + w];
  }
}
