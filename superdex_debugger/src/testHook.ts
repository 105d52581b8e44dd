import type { FrameMsg, SessionMsg, StatusMsg } from './protocol';

/**
 * The automation interface on `window.superdex` (part of the product: tests and scripts drive
 * the page through it). Frame indices count the stored frames of a scene, 0 = oldest.
 */
export interface SuperdexHook {
  connected(): boolean;
  session(): SessionMsg | null;
  /** The latest `status` message. */
  status(): StatusMsg | null;
  /** Number of stored frames of a scene (the first scene by default). */
  frameCount(sceneHandle?: number): number;
  /** The k-th stored frame message exactly as received (undefined if out of range). */
  frame(k: number, sceneHandle?: number): FrameMsg | undefined;
  /** Index of the frame shown, among the stored frames of the shown scene. */
  currentFrameIndex(): number;
  /** Shows the k-th stored frame of the shown scene (stops following the newest frame). */
  seek(k: number): void;
  /** Every actor and link name in the scene tree. */
  actorNames(): string[];
  /** Every signal name seen, over all scenes. */
  signalNames(): string[];
  /** Points stored for a signal, summed over scenes. */
  signalPointCount(name: string): number;
  /** Names of the signals currently drawn in charts. */
  plottedSignals(): string[];
  /** Sends a control action (pause, play, fast, step, restore). */
  control(action: string): void;
  /** Replay: the `end` message has arrived. */
  replayEnded(): boolean;
  /** Replay: the `end` message's frame count, or null. */
  replayTotal(): number | null;
  /** Scene handles in order of appearance. */
  scenes(): number[];
  /** Links of the shown scene whose glTF render model has loaded and is in the 3D view. */
  renderModelCount(): number;
  /** Times the 3D view has been drawn since the page loaded. */
  drawCount(): number;
  /** Handles of the actors drawn in the 3D view (a replay shows destroyed actors up to their
   * last frame). */
  shownActors(): number[];
  /** The 3D view's axis convention: FLU (z up) or RUB (y up). */
  upAxis(): 'FLU' | 'RUB';
}

declare global {
  interface Window {
    superdex: SuperdexHook;
  }
}

export function installHook(hook: SuperdexHook): void {
  window.superdex = hook;
}
