// What the viewer draws of the worker (pure, no three.js): the capsules of the posed
// body from a snapshot's `worker` and the welcome's segments and radii, which of them
// collide and with what, and the panel's lines — reach shortfall per arm, RULA, REBA and
// the posture class (docs/worker.md, docs/protocol.md); a seated worker's seat as a box.

import type { SeatBox, Vec3, WorkerData, WorkerSnapshot } from './protocol';

/** One capsule to draw: the axis a–b and radius [m]; `contact` what it is inside now. */
export interface ManikinCapsule {
  segment: string;
  a: Vec3;
  b: Vec3;
  radius: number;
  contact: { obstacle: 'part' | 'hose'; name: string; depth: number } | null;
}

/** A grip this far short of its hand [m] or more is out of reach (the verdict's 1 mm). */
export const REACH_TOLERANCE = 1e-3;

const CLASS_WORDS: Record<WorkerSnapshot['posture_class'], string> = {
  upright: 'standing upright',
  bent_trunk: 'bent trunk',
  arms_above_shoulder: 'arms above shoulder',
  sitting: 'sitting',
  sitting_bent_trunk: 'sitting with bent trunk',
};

/** The seat to draw: the snapshot's box with its left direction (up × forward), or null
 *  for a standing worker or a box that is not finite, has a size not above zero, or
 *  directions that are not unit vectors at right angles (to 1e-6). */
export function seatBox(pose: WorkerSnapshot | undefined): (SeatBox & { left: Vec3 }) | null {
  const s = pose?.seat;
  if (s === undefined || s === null) return null;
  const all = [...s.centre, ...s.size, ...s.forward, ...s.up];
  if (all.length !== 12 || !all.every(Number.isFinite) || !s.size.every((x) => x > 0)) return null;
  const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const unit = (a: Vec3) => Math.abs(dot(a, a) - 1) < 1e-6;
  if (!unit(s.forward) || !unit(s.up) || Math.abs(dot(s.forward, s.up)) > 1e-6) return null;
  const [f, u] = [s.forward, s.up];
  const left: Vec3 = [u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]];
  return { centre: s.centre, size: s.size, forward: f, up: u, left };
}

/** The capsules of `pose` for the body `data`; `names` the welcome's part and hose
 *  names. A pose that does not fit the body (wrong count, a non-finite number) draws
 *  nothing: an empty list. */
export function manikinCapsules(
  data: WorkerData,
  pose: WorkerSnapshot,
  names: { parts: readonly string[]; hoses: readonly string[] },
): ManikinCapsule[] {
  const n = data.segments.length;
  if (data.radii.length !== n || pose.capsules.length !== 6 * n) return [];
  if (!pose.capsules.every(Number.isFinite) || !data.radii.every((r) => Number.isFinite(r) && r >= 0)) return [];
  const c = pose.capsules;
  const out: ManikinCapsule[] = data.segments.map((segment, i) => ({
    segment,
    a: [c[6 * i], c[6 * i + 1], c[6 * i + 2]],
    b: [c[6 * i + 3], c[6 * i + 4], c[6 * i + 5]],
    radius: data.radii[i],
    contact: null,
  }));
  for (const k of pose.contacts) {
    const cap = out[k.segment];
    if (cap === undefined) continue;
    if (cap.contact !== null && cap.contact.depth >= k.depth) continue;
    const list = k.obstacle === 'hose' ? names.hoses : names.parts;
    cap.contact = { obstacle: k.obstacle, name: list[k.index] ?? `${k.obstacle} ${k.index}`, depth: k.depth };
  }
  return out;
}

/** The panel's lines for the worker: who and the scores, then each arm's reach, then
 *  each segment inside something. */
export function manikinLines(data: WorkerData, pose: WorkerSnapshot | undefined, capsules: readonly ManikinCapsule[]): string[] {
  if (pose === undefined) return [`${data.who}: not posed yet`];
  const lines = [`${data.who} at t = ${pose.time.toFixed(2)} s: RULA ${pose.rula}, REBA ${pose.reba}, ${CLASS_WORDS[pose.posture_class] ?? pose.posture_class}`];
  const seat = seatBox(pose);
  if (seat !== null) lines.push(`seated, the seat ${(1e3 * seat.size[2]).toFixed(0)} mm high`);
  ['right', 'left'].forEach((side, i) => {
    const arm = pose.arms[i];
    if (arm === null || arm === undefined) return;
    lines.push(
      arm.shortfall >= REACH_TOLERANCE
        ? `${side} arm: hand ${arm.hand} out of reach by ${(1e3 * arm.shortfall).toFixed(0)} mm`
        : `${side} arm: hand ${arm.hand} reached`,
    );
  });
  for (const c of capsules) {
    if (c.contact === null) continue;
    const what = c.contact.obstacle === 'hose' ? `hose '${c.contact.name}'` : `'${c.contact.name}'`;
    lines.push(`${c.segment} ${(1e3 * c.contact.depth).toFixed(0)} mm inside ${what}`);
  }
  return lines;
}

/** How long the viewer takes to draw a step [s]: the body glides from the stance it left
 *  to the new one (the simulation moves it at once; this only shows the way it went). */
export const STEP_DRAW_S = 0.5;

/** Whether the worker took a step or turned between two snapshots: its step count or its
 *  stance changed. Snapshots without a stance (old recordings) never step. */
export function stepped(before: WorkerSnapshot | undefined, after: WorkerSnapshot | undefined): boolean {
  if (before?.stance === undefined || after?.stance === undefined) return false;
  if ((before.steps ?? 0) !== (after.steps ?? 0)) return true;
  const a = before.stance;
  const b = after.stance;
  return [0, 1, 2].some((k) => a.position[k] !== b.position[k] || a.forward[k] !== b.forward[k]);
}

/** The capsules drawn a fraction `f` (0..1, clamped) through a step from `from` to `to`:
 *  every end point on the straight line between, with a smooth start and stop
 *  (3f² − 2f³). Lists of different lengths (another body): `to`. */
export function glide(from: readonly ManikinCapsule[], to: readonly ManikinCapsule[], f: number): ManikinCapsule[] {
  if (from.length !== to.length) return to.slice();
  const g = Math.min(1, Math.max(0, Number.isFinite(f) ? f : 1));
  const s = g * g * (3 - 2 * g);
  const mix = (p: Vec3, q: Vec3): Vec3 => [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2])];
  return to.map((c, i) => ({ ...c, a: mix(from[i].a, c.a), b: mix(from[i].b, c.b) }));
}
