// What the hoses are coloured by: the hand load (SPEC I4, one colour per
// hose), or per beam the bend radius against its minimum, the twist relative to the
// routed hose, the axial force — each mapped to a colour value c in [0, 1] (blue → green →
// red, colour.ts) over a range the legend shows with its unit. SI inside; display units
// (mm, °/m, N) only in the texts. Pure logic: no DOM, no three.js.

export type ColourMode = 'hand_load' | 'bend_radius' | 'twist' | 'axial_force';

export const COLOUR_MODES: readonly { id: ColourMode; label: string }[] = [
  { id: 'hand_load', label: 'hand load' },
  { id: 'bend_radius', label: 'bend radius vs minimum' },
  { id: 'twist', label: 'twist' },
  { id: 'axial_force', label: 'axial force' },
];

/** The per-beam fields of one hose in a snapshot (SI). */
export interface HoseFields {
  colour: number;
  bend_radius_ratio?: number[];
  twist?: number[];
  axial_force?: number[];
}

/**
 * A legend: the values at c = 0 and c = 1 (display units), the quantity's name, the
 * unit, and how a value (SI) maps to c. `signed`: c = 0.5 is zero (axial force).
 */
export interface LegendRange {
  mode: ColourMode;
  title: string;
  unit: string;
  /** Texts at the left end, middle and right end of the colour bar. */
  ticks: [string, string, string];
  /** SI value at c = 1 (and −value at c = 0 when signed). */
  scale: number;
  signed: boolean;
}

const TWIST_LIMIT_DEFAULT = (10 * Math.PI) / 180; // rad/m, the checks' default
/** Three significant digits, no trailing zeros. */
const fmt = (x: number) => String(Number(x.toPrecision(3)));

/**
 * The legend of `mode`. `twistLimit` [rad/m] (welcome; null: the default 10 °/m);
 * `axialScale` [N] the largest axial force magnitude to show (see `growAxialScale`).
 */
export function legendRange(mode: ColourMode, twistLimit: number | null | undefined, axialScale: number): LegendRange {
  switch (mode) {
    case 'hand_load':
      return { mode, title: 'hand load / limit', unit: '%', ticks: ['0', '50 %', '≥ 100 %'], scale: 1, signed: false };
    case 'bend_radius':
      return {
        mode, title: 'minimum / current bend radius', unit: 'R_min / R',
        ticks: ['0 (straight)', '0.5', '≥ 1 (at the minimum)'], scale: 1, signed: false,
      };
    case 'twist': {
      const limit = twistLimit != null && twistLimit > 0 ? twistLimit : TWIST_LIMIT_DEFAULT;
      const deg = (limit * 180) / Math.PI;
      return {
        mode, title: 'twist relative to the route', unit: '°/m',
        ticks: ['0', `${fmt(deg / 2)} °/m`, `≥ ${fmt(deg)} °/m (limit)`], scale: limit, signed: false,
      };
    }
    case 'axial_force': {
      const f = axialScale > 0 && Number.isFinite(axialScale) ? axialScale : 1;
      return {
        mode, title: 'axial force', unit: 'N',
        ticks: [`−${fmt(f)} N (compression)`, '0', `+${fmt(f)} N (tension)`], scale: f, signed: true,
      };
    }
  }
}

/** The colour value c ∈ [0, 1] of SI value `v` in `range` (non-finite: 1, red). */
export function colourValueOf(range: LegendRange, v: number): number {
  if (!Number.isFinite(v)) return 1;
  const x = range.signed ? 0.5 + (0.5 * v) / range.scale : Math.abs(v) / range.scale;
  return Math.min(Math.max(x, 0), 1);
}

/** The per-beam SI values `mode` colours hose `h` by, or null (one colour per hose). */
export function beamValues(mode: ColourMode, h: HoseFields): readonly number[] | null {
  switch (mode) {
    case 'hand_load': return null;
    case 'bend_radius': return h.bend_radius_ratio ?? null;
    case 'twist': return h.twist ?? null;
    case 'axial_force': return h.axial_force ?? null;
  }
}

/**
 * Colour values per node (length nodes) from per-beam values (length nodes − 1): a node
 * takes the worse (larger c) of its two beams, so that a short violation is not averaged
 * away. Writes into `out`; missing beams count as c = 0.
 */
export function nodeColourValues(range: LegendRange, beams: readonly number[], out: Float32Array): Float32Array {
  const n = out.length;
  for (let i = 0; i < n; i++) {
    const a = i > 0 && i - 1 < beams.length ? colourValueOf(range, beams[i - 1]) : 0;
    const b = i < beams.length && i < n - 1 ? colourValueOf(range, beams[i]) : 0;
    out[i] = range.signed ? pickSigned(a, b, i > 0 && i - 1 < beams.length, i < beams.length && i < n - 1) : Math.max(a, b);
  }
  return out;
}

/** Signed maps: the value farther from the middle (zero) wins. */
function pickSigned(a: number, b: number, hasA: boolean, hasB: boolean): number {
  if (!hasA) return hasB ? b : 0.5;
  if (!hasB) return a;
  return Math.abs(a - 0.5) >= Math.abs(b - 0.5) ? a : b;
}

/**
 * The axial-force legend's scale [N]: it grows to the largest |force| seen (rounded up to
 * 1, 2 or 5 × 10ⁿ, at least 1 N) and does not shrink, so that the colours do not flicker.
 */
export function growAxialScale(previous: number, hoses: readonly HoseFields[]): number {
  let m = 0;
  for (const h of hoses) for (const f of h.axial_force ?? []) if (Number.isFinite(f)) m = Math.max(m, Math.abs(f));
  if (m <= previous) return previous;
  return niceCeil(Math.max(m, 1));
}

/** The smallest 1, 2 or 5 × 10ⁿ ≥ x (x > 0). */
export function niceCeil(x: number): number {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  for (const k of [1, 2, 5, 10]) if (k * p >= x * (1 - 1e-12)) return k * p;
  return 10 * p;
}
