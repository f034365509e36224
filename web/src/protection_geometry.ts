// Where and how a protection (tape, corrugated tube, sleeve) is drawn over a hose tube:
// pure functions over the tube's ring arrays (no three.js), so the unit tests can run them.
// A protection is a second, slightly larger tube over the rings of its stretch: its
// vertices are the hose tube's pushed out from the ring centres by a factor per ring.

export type ProtectionKind = 'tape' | 'fleece_tape' | 'corrugated_tube' | 'sleeve' | 'other';

/** How one kind looks: radius factor, rib depth (every other ring), shade, bands. */
export interface ProtectionStyle {
  /** Radius over the bundle's, as a factor. */
  scale: number;
  /** Extra radius factor of every other ring (the ribs of a corrugated tube). */
  rib: number;
  /** Factor on the hose's colour under it (its colour mode stays readable, darker). */
  shade: number;
  /** Further factor on every other ring (1: no bands; tape shows its windings). */
  band: number;
  roughness: number;
}

// shades are factors on linear colour (about their square root in sRGB, as seen)
const STYLES: Record<ProtectionKind, ProtectionStyle> = {
  tape: { scale: 1.04, rib: 0, shade: 0.7, band: 0.35, roughness: 0.45 },
  fleece_tape: { scale: 1.05, rib: 0, shade: 0.6, band: 0.5, roughness: 1 },
  corrugated_tube: { scale: 1.1, rib: 0.1, shade: 0.12, band: 1, roughness: 0.7 },
  sleeve: { scale: 1.07, rib: 0, shade: 0.3, band: 1, roughness: 1 },
  other: { scale: 1.06, rib: 0, shade: 0.45, band: 1, roughness: 0.8 },
};

/** The style of a kind (an unknown kind is drawn as `other`). */
export function protectionStyle(kind: string): ProtectionStyle {
  return STYLES[kind as ProtectionKind] ?? STYLES.other;
}

/**
 * The rings `[first, last]` of a tube of `rings` rings spread evenly over a hose of arc
 * length `length` that the stretch `from..to` [m] covers, at least two; null when the
 * stretch or the hose is empty.
 */
export function ringRange(from: number, to: number, length: number, rings: number): [number, number] | null {
  if (!(length > 0) || !(to > from) || rings < 2) return null;
  const at = (s: number) => Math.min(rings - 1, Math.max(0, Math.round((s / length) * (rings - 1))));
  let first = at(from);
  let last = at(to);
  if (last <= first) {
    if (first >= rings - 1) first = rings - 2;
    last = first + 1;
  }
  return [first, last];
}

/** Radius factor of ring `k` (counted along the hose) under `style`. */
export function ringScale(style: ProtectionStyle, k: number): number {
  return style.scale + (k % 2 === 1 ? style.rib : 0);
}

/** Shade of ring `k` under `style` (multiplies the hose's colour there). */
export function ringShade(style: ProtectionStyle, k: number): number {
  return style.shade * (k % 2 === 1 ? style.band : 1);
}

/**
 * Writes the protection's vertices for rings `first..last` of a tube with `radial + 1`
 * vertices per ring: each the tube's vertex `pos` pushed out from its ring's centre
 * (`centre`, one xyz per ring) by the ring's factor, coloured as the tube (`rgb`) by the
 * ring's shade. `out` and `outRgb` hold (last − first + 1) · (radial + 1) · 3 numbers.
 */
export function fillProtection(
  pos: ArrayLike<number>,
  rgb: ArrayLike<number>,
  centre: ArrayLike<number>,
  radial: number,
  first: number,
  last: number,
  style: ProtectionStyle,
  out: Float32Array,
  outRgb: Float32Array,
): void {
  const per = radial + 1;
  for (let k = first; k <= last; k++) {
    const f = ringScale(style, k);
    const shade = ringShade(style, k);
    const cx = centre[3 * k], cy = centre[3 * k + 1], cz = centre[3 * k + 2];
    for (let j = 0; j < per; j++) {
      const v = 3 * (k * per + j);
      const o = 3 * ((k - first) * per + j);
      out[o] = cx + (pos[v] - cx) * f;
      out[o + 1] = cy + (pos[v + 1] - cy) * f;
      out[o + 2] = cz + (pos[v + 2] - cz) * f;
      outRgb[o] = rgb[v] * shade;
      outRgb[o + 1] = rgb[v + 1] * shade;
      outRgb[o + 2] = rgb[v + 2] * shade;
    }
  }
}

/**
 * Triangle indices of a tube of `rings` rings with `radial + 1` vertices each, facing
 * outwards when each ring runs round the tangent anticlockwise (n → b, b = t × n, as the
 * hose sweep lays them): (a+1 − a) × (b − a) ∥ the outward radius.
 */
export function tubeIndices(rings: number, radial: number): number[] {
  const idx: number[] = [];
  for (let i = 0; i < rings - 1; i++) {
    for (let j = 0; j < radial; j++) {
      const a = i * (radial + 1) + j;
      const b = a + radial + 1;
      idx.push(a, a + 1, b, b, a + 1, b + 1);
    }
  }
  return idx;
}
