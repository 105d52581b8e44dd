import type { FrameMsg } from './protocol';
import type { Ring } from './ring';

/**
 * Replays stored frames at their recorded speed: the shown frame is the last one whose simulated
 * time t is at or before t0 + rate * (wall time since play).
 */
export class Playback {
  playing = false;
  /** Simulated seconds per wall-clock second. */
  rate = 1;
  private wall0 = 0;
  private t0 = 0;

  /** Starts from stored frame `index` (from the first frame if at the end). Returns the start index. */
  play(frames: Ring<FrameMsg>, index: number, now: number): number {
    if (index >= frames.length - 1) index = 0;
    this.playing = frames.length > 0;
    this.wall0 = now;
    this.t0 = frames.get(index)?.t ?? 0;
    return index;
  }

  stop(): void {
    this.playing = false;
  }

  setRate(rate: number, frames: Ring<FrameMsg> | undefined, index: number, now: number): void {
    // Restart the clock so that the change takes effect from the current frame.
    if (this.playing && frames) {
      this.wall0 = now;
      this.t0 = frames.get(index)?.t ?? 0;
    }
    this.rate = rate;
  }

  /** The index to show at wall time `now` (ms), advancing from `index`; stops at the last frame. */
  tick(frames: Ring<FrameMsg>, index: number, now: number): number {
    if (!this.playing) return index;
    const target = this.t0 + ((now - this.wall0) / 1000) * this.rate;
    let k = Math.max(0, index);
    while (k + 1 < frames.length && frames.get(k + 1)!.t <= target) k++;
    if (k >= frames.length - 1) this.playing = false;
    return k;
  }
}
