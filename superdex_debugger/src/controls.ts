import type { ConnectionState } from './connection';
import { esc, num } from './format';
import { ICONS } from './icons';
import type { ControlAction, SessionMsg, StatusMsg } from './protocol';

export interface ToolbarHandlers {
  /** A live control button was pressed. */
  control(action: ControlAction): void;
  setFramesVisible(v: boolean): void;
  setContactsVisible(v: boolean): void;
  setConstraintsVisible(v: boolean): void;
  setTendonsVisible(v: boolean): void;
  /** Also draw the colliders of links shown with a render model. */
  setCollidersVisible(v: boolean): void;
  /** Force arrow scale, m/N. */
  setForceScale(mPerN: number): void;
}

/** Force scale slider: 10^(value) m/N. */
const FORCE_EXP = { min: -4, max: 0, initial: Math.log10(0.02) };

/**
 * The toolbar: connection state, session mode, the live controls (pause, play, fast, step,
 * restore), the latest `status` (state, speed, t, step) and the view toggles.
 */
export class Toolbar {
  private readonly conn: HTMLElement;
  private readonly mode: HTMLElement;
  private readonly live: HTMLElement;
  private readonly status: HTMLElement;
  private readonly buttons = new Map<ControlAction, HTMLButtonElement>();
  private readonly collidersToggle: HTMLElement;

  constructor(el: HTMLElement, h: ToolbarHandlers) {
    el.innerHTML = `
      <div class="brand"><span class="logo"></span>SuperDex<span class="sub">Debugger</span></div>
      <div class="pill conn connecting" data-id="conn"><span class="dot"></span><span class="txt">connecting…</span></div>
      <div class="pill mode" data-id="mode" hidden></div>
      <div class="group live-controls" data-id="live" hidden>
        <button data-action="pause" title="Pause (space)">${ICONS.pause}<span>Pause</span></button>
        <button data-action="play" title="Play in real time (space)">${ICONS.play}<span>Play</span></button>
        <button data-action="fast" title="Step as fast as possible">${ICONS.fast}<span>Fast</span></button>
        <button data-action="step" title="One step (→ while paused)">${ICONS.step}<span>Step</span></button>
        <button data-action="restore" title="Return every scene to its first state">${ICONS.restore}<span>Restore</span></button>
      </div>
      <div class="status" data-id="status" hidden></div>
      <div class="spacer"></div>
      <div class="group toggles">
        <label class="toggle" data-id="colliders-toggle" title="Also draw the colliders of links shown with a render model" hidden><input type="checkbox" data-id="colliders"><span>Colliders</span></label>
        <label class="toggle"><input type="checkbox" data-id="frames"><span>Frames</span></label>
        <label class="toggle"><input type="checkbox" data-id="contacts" checked><span>Contacts</span></label>
        <label class="toggle"><input type="checkbox" data-id="constraints" checked><span>Constraints</span></label>
        <label class="toggle"><input type="checkbox" data-id="tendons" checked><span>Tendons</span></label>
        <label class="scale" title="Force arrow length per newton">
          <input type="range" data-id="fscale" min="${FORCE_EXP.min}" max="${FORCE_EXP.max}" step="0.05" value="${FORCE_EXP.initial}">
          <span data-id="fscale-label"></span>
        </label>
      </div>`;
    const q = <T extends HTMLElement>(id: string) => el.querySelector<T>(`[data-id="${id}"]`)!;
    this.conn = q('conn');
    this.mode = q('mode');
    this.live = q('live');
    this.status = q('status');
    this.collidersToggle = q('colliders-toggle');
    for (const b of this.live.querySelectorAll<HTMLButtonElement>('button')) {
      const action = b.dataset.action as ControlAction;
      this.buttons.set(action, b);
      b.addEventListener('click', () => h.control(action));
    }
    q<HTMLInputElement>('frames').addEventListener('change', (e) => h.setFramesVisible((e.target as HTMLInputElement).checked));
    q<HTMLInputElement>('colliders').addEventListener('change', (e) => h.setCollidersVisible((e.target as HTMLInputElement).checked));
    q<HTMLInputElement>('contacts').addEventListener('change', (e) => h.setContactsVisible((e.target as HTMLInputElement).checked));
    q<HTMLInputElement>('constraints').addEventListener('change', (e) => h.setConstraintsVisible((e.target as HTMLInputElement).checked));
    q<HTMLInputElement>('tendons').addEventListener('change', (e) => h.setTendonsVisible((e.target as HTMLInputElement).checked));
    const fs = q<HTMLInputElement>('fscale');
    const fsLabel = q('fscale-label');
    const onScale = () => {
      const v = Math.pow(10, Number(fs.value));
      fsLabel.textContent = `${v < 0.01 ? v.toPrecision(2) : v.toFixed(3)} m/N`;
      h.setForceScale(v);
    };
    fs.addEventListener('input', onScale);
    onScale();
  }

  /** The Colliders toggle is offered while the shown scene has render models (it starts off). */
  setHasRenderModels(v: boolean): void {
    this.collidersToggle.hidden = !v;
  }

  setConnection(s: ConnectionState): void {
    this.conn.className = `pill conn ${s}`;
    this.conn.querySelector('.txt')!.textContent = s === 'connecting' ? 'connecting…' : s;
  }

  setSession(s: SessionMsg): void {
    const replay = s.mode === 'replay';
    this.mode.hidden = false;
    this.mode.className = `pill mode ${replay ? 'replay' : 'live'}`;
    this.mode.innerHTML = replay ? `REPLAY${s.source ? ` <span class="src">${esc(s.source)}</span>` : ''}` : 'LIVE';
    this.live.hidden = replay;
    this.status.hidden = replay;
  }

  setStatus(st: StatusMsg): void {
    const playing = st.state === 'playing';
    this.buttons.get('pause')!.classList.toggle('active', !playing);
    this.buttons.get('play')!.classList.toggle('active', playing && st.speed !== 'fast');
    this.buttons.get('fast')!.classList.toggle('active', playing && st.speed === 'fast');
    this.buttons.get('step')!.disabled = playing;
    this.status.innerHTML =
      `<span class="state ${esc(st.state)}">${esc(st.state)}</span>` +
      `<span class="kv speed">${esc(st.speed)}</span>` +
      `<span class="kv"><b>t</b>${num(st.t, 3)} s</span>` +
      `<span class="kv"><b>step</b>${st.step}</span>`;
  }
}
