// A junction body's pose from its outlets (pure, no three.js): the body sits at the mean
// of its outlet nodes, an arm reaching out to each outlet. A body without a shape of its
// own (`body.part` in the scene) is drawn as this hub with arms; a body with one is drawn
// as that part, at the pose the snapshot's `part_poses` give it.

import type { Vec3 } from './protocol';

export interface JunctionPose {
  centre: Vec3;
  /** Per outlet: unit direction from the centre and distance to it [m]. */
  arms: { direction: Vec3; length: number }[];
}

/** The pose of a body whose outlets sit at `outlets` (world frame, m). */
export function junctionPose(outlets: Vec3[]): JunctionPose {
  const n = Math.max(outlets.length, 1);
  const centre: Vec3 = [0, 0, 0];
  for (const p of outlets) for (let d = 0; d < 3; d++) centre[d] += p[d] / n;
  const arms = outlets.map((p) => {
    const v: Vec3 = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
    const length = Math.hypot(v[0], v[1], v[2]);
    const direction: Vec3 = length > 0 ? [v[0] / length, v[1] / length, v[2] / length] : [0, 0, 1];
    return { direction, length };
  });
  return { centre, arms };
}

/** Radius of the hub [m]: a third more than the thickest outlet's, at least 2 mm. */
export function hubRadius(outletRadii: number[]): number {
  return Math.max(0.002, 1.35 * Math.max(0, ...outletRadii));
}

/** Whether a junction body is drawn as a hub with arms: only when it has no shape of its
 *  own (a body with one is drawn as its part, posed by the snapshot). */
export function drawnAsHub(body: { shape?: number | null }): boolean {
  return body.shape === undefined || body.shape === null;
}
