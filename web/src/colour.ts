// Force colour (SPEC I4, dissertation eq. 5.13): c = min(|f|/f_max, 1) maps blue (0) →
// green (0.5) → red (≥ 1), linear in each half — the same law as
// pliant_assembly::ergonomics::colour_rgb.

/** RGB in [0, 1] for colour value c; NaN counts as over the limit (red). */
export function colourRgb(c: number): [number, number, number] {
  const v = Number.isNaN(c) ? 1 : Math.min(Math.max(c, 0), 1);
  if (v <= 0.5) {
    const t = 2 * v;
    return [0, t, 1 - t];
  }
  const t = 2 * v - 1;
  return [t, 1 - t, 0];
}

/** CSS colour for c. */
export function colourCss(c: number): string {
  const [r, g, b] = colourRgb(c);
  return `rgb(${Math.round(255 * r)}, ${Math.round(255 * g)}, ${Math.round(255 * b)})`;
}
