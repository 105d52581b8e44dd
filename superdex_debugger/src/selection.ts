/** What is selected in the tree or the 3D view: a scene, an actor in it, or one of its links. */
export interface Selection {
  scene: number;
  actor?: number;
  link?: number;
}

export function sameSelection(a: Selection | null, b: Selection | null): boolean {
  return a?.scene === b?.scene && a?.actor === b?.actor && a?.link === b?.link;
}
