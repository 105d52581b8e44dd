import { num } from './format';
import { ICONS } from './icons';

/** What the timeline bar shows. */
export interface TimelineState {
  mode: 'live' | 'replay' | null;
  /** Frames stored for the shown scene. */
  count: number;
  /** Index of the shown frame among the stored ones (0 = oldest), -1 if none. */
  index: number;
  /** Simulated time of the shown frame, s. */
  t: number | null;
  /** Simulated time of the newest stored frame, s. */
  tLast: number | null;
  /** Replay: playback running. */
  playing: boolean;
  /** Live: the view follows the newest frame. */
  following: boolean;
  /** Replay: the `end` message's frame count, once received. */
  total: number | null;
}

export interface TimelineHandlers {
  seek(index: number): void;
  /** Replay: start or stop playback. */
  togglePlay(): void;
  /** Replay: playback rate (1 = recorded speed). */
  setRate(rate: number): void;
  /** Live: follow the newest frame again. */
  follow(): void;
}

/** The bar under the 3D view: a slider over the stored frames, playback buttons and readouts. */
export class Timeline {
  private readonly slider: HTMLInputElement;
  private readonly playBtn: HTMLButtonElement;
  private readonly firstBtn: HTMLButtonElement;
  private readonly liveBtn: HTMLButtonElement;
  private readonly rate: HTMLSelectElement;
  private readonly frameLabel: HTMLElement;
  private readonly timeLabel: HTMLElement;
  private dragging = false;
  private last = '';

  constructor(el: HTMLElement, h: TimelineHandlers) {
    el.innerHTML = `
      <button class="tbtn" data-id="first" title="First frame">${ICONS.first}</button>
      <button class="tbtn primary" data-id="play" title="Play / pause (space)">${ICONS.play}</button>
      <select data-id="rate" title="Playback speed"><option value="0.25">0.25×</option><option value="0.5">0.5×</option><option value="1" selected>1×</option><option value="2">2×</option><option value="4">4×</option></select>
      <input type="range" data-id="slider" min="0" max="0" value="0" step="1">
      <div class="readout"><span data-id="frame">–</span><span data-id="time">–</span></div>
      <button class="tbtn live" data-id="live" title="Follow the newest frame">${ICONS.live}<span>LIVE</span></button>`;
    const q = <T extends HTMLElement>(id: string) => el.querySelector<T>(`[data-id="${id}"]`)!;
    this.slider = q('slider');
    this.playBtn = q('play');
    this.firstBtn = q('first');
    this.liveBtn = q('live');
    this.rate = q('rate');
    this.frameLabel = q('frame');
    this.timeLabel = q('time');
    this.slider.addEventListener('input', () => h.seek(Number(this.slider.value)));
    this.slider.addEventListener('pointerdown', () => (this.dragging = true));
    window.addEventListener('pointerup', () => (this.dragging = false));
    this.playBtn.addEventListener('click', () => h.togglePlay());
    this.firstBtn.addEventListener('click', () => h.seek(0));
    this.liveBtn.addEventListener('click', () => h.follow());
    this.rate.addEventListener('change', () => h.setRate(Number(this.rate.value)));
  }

  update(s: TimelineState): void {
    const key = JSON.stringify(s);
    if (key === this.last) return;
    this.last = key;
    const replay = s.mode === 'replay';
    this.playBtn.hidden = !replay;
    this.firstBtn.hidden = !replay;
    this.rate.hidden = !replay;
    this.liveBtn.hidden = replay;
    this.liveBtn.classList.toggle('on', s.following);
    this.playBtn.innerHTML = s.playing ? ICONS.pause : ICONS.play;
    this.slider.max = String(Math.max(0, s.count - 1));
    this.slider.disabled = s.count === 0;
    if (!this.dragging) this.slider.value = String(Math.max(0, s.index));
    // Fill the track up to the thumb.
    const frac = s.count > 1 ? Math.max(0, s.index) / (s.count - 1) : 0;
    this.slider.style.setProperty('--fill', `${(frac * 100).toFixed(2)}%`);
    const total = s.total !== null ? ` (${s.total} in file)` : '';
    this.frameLabel.textContent = s.count ? `frame ${s.index + 1} / ${s.count}${replay ? total : ''}` : 'no frames';
    this.timeLabel.textContent = s.t !== null ? `t = ${num(s.t, 3)} s${s.tLast !== null ? ` / ${num(s.tLast, 3)}` : ''}` : '';
  }
}
