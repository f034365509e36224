// Where and how a protection (tape, corrugated tube, sleeve) is drawn over a hose tube:
// pure functions over the tube's ring arrays (no three.js), so the unit tests can run them.
// A protection is a second, slightly larger tube over the rings of its stretch: its
// vertices are the hose tube's pushed out from the ring centres by a factor per ring.

export type ProtectionKind = 'tape' | 'fleece_tape' | 'corrugated_tube' | 'sleeve' | 'other';

/** How one kind looks: radius factor, rib depth (every other ring), colour, bands. */
export interface ProtectionStyle {
  /** Radius over the bundle's, as a factor. */
  scale: number;
  /** Extra radius factor of every other ring (the ribs of a corrugated tube). */
  rib: number;
  colour: number;
  roughness: number;
  /** Shade of every other ring (1: no bands; tape shows its windings as bands). */
  band: number;
}

const STYLES: Record<ProtectionKind, ProtectionStyle> = {
  tape: { scale: 1.04, rib: 0, colour: 0x3a3a3a, roughness: 0.45, band: 0.7 },
  fleece_tape: { scale: 1.05, rib: 0, colour: 0x55524c, roughness: 1, band: 0.8 },
  corrugated_tube: { scale: 1.1, rib: 0.1, colour: 0x1c1c1c, roughness: 0.7, band: 1 },
  sleeve: { scale: 1.07, rib: 0, colour: 0x2e3a48, roughness: 1, band: 1 },
  other: { scale: 1.06, rib: 0, colour: 0x5a5040, roughness: 0.8, band: 1 },
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

/** Shade of ring `k` under `style` (multiplies its colour). */
export function ringShade(style: ProtectionStyle, k: number): number {
  return k % 2 === 1 ? style.band : 1;
}

/**
 * Writes the protection's vertices for rings `first..last` of a tube with `radial + 1`
 * vertices per ring: each the tube's vertex `pos` pushed out from its ring's centre
 * (`centre`, one xyz per ring) by the ring's factor. `out` holds (last − first + 1) ·
 * (radial + 1) · 3 numbers.
 */
export function fillProtection(
  pos: ArrayLike<number>,
  centre: ArrayLike<number>,
  radial: number,
  first: number,
  last: number,
  style: ProtectionStyle,
  out: Float32Array,
): void {
  const per = radial + 1;
  for (let k = first; k <= last; k++) {
    const f = ringScale(style, k);
    const cx = centre[3 * k], cy = centre[3 * k + 1], cz = centre[3 * k + 2];
    for (let j = 0; j < per; j++) {
      const v = 3 * (k * per + j);
      const o = 3 * ((k - first) * per + j);
      out[o] = cx + (pos[v] - cx) * f;
      out[o + 1] = cy + (pos[v + 1] - cy) * f;
      out[o + 2] = cz + (pos[v + 2] - cz) * f;
    }
  }
}

/** Triangle indices of a tube of `rings` rings with `radial + 1` vertices each. */
export function tubeIndices(rings: number, radial: number): number[] {
  const idx: number[] = [];
  for (let i = 0; i < rings - 1; i++) {
    for (let j = 0; j < radial; j++) {
      const a = i * (radial + 1) + j;
      const b = a + radial + 1;
      idx.push(a, b, a + 1, b, b + 1, a + 1);
    }
  }
  return idx;
}
