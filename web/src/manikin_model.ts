// What the viewer draws of the worker (pure, no three.js): the capsules of the posed
// body from a snapshot's `worker` and the welcome's segments and radii, which of them
// collide and with what, and the panel's lines — reach shortfall per arm, RULA, REBA and
// the posture class (docs/worker.md, docs/protocol.md).

import type { Vec3, WorkerData, WorkerSnapshot } from './protocol';

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
};

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
