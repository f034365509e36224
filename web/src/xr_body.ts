// The VR user's body for the worker (docs/worker.md): the headset's eyes and gaze and
// each controller's grip, by handedness, as a `worker_pose` message (world frame, m) —
// sent at most BODY_POSE_HZ times a second, and only in a scene with a worker.

import type { ClientMessage, Vec3 } from './protocol';

/** Most `worker_pose` messages a second. */
export const BODY_POSE_HZ = 20;

/** Whether a pose is due at `now` [ms] after the last one sent at `last` [ms]. */
export function bodyPoseDue(now: number, last: number): boolean {
  return now - last >= 1000 / BODY_POSE_HZ;
}

/** The `worker_pose` message: `eyes` and a point `ahead` on the gaze (null: no headset
 *  pose), and the controllers' grips with their handedness ('right', 'left'; others and
 *  untracked ones are left out). Null when there is nothing finite to send. */
export function bodyPoseMessage(
  eyes: Vec3 | null,
  ahead: Vec3 | null,
  grips: readonly { handedness: string; position: Vec3 | null }[],
): ClientMessage | null {
  const finite = (v: Vec3 | null): v is Vec3 => v !== null && v.every(Number.isFinite);
  let head: { position: Vec3; gaze: Vec3 } | undefined;
  if (finite(eyes) && finite(ahead)) {
    const gaze: Vec3 = [ahead[0] - eyes[0], ahead[1] - eyes[1], ahead[2] - eyes[2]];
    if (Math.hypot(...gaze) > 1e-9) head = { position: eyes, gaze };
  }
  const hand = (side: string): Vec3 | null => {
    const g = grips.find((h) => h.handedness === side);
    return g !== undefined && finite(g.position) ? g.position : null;
  };
  const hands: [Vec3 | null, Vec3 | null] = [hand('right'), hand('left')];
  if (head === undefined && hands[0] === null && hands[1] === null) return null;
  return head === undefined ? { type: 'worker_pose', hands } : { type: 'worker_pose', head, hands };
}
