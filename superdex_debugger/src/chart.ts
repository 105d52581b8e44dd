import uPlot from 'uplot';
import { seriesColor } from './colors';
import { esc, num } from './format';
import type { SignalSeries } from './signals';

/** Height of the plotting canvas, CSS px. */
const CHART_HEIGHT = 120;

const AXIS = {
  stroke: '#8a93a3',
  font: '10px system-ui, sans-serif',
  grid: { stroke: 'rgba(255,255,255,0.06)', width: 1 },
  ticks: { stroke: 'rgba(255,255,255,0.12)', width: 1, size: 4 },
};

/**
 * One uPlot chart of one signal against simulated time t (s): a series per component, a
 * vertical cursor at the shown frame's time, and a header with the value at that time.
 */
export class SignalChart {
  readonly el = document.createElement('div');
  private readonly header = document.createElement('div');
  private readonly body = document.createElement('div');
  private u: uPlot | null = null;
  private components = 0;
  private cursorT: number | null = null;
  /** Called with a time (s) when the chart is clicked. */
  onSeekTime: (t: number) => void = () => {};

  constructor(readonly name: string, private width: number) {
    this.el.className = 'chart';
    this.el.dataset.signal = name;
    this.el.dataset.points = '0';
    this.header.className = 'chart-header';
    this.el.append(this.header, this.body);
    this.setHeader(undefined);
  }

  private build(components: number): void {
    this.u?.destroy();
    this.components = components;
    const series: uPlot.Series[] = [{ label: 't' }];
    for (let c = 0; c < components; c++) {
      series.push({ label: components > 1 ? `[${c}]` : this.name, stroke: seriesColor(c), width: 1.5, spanGaps: false, points: { show: false } });
    }
    const opts: uPlot.Options = {
      width: this.width,
      height: CHART_HEIGHT,
      legend: { show: false },
      cursor: { drag: { x: false, y: false }, points: { show: false }, y: false },
      scales: {
        x: { time: false },
        // A constant signal gets a ±1 range around its value instead of uPlot's 0..100.
        y: { range: (_u, min, max) => (min === max ? [min - 1, max + 1] : uPlot.rangeNum(min, max, 0.1, true)) },
      },
      axes: [
        { ...AXIS, size: 22 },
        { ...AXIS, size: 46, values: (_u, vals) => vals.map((v) => shortNum(v)) },
      ],
      series,
      hooks: { draw: [(u) => this.drawCursor(u)] },
    };
    this.u = new uPlot(opts, [[], ...Array.from({ length: components }, () => [])] as uPlot.AlignedData, this.body);
    this.u.over.addEventListener('click', (e) => {
      if (!this.u) return;
      const t = this.u.posToVal(e.offsetX, 'x');
      if (Number.isFinite(t)) this.onSeekTime(t);
    });
  }

  /** Draws the time cursor as a vertical line across the plotting area. */
  private drawCursor(u: uPlot): void {
    if (this.cursorT === null) return;
    const x = u.valToPos(this.cursorT, 'x', true);
    if (x < u.bbox.left - 1 || x > u.bbox.left + u.bbox.width + 1) return;
    const ctx = u.ctx;
    ctx.save();
    ctx.strokeStyle = 'rgba(255, 209, 102, 0.9)';
    ctx.lineWidth = Math.max(1, devicePixelRatio);
    ctx.beginPath();
    ctx.moveTo(x, u.bbox.top);
    ctx.lineTo(x, u.bbox.top + u.bbox.height);
    ctx.stroke();
    ctx.restore();
  }

  /**
   * Shows the series within [xMin, xMax] (s) and the cursor at time `cursor`.
   * `value` is the signal at the cursor, for the header.
   */
  update(s: SignalSeries, xMin: number, xMax: number, cursor: number | null, value: (number | null)[] | undefined, dataChanged: boolean): void {
    const comps = Math.max(1, s.values.length);
    if (!this.u || comps !== this.components) {
      this.build(comps);
      dataChanged = true;
    }
    const u = this.u!;
    this.cursorT = cursor;
    if (xMax <= xMin) {
      xMin -= 0.5;
      xMax += 0.5;
    }
    u.batch(() => {
      if (dataChanged) {
        u.setData([s.t, ...s.values] as uPlot.AlignedData, false);
        this.el.dataset.points = String(s.t.length);
      }
      const sx = u.scales.x;
      if (dataChanged || sx.min !== xMin || sx.max !== xMax) u.setScale('x', { min: xMin, max: xMax });
      else u.redraw(false, false);
    });
    this.setHeader(value);
  }

  private setHeader(value: (number | null)[] | undefined): void {
    const vals = value
      ? value.map((v, c) => `<span class="val" style="color:${seriesColor(c)}">${num(v, 3)}</span>`).join('')
      : '<span class="val">–</span>';
    this.header.innerHTML = `<span class="sig-name" title="${esc(this.name)}">${esc(this.name)}</span><span class="vals">${vals}</span>`;
  }

  resize(width: number): void {
    this.width = width;
    this.u?.setSize({ width, height: CHART_HEIGHT });
  }

  destroy(): void {
    this.u?.destroy();
    this.el.remove();
  }
}

/** Compact axis labels: 1.2k, 0.05, 3e-4. */
function shortNum(v: number): string {
  const a = Math.abs(v);
  if (a === 0) return '0';
  if (a >= 1e4 || a < 1e-3) return v.toExponential(0);
  if (a >= 1000) return `${(v / 1000).toFixed(1)}k`;
  return String(Number(v.toPrecision(3)));
}
