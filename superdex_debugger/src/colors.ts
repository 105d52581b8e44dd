import * as THREE from 'three';

/** Distinct, soft colours for actors, used in order of description. */
const PALETTE = [
  '#5b9bf0', // blue
  '#f0a35b', // orange
  '#6cc38a', // green
  '#e6707a', // red
  '#b592e0', // violet
  '#5fc4c4', // teal
  '#e8cc5e', // yellow
  '#f293c0', // pink
  '#a7b86b', // olive
  '#c79a7b', // tan
];

/** Colour for planes and other static ground-like geometry. */
export const GROUND_COLOR = '#2f3540';

/** Colour of static actors (the tree swatch and their non-plane colliders). */
export const STATIC_COLOR = '#8a93a3';

/** The palette colour for the i-th actor (cycles). */
export function actorColor(i: number): string {
  return PALETTE[((i % PALETTE.length) + PALETTE.length) % PALETTE.length];
}

/** Colour of the c-th component series of a plotted signal. */
export function seriesColor(c: number): string {
  const s = ['#5b9bf0', '#f0a35b', '#6cc38a', '#e6707a', '#b592e0', '#5fc4c4', '#e8cc5e'];
  return s[c % s.length];
}

export function toThree(css: string): THREE.Color {
  return new THREE.Color(css);
}
