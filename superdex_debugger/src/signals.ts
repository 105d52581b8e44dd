import type { FrameMsg } from './protocol';

/** Time series of one named signal: one y array per component, aligned with `t`. */
export interface SignalSeries {
  name: string;
  /** Simulated time of each point, s. */
  t: number[];
  /** values[c][i]: component c at t[i]; null where the signal had fewer components or was not finite. */
  values: (number | null)[][];
}

/** Collects the `signals` of a scene's frames into per-name time series (bounded). */
export class SignalStore {
  readonly series = new Map<string, SignalSeries>();

  /** @param capacity maximum number of points kept per signal (the oldest are dropped). */
  constructor(readonly capacity: number) {}

  /** Appends the frame's signals; returns the names seen for the first time. */
  add(frame: FrameMsg): string[] {
    const signals = frame.signals;
    if (!signals || typeof signals !== 'object') return [];
    const added: string[] = [];
    for (const [name, raw] of Object.entries(signals)) {
      const vals = Array.isArray(raw) ? raw : [raw];
      let s = this.series.get(name);
      if (!s) {
        s = { name, t: [], values: [] };
        this.series.set(name, s);
        added.push(name);
      }
      // A signal that grows components gets null-filled columns for its past points.
      while (s.values.length < vals.length) s.values.push(new Array(s.t.length).fill(null));
      s.t.push(frame.t);
      for (let c = 0; c < s.values.length; c++) {
        const v = vals[c];
        s.values[c].push(typeof v === 'number' && Number.isFinite(v) ? v : null);
      }
      // Trim in chunks so that dropping the oldest points stays cheap.
      if (s.t.length > this.capacity + 512) {
        const n = s.t.length - this.capacity;
        s.t.splice(0, n);
        for (const col of s.values) col.splice(0, n);
      }
    }
    return added;
  }

  /** Value of a signal at time t (the latest point at or before t), or undefined. */
  valueAt(name: string, t: number): (number | null)[] | undefined {
    const s = this.series.get(name);
    if (!s || s.t.length === 0) return undefined;
    let lo = 0;
    let hi = s.t.length - 1;
    if (t < s.t[0]) return undefined;
    // Binary search for the last index with t[i] <= t.
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (s.t[mid] <= t) lo = mid;
      else hi = mid - 1;
    }
    return s.values.map((col) => col[lo]);
  }
}
