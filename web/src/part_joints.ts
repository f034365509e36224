// How each part of a session may move, read from its scene document (the `scene_source`
// answer's `document`, docs/scene-format.md "Parts that move"): a scripted hinge or slide
// `motion`, or a part inputs may move (`movable = true`, or moved by the timeline) with
// the hinge or slide its timeline's `rotate_part` / `move_part` actions describe. Also the
// part each stub, connector and clip sits on, and the mapping between a panel slider and a
// joint coordinate. Pure: no DOM, no three.js (unit-tested in node).

import type { PartPose, Vec3 } from './protocol';

/** A hinge: turns about `axis` (unit) through `point` [m] (null: the part's bounding-box
 *  centre) over `min`..`max` degrees from where the scene placed the part. A slide: moves
 *  along `direction` (unit) over `min`..`max` metres. */
export type Joint =
  | { kind: 'hinge'; axis: Vec3; point: Vec3 | null; min: number; max: number }
  | { kind: 'slide'; direction: Vec3; min: number; max: number };

/** One part that moves: its index in the welcome's `parts`, whether inputs may move it
 *  (`move_part` / `rotate_part`; a scripted `motion` may not be moved), and its joint
 *  when the scene describes one. */
export interface PartControl {
  part: number;
  name: string;
  movable: boolean;
  scripted: boolean;
  joint: Joint | null;
}

type Table = Record<string, unknown>;

const isTable = (x: unknown): x is Table => x !== null && typeof x === 'object' && !Array.isArray(x);
const tables = (x: unknown): Table[] => (Array.isArray(x) ? x.filter(isTable) : []);

/** A finite 3-vector, or null. */
function vec3(x: unknown): Vec3 | null {
  if (!Array.isArray(x) || x.length !== 3 || !x.every((c) => typeof c === 'number' && Number.isFinite(c))) return null;
  return [x[0], x[1], x[2]];
}

function unit(v: Vec3 | null): Vec3 | null {
  if (v === null) return null;
  const l = Math.hypot(v[0], v[1], v[2]);
  return l > 0 ? [v[0] / l, v[1] / l, v[2] / l] : null;
}

const scaled = (v: Vec3, s: number): Vec3 => [v[0] * s, v[1] * s, v[2] * s];

/** The keyframe values of `{ times_s, values }`, finite ones only. */
function keyframeValues(x: unknown): number[] {
  if (!isTable(x) || !Array.isArray(x.values)) return [];
  return x.values.filter((v): v is number => typeof v === 'number' && Number.isFinite(v));
}

/** The range spanned by 0 and `values`; `fallback` on each side when that is a point. */
function span(values: number[], fallback: number): { min: number; max: number } {
  const min = Math.min(0, ...values);
  const max = Math.max(0, ...values);
  return max - min > 0 ? { min, max } : { min: -fallback, max: fallback };
}

/** Degrees a hinge slider spans when the scene gives no angle but 0. */
export const DEFAULT_HINGE_RANGE_DEG = 90;
/** Metres a slide slider spans when the scene gives no travel but 0. */
export const DEFAULT_SLIDE_RANGE_M = 0.25;

/** The scripted joint of a `motion` table, lengths converted by `toMetres`. */
function scriptedJoint(motion: Table, toMetres: number): Joint | null {
  if (motion.kind === 'hinge') {
    const axis = unit(vec3(motion.axis));
    const point = vec3(motion.point);
    if (axis === null) return null;
    return { kind: 'hinge', axis, point: point === null ? null : scaled(point, toMetres), ...span(keyframeValues(motion.angle_deg), DEFAULT_HINGE_RANGE_DEG) };
  }
  if (motion.kind === 'slide') {
    const direction = unit(vec3(motion.direction));
    if (direction === null) return null;
    const r = span(keyframeValues(motion.distance), DEFAULT_SLIDE_RANGE_M / toMetres);
    return { kind: 'slide', direction, min: r.min * toMetres, max: r.max * toMetres };
  }
  return null;
}

/** The joint the timeline's actions on part `name` describe: the first `rotate_part`'s
 *  axis and point over the angles its `to_deg`s reach, else the first `move_part`'s
 *  direction over the distances its offsets reach. */
function timelineJoint(actions: Table[], name: string, toMetres: number): Joint | null {
  const own = actions.filter((a) => a.part === name);
  const turns = own.filter((a) => a.action === 'rotate_part');
  const first = turns.find((a) => unit(vec3(a.axis)) !== null);
  if (first !== undefined) {
    const axis = unit(vec3(first.axis)) as Vec3;
    const point = vec3(first.point);
    const angles = turns
      .filter((a) => { const u = unit(vec3(a.axis)); return u !== null && Math.abs(u[0] * axis[0] + u[1] * axis[1] + u[2] * axis[2]) > 1 - 1e-9; })
      .map((a) => {
        const u = unit(vec3(a.axis)) as Vec3;
        const sense = Math.sign(u[0] * axis[0] + u[1] * axis[1] + u[2] * axis[2]);
        return typeof a.to_deg === 'number' ? a.to_deg * sense : typeof a.by_deg === 'number' ? a.by_deg * sense : NaN;
      })
      .filter(Number.isFinite);
    return { kind: 'hinge', axis, point: point === null ? null : scaled(point, toMetres), ...span(angles, DEFAULT_HINGE_RANGE_DEG) };
  }
  const shifts = own.filter((a) => a.action === 'move_part').map((a) => vec3(a.to) ?? vec3(a.by)).filter((v): v is Vec3 => v !== null);
  const direction = unit(shifts.find((v) => unit(v) !== null) ?? null);
  if (direction === null) return null;
  const distances = shifts.map((v) => (v[0] * direction[0] + v[1] * direction[1] + v[2] * direction[2]) * toMetres);
  return { kind: 'slide', direction, ...span(distances, DEFAULT_SLIDE_RANGE_M) };
}

/** Metres per length unit of a scene document (`length_unit`, default mm). */
export function metresPerUnit(lengthUnit: string | undefined): number {
  return lengthUnit === 'm' ? 1 : 1e-3;
}

/**
 * The parts of `partNames` (the welcome's, in its order) that move, read from the scene
 * document `doc`. A part with a scripted `motion` is `scripted` (shown, not moved by
 * inputs); one with `movable = true` or moved by the timeline is `movable`.
 */
export function partControls(doc: unknown, lengthUnit: string | undefined, partNames: readonly string[]): PartControl[] {
  if (!isTable(doc)) return [];
  const toMetres = metresPerUnit(lengthUnit);
  const actions = tables(doc.timeline);
  const out: PartControl[] = [];
  for (const p of tables(doc.parts)) {
    if (typeof p.name !== 'string') continue;
    const index = partNames.indexOf(p.name);
    if (index < 0) continue;
    if (isTable(p.motion)) {
      out.push({ part: index, name: p.name, movable: false, scripted: true, joint: scriptedJoint(p.motion, toMetres) });
      continue;
    }
    const moved = actions.some((a) => a.part === p.name && (a.action === 'rotate_part' || a.action === 'move_part'));
    if (p.movable === true || moved) {
      out.push({ part: index, name: p.name, movable: true, scripted: false, joint: timelineJoint(actions, p.name, toMetres) });
    }
  }
  return out;
}

/**
 * For each fastener of `fasteners` (the welcome's, by name), the index into `partNames`
 * of the part it sits on (`part = "…"` in its `[[stubs]]`, `[[connectors]]` or
 * `[[clips]]` entry), or -1 when it stands in the world.
 */
export function fastenerCarriers(doc: unknown, fasteners: readonly { name: string }[], partNames: readonly string[]): number[] {
  const carrier = new Map<string, string>();
  if (isTable(doc)) {
    for (const list of [doc.stubs, doc.connectors, doc.clips]) {
      for (const f of tables(list)) if (typeof f.name === 'string' && typeof f.part === 'string') carrier.set(f.name, f.part);
    }
  }
  return fasteners.map((f) => {
    const part = carrier.get(f.name);
    return part === undefined ? -1 : partNames.indexOf(part);
  });
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
  | { type: 'rotate_part'; part: string; axis: Vec3; point?: Vec3; to_deg: number; duration_s: number }
  | { type: 'move_part'; part: string; to: Vec3; duration_s: number } {
  const speed = joint.kind === 'hinge' ? HINGE_SPEED_DEG_S : SLIDE_SPEED_M_S;
  const duration_s = Math.max(MIN_MOVE_S, Math.abs(x - from) / speed);
  if (joint.kind === 'hinge') {
    const m = { type: 'rotate_part' as const, part: name, axis: joint.axis, to_deg: x, duration_s };
    return joint.point === null ? m : { ...m, point: joint.point };
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
