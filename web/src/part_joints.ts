// How each part of a session may move, as the welcome tells (docs/protocol.md "welcome":
// each part's `joint`, `scripted`, `movable` and `parent`, each fastener's `part`): the
// hinge or slide a panel slider drives, with its range, and the mapping between a slider
// and a joint coordinate. Pure: no DOM, no three.js (unit-tested in node).

import type { FastenerData, JointData, PartData, PartPose, Vec3 } from './protocol';

/** A hinge: turns about `axis` (unit) through `point` [m] over `min`..`max` degrees from
 *  where the scene placed the part. A slide: moves along `direction` (unit) over
 *  `min`..`max` metres. */
export type Joint =
  | { kind: 'hinge'; axis: Vec3; point: Vec3; min: number; max: number }
  | { kind: 'slide'; direction: Vec3; min: number; max: number };

/** One part that moves: its index in the welcome's `parts`, whether inputs may move it
 *  (`move_part` / `rotate_part`; a scripted `motion` may not be moved), its hinge or
 *  slide when it has one, and in words how it moves otherwise. */
export interface PartControl {
  part: number;
  name: string;
  movable: boolean;
  scripted: boolean;
  joint: Joint | null;
  /** A scripted motion without a slider ("periodic motion, 25 Hz"); '' otherwise. */
  motion: string;
}

/** Degrees a hinge slider spans (either way) when the welcome gives no angle but 0. */
export const DEFAULT_HINGE_RANGE_DEG = 90;
/** Metres a slide slider spans (either way) when the welcome gives no travel but 0. */
export const DEFAULT_SLIDE_RANGE_M = 0.25;

const DEG = 180 / Math.PI;

const scaled = (v: Vec3, s: number): Vec3 => [v[0] * s, v[1] * s, v[2] * s];

/** A welcome's range, or ±`fallback` when it has none or is a point. */
function span(range: readonly [number, number] | null | undefined, scale: number, fallback: number): { min: number; max: number } {
  if (range === null || range === undefined || !(range[1] - range[0] > 0)) return { min: -fallback, max: fallback };
  return { min: range[0] * scale, max: range[1] * scale };
}

/** The slider joint of a welcome's joint (hinge range in degrees), or null for a sampled
 *  path or a periodic motion. */
function sliderJoint(j: JointData): Joint | null {
  if (j.kind === 'hinge') return { kind: 'hinge', axis: j.axis, point: j.point, ...span(j.range, DEG, DEFAULT_HINGE_RANGE_DEG) };
  if (j.kind === 'slide') return { kind: 'slide', direction: j.direction, ...span(j.range, 1, DEFAULT_SLIDE_RANGE_M) };
  return null;
}

/** A sampled path or periodic motion in words. */
function motionText(j: JointData): string {
  if (j.kind === 'sampled_path') return `sampled path, ${j.time_range[0].toFixed(2)} … ${j.time_range[1].toFixed(2)} s`;
  if (j.kind === 'periodic') {
    const f = [...j.translation, ...j.rotation].filter((o) => o.amplitude !== 0).map((o) => o.frequency);
    const hz = [...new Set(f)].map((x) => `${x} Hz`).join(', ');
    return hz === '' ? 'periodic motion' : `periodic motion, ${hz}`;
  }
  return '';
}

/**
 * The parts of the welcome's `parts` that move: a part with a scripted `motion` is
 * `scripted` (shown, not moved by inputs); one inputs may move is `movable`. A part that
 * only moves with its parent has no row.
 */
export function partControls(parts: readonly PartData[]): PartControl[] {
  const out: PartControl[] = [];
  parts.forEach((p, part) => {
    const scripted = p.scripted === true && p.joint !== null && p.joint !== undefined;
    const movable = p.movable === true;
    if (!scripted && !movable) return;
    const j = p.joint ?? null;
    out.push({ part, name: p.name, movable, scripted, joint: j === null ? null : sliderJoint(j), motion: j === null ? '' : motionText(j) });
  });
  return out;
}

/** For each of the welcome's `fasteners`, the index of the part it sits on (its `part`),
 *  or -1 when it stands in the world. */
export function fastenerCarriers(fasteners: readonly FastenerData[]): number[] {
  return fasteners.map((f) => f.part ?? -1);
}

/** Slider positions from one end of a joint's range to the other. */
export const SLIDER_STEPS = 1000;

/** The joint coordinate (degrees or metres) at slider position `v` (0..SLIDER_STEPS). */
export function sliderToCoordinate(joint: Joint, v: number): number {
  const f = Math.min(1, Math.max(0, v / SLIDER_STEPS));
  return joint.min + f * (joint.max - joint.min);
}

/** The slider position (0..SLIDER_STEPS, rounded, clamped) showing coordinate `x`. */
export function coordinateToSlider(joint: Joint, x: number): number {
  const f = (x - joint.min) / (joint.max - joint.min);
  return Math.round(Math.min(1, Math.max(0, Number.isFinite(f) ? f : 0)) * SLIDER_STEPS);
}

/** The joint coordinate of a part at `pose` (null: where the scene placed it): a hinge's
 *  turn about its axis [deg, in (−180, 180]] — 2·atan2(q⃗·â, w) —, a slide's travel along
 *  its direction [m]. */
export function coordinateOfPose(joint: Joint, pose: PartPose | null): number {
  if (pose === null) return 0;
  if (joint.kind === 'hinge') {
    const [x, y, z, w] = pose.rotation;
    const a = joint.axis;
    let deg = (2 * Math.atan2(x * a[0] + y * a[1] + z * a[2], w) * 180) / Math.PI;
    if (deg > 180) deg -= 360;
    if (deg <= -180) deg += 360;
    return deg;
  }
  const t = pose.translation;
  const d = joint.direction;
  return t[0] * d[0] + t[1] * d[1] + t[2] * d[2];
}

/** The joint coordinate a handle dragged from coordinate `start` reaches, clamped to
 *  the joint's range: plus the drag's turn about the hinge axis (`turn` [x, y, z, w],
 *  world frame), or plus its shift along the slide (`shift` [m]). */
export function draggedCoordinate(joint: Joint, start: number, turn: readonly [number, number, number, number], shift: Vec3): number {
  const by =
    joint.kind === 'hinge'
      ? coordinateOfPose(joint, { part: 0, translation: [0, 0, 0], rotation: [turn[0], turn[1], turn[2], turn[3]] })
      : shift[0] * joint.direction[0] + shift[1] * joint.direction[1] + shift[2] * joint.direction[2];
  return Math.min(joint.max, Math.max(joint.min, start + by));
}

/** Turning speed of a slider-driven hinge [deg/s] and travel speed of a slide [m/s]: a
 *  door swung by hand. */
export const HINGE_SPEED_DEG_S = 90;
export const SLIDE_SPEED_M_S = 0.25;
/** The shortest move a slider sends [s] (moves must not jump). */
export const MIN_MOVE_S = 0.1;

/** The `rotate_part` / `move_part` message that takes part `name` to coordinate `x` of its
 *  joint, from `from`, at the joint's speed. */
export function jointMessage(name: string, joint: Joint, x: number, from: number):
  | { type: 'rotate_part'; part: string; axis: Vec3; point: Vec3; to_deg: number; duration_s: number }
  | { type: 'move_part'; part: string; to: Vec3; duration_s: number } {
  const speed = joint.kind === 'hinge' ? HINGE_SPEED_DEG_S : SLIDE_SPEED_M_S;
  const duration_s = Math.max(MIN_MOVE_S, Math.abs(x - from) / speed);
  if (joint.kind === 'hinge') {
    return { type: 'rotate_part', part: name, axis: joint.axis, point: joint.point, to_deg: x, duration_s };
  }
  return { type: 'move_part', part: name, to: scaled(joint.direction, x), duration_s };
}

/** Where a point `p` given in a part's reference placement is at `pose`: R·p + t. */
export function carry(pose: PartPose, p: Vec3): Vec3 {
  const [qx, qy, qz, qw] = pose.rotation;
  // v' = v + 2w (q⃗ × v) + 2 q⃗ × (q⃗ × v)
  const cx = qy * p[2] - qz * p[1];
  const cy = qz * p[0] - qx * p[2];
  const cz = qx * p[1] - qy * p[0];
  return [
    p[0] + 2 * (qw * cx + qy * cz - qz * cy) + pose.translation[0],
    p[1] + 2 * (qw * cy + qz * cx - qx * cz) + pose.translation[1],
    p[2] + 2 * (qw * cz + qx * cy - qy * cx) + pose.translation[2],
  ];
}

type Quat = readonly [number, number, number, number];

/** The Hamilton product a·b of unit quaternions [x, y, z, w]. */
function product(a: Quat, b: Quat): [number, number, number, number] {
  return [
    a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
    a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
    a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
    a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
  ];
}

const conjugate = (q: Quat): [number, number, number, number] => [-q[0], -q[1], -q[2], q[3]];

/** `v` turned by the unit quaternion `q`: R(q)·v. */
export function turned(q: Quat, v: Vec3): Vec3 {
  return carry({ part: 0, translation: [0, 0, 0], rotation: [q[0], q[1], q[2], q[3]] }, v);
}

/** A child part's own pose — its motion in its parent's reference placement, the frame
 *  its joint is given in — from its world pose and its parent's (null: the parent stands
 *  where the scene placed it). The server composes P = P_parent ∘ P_own (docs/scene-format.md,
 *  "Parts that move"), so P_own = P_parent⁻¹ ∘ P: q_own = q_p⁻¹ q, t_own = R_p⁻¹ (t − t_p). */
export function ownPose(pose: PartPose, parent: PartPose | null): PartPose {
  if (parent === null) return pose;
  const inverse = conjugate(parent.rotation);
  const t = pose.translation;
  const tp = parent.translation;
  return {
    part: pose.part,
    translation: turned(inverse, [t[0] - tp[0], t[1] - tp[1], t[2] - tp[2]]),
    rotation: product(inverse, pose.rotation),
  };
}

/** A handle's drag seen from a child's parent (null: the parent at rest): the world turn
 *  `turn` as R_p⁻¹ turn R_p and the world shift as R_p⁻¹ shift, so that they compare with
 *  the child's joint, which is given in the parent's frame. */
export function dragInParent(
  parent: PartPose | null,
  turn: Quat,
  shift: Vec3,
): { turn: [number, number, number, number]; shift: Vec3 } {
  if (parent === null) return { turn: [turn[0], turn[1], turn[2], turn[3]], shift };
  const inverse = conjugate(parent.rotation);
  return { turn: product(product(inverse, turn), parent.rotation), shift: turned(inverse, shift) };
}
