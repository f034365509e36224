// Places along a hose by arc length: where a check's violation (its `arc_length` from the
// first node) lies on the hose as drawn. The drawn polyline through the nodes stands in
// for the rest length (hose strains are small). Pure logic: no DOM, no three.js.

import type { Vec3 } from './protocol';

/**
 * The point at arc length `s` [m] along the polyline through the nodes `xyz` (x, y, z
 * of each node, flattened), clamped to its ends; null without nodes.
 */
export function pointAtArcLength(xyz: ArrayLike<number>, s: number): Vec3 | null {
  const n = Math.floor(xyz.length / 3);
  if (n === 0) return null;
  const at = (i: number): Vec3 => [xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]];
  if (!(s > 0)) return at(0);
  let walked = 0;
  for (let i = 0; i + 1 < n; i++) {
    const dx = xyz[3 * i + 3] - xyz[3 * i];
    const dy = xyz[3 * i + 4] - xyz[3 * i + 1];
    const dz = xyz[3 * i + 5] - xyz[3 * i + 2];
    const l = Math.hypot(dx, dy, dz);
    if (l > 0 && walked + l >= s) {
      const t = (s - walked) / l;
      return [xyz[3 * i] + t * dx, xyz[3 * i + 1] + t * dy, xyz[3 * i + 2] + t * dz];
    }
    walked += l;
  }
  return at(n - 1);
}
