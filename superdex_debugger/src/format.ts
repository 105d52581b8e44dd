/** Number formatting for the panels. */

/** A number with `digits` decimals; "–" for missing values. */
export function num(v: number | null | undefined, digits = 4): string {
  if (v === null || v === undefined || !Number.isFinite(v)) return '–';
  const s = v.toFixed(digits);
  // Avoid "-0.0000".
  return /^-0\.?0*$/.test(s) ? s.slice(1) : s;
}

/** A vector as "x, y, z". */
export function vec(v: ArrayLike<number> | null | undefined, digits = 4): string {
  if (!v) return '–';
  return Array.from(v, (x) => num(x, digits)).join(', ');
}

/** Escapes text for use in innerHTML. */
export function esc(s: string): string {
  return s.replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]!);
}
