// Where the scene goes in an immersive session (pure, no three.js). Both sessions use the
// `local-floor` reference space: y = 0 is the real floor under the user, who looks down
// −z. In VR the scene's centre floats at working height (1 m) 0.6 m in front of the user;
// in AR the scene stands on the real floor — its lowest point (the ground under the parts
// and hoses) at y = 0 — with its centre 1.2 m in front, so that the user walks round it.

import type { Vec3 } from './protocol';

export type XrMode = 'immersive-vr' | 'immersive-ar';

/** VR: the height of the scene's centre above the floor [m]. */
export const VR_HEIGHT = 1.0;
/** VR, AR: how far in front of the user the scene's centre is [m]. */
export const VR_DISTANCE = 0.6;
export const AR_DISTANCE = 1.2;

/** The offset of the world group in `mode`, for the scene's centre `centre` and its
 *  lowest height `lowest` (three.js space, y up, with the group at the origin). */
export function xrOffset(mode: XrMode, centre: Vec3, lowest: number): Vec3 {
  if (mode === 'immersive-ar') return [-centre[0], -lowest, -AR_DISTANCE - centre[2]];
  return [-centre[0], VR_HEIGHT - centre[1], -VR_DISTANCE - centre[2]];
}

// AR on a real table or floor (WebXR Hit Test Module): the viewer's ray meets a real
// surface, a reticle shows where; on select the scene's lowest point is put there, its
// centre straight above the hit. Only surfaces that face up count (a hit pose's y axis
// is the surface normal). Without hit test the floor placement above stays.

/** A hit counts as a table or floor when its normal is within this angle of the
 *  vertical [rad] (15°). */
export const MAX_SURFACE_TILT = (15 * Math.PI) / 180;

/** The surface normal of a hit pose of orientation `q` = [x, y, z, w]: the pose's y axis
 *  (the quaternion applied to (0, 1, 0)). */
export function hitNormal(q: readonly [number, number, number, number]): Vec3 {
  const [x, y, z, w] = q;
  return [2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)];
}

/** Whether a hit pose of orientation `q` lies on a surface facing up (a table, the floor):
 *  its normal within MAX_SURFACE_TILT of the vertical. */
export function facesUp(q: readonly [number, number, number, number]): boolean {
  const n = hitNormal(q);
  const length = Math.hypot(n[0], n[1], n[2]);
  return length > 0 && n[1] / length >= Math.cos(MAX_SURFACE_TILT);
}

/** The offset of the world group that puts the scene's lowest point (height `lowest`) on
 *  the surface at `hit` with its centre `centre` straight above it (three.js space, y up,
 *  the group at the origin). */
export function hitOffset(centre: Vec3, lowest: number, hit: Vec3): Vec3 {
  return [hit[0] - centre[0], hit[1] - lowest, hit[2] - centre[2]];
}
