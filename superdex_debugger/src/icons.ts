/** Small inline SVG icons (16x16, currentColor) for buttons, independent of installed fonts. */
const svg = (body: string) => `<svg viewBox="0 0 16 16" width="14" height="14" aria-hidden="true">${body}</svg>`;

export const ICONS = {
  pause: svg('<rect x="3.5" y="2.5" width="3" height="11" rx="0.8" fill="currentColor"/><rect x="9.5" y="2.5" width="3" height="11" rx="0.8" fill="currentColor"/>'),
  play: svg('<path d="M4 2.5v11l9-5.5z" fill="currentColor"/>'),
  fast: svg('<path d="M1.5 3v10l6.5-5zM8 3v10l6.5-5z" fill="currentColor"/>'),
  step: svg('<path d="M3 2.5v11l7.5-5.5z" fill="currentColor"/><rect x="11" y="2.5" width="2.5" height="11" rx="0.6" fill="currentColor"/>'),
  restore: svg('<path d="M3.2 6.2A5 5 0 1 1 3 9.5" fill="none" stroke="currentColor" stroke-width="1.8" stroke-linecap="round"/><path d="M1.5 2.5v4.5H6z" fill="currentColor"/>'),
  first: svg('<rect x="2.5" y="2.5" width="2.5" height="11" rx="0.6" fill="currentColor"/><path d="M13 2.5v11L5.5 8z" fill="currentColor"/>'),
  live: svg('<circle cx="8" cy="8" r="4" fill="currentColor"/>'),
};
