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
