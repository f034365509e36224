// The messages of Pliant's protocol version 1 (docs/protocol.md), as TypeScript types.

import type { HoseFields } from './colour_modes';
import type { Grip } from './grips';

export type Vec3 = [number, number, number];
export type Quat = [number, number, number, number]; // x, y, z, w

export interface HoseData {
  name: string;
  radii: number[];
  /** The bend-radius check's minimum [m] (null: not checked). */
  min_bend_radius?: number | null;
  /** Arc length of the centre line [m]; the nodes lie at equal spacing along it. */
  length?: number;
  /** Protections over stretches of the hose. */
  protections?: ProtectionData[];
}
/** A protection over the stretch `from..to` of a hose (arc length, m). */
export interface ProtectionData {
  kind: 'tape' | 'fleece_tape' | 'corrugated_tube' | 'sleeve' | 'other';
  from: number;
  to: number;
}
/** A junction body: the hose ends it joins (hose index, node index of that end). */
export interface JunctionBodyData {
  name: string;
  mass: number;
  /** Centre of mass at rest [m] and inertia tensor about it (rows, world axes) [kg·m²];
   *  absent in recordings made before the welcome carried them. */
  centre_of_mass?: Vec3;
  inertia?: [Vec3, Vec3, Vec3];
  /** Whether the mass is lumped on the outlets (no centre of mass or inertia given). */
  lumped?: boolean;
  outlets: { hose: number; node: number }[];
  /** The part (index into `parts`) that is its shape, posed by the snapshot's
   *  `part_poses`; null or absent: no shape (drawn as a hub with arms). */
  shape?: number | null;
}
export interface PartData {
  name: string;
  bounds_min: Vec3;
  bounds_max: Vec3;
  vertices: number[];
  triangles: number[];
  /** How it moves (null: it stands still, or inputs move it freely); absent in
   *  recordings made before the welcome carried it. */
  joint?: JointData | null;
  /** The joint is its scripted `motion`: inputs cannot move it. */
  scripted?: boolean;
  /** Inputs (`move_part`, `rotate_part`, the timeline) may move it. */
  movable?: boolean;
  /** The part that carries it (index into the welcome's parts). */
  parent?: number | null;
}
/** One sine of a periodic motion: A sin(2π f t + φ). */
export interface Oscillation { amplitude: number; frequency: number; phase: number }
/** A part's joint (SI: m, rad, s; `range` from where the scene placed it, null: no end). */
export type JointData =
  | { kind: 'hinge'; axis: Vec3; point: Vec3; range: [number, number] | null }
  | { kind: 'slide'; direction: Vec3; range: [number, number] | null }
  | { kind: 'sampled_path'; centre: Vec3; time_range: [number, number] }
  | { kind: 'periodic'; centre: Vec3; translation: Oscillation[]; rotation: Oscillation[] };
export interface FastenerData {
  name: string;
  kind: 'stub' | 'connector' | 'clip';
  origin: Vec3;
  axis: Vec3;
  opening: Vec3;
  length: number;
  diameter: number;
  opening_width: number;
  /** The part it sits on and moves with (null or absent: it stands in the world). */
  part?: number | null;
}
export interface SceneData {
  scene: string;
  source: string;
  time_step: number;
  hoses: HoseData[];
  /** Junction bodies (welded branch points are not listed). */
  junction_bodies?: JunctionBodyData[];
  parts: PartData[];
  fasteners?: FastenerData[];
  ergonomics: string;
  /** The twist check's limit relative to the routed hose [rad/m] (null: not checked). */
  twist_limit?: number | null;
  limits: { max_message_bytes: number; max_messages_per_second: number; snapshot_hz: number; max_hands: number };
  /** The worker (`[worker]`): who, and per capsule its segment and radius [m]. */
  worker?: WorkerData;
}
/** The worker's fixed data: `segments[i]` has radius `radii[i]` and is the snapshot's
 *  capsule i. */
export interface WorkerData { who: string; stature: number; segments: string[]; radii: number[] }
/** The worker as last posed: capsule i's axis runs from capsules[6i..6i+3] to
 *  capsules[6i+3..6i+6] (world frame, m). */
export interface WorkerSnapshot {
  time: number;
  capsules: number[];
  /** Segments inside a part or hose now: `index` into the welcome's parts or hoses. */
  contacts: { segment: number; obstacle: 'part' | 'hose'; index: number; depth: number }[];
  /** Right arm, left arm: the hand followed and how far the grip stays short of it [m]. */
  arms: ({ hand: number; shortfall: number } | null)[];
  rula: number;
  reba: number;
  posture_class: 'upright' | 'bent_trunk' | 'arms_above_shoulder' | 'sitting' | 'sitting_bent_trunk';
  /** Where it stands: the floor point between the feet [m] and the unit direction it
   *  faces (absent in recordings made before the snapshot carried it). */
  stance?: { position: Vec3; forward: Vec3 };
  /** Steps taken so far. */
  steps?: number;
  /** A seated worker's seat as a box (absent: standing): its centre [m], its full lengths
   *  along the worker's forward, left and up directions [m], and those directions. */
  seat?: SeatBox;
}
export interface SeatBox { centre: Vec3; size: Vec3; forward: Vec3; up: Vec3 }
export interface Welcome { type: 'welcome'; version: number; client_id: number; session: SceneData }

export type LoadKind = 'push' | 'pull' | 'twist' | 'bending';
export interface HandSnapshot {
  hand_id: number;
  hose: number;
  /** How the hand holds the hose. */
  grip?: Grip;
  position: Vec3;
  orientation: Quat;
  target: Vec3;
  force: Vec3;
  torque: Vec3;
  ratio: number | null;
  kind: LoadKind | null;
  colour: number;
  force_kind?: LoadKind | null;
  force_limit?: number | null;
  force_ratio?: number | null;
  /** The moment with the larger ratio: twist (screwdriver row) or bending (T-handle row). */
  torque_kind?: LoadKind | null;
  torque_limit?: number | null;
  torque_ratio?: number | null;
}
export interface FastenerSnapshot {
  name: string;
  kind: 'stub' | 'connector' | 'clip';
  max_force: number;
  max_force_time: number;
  final_state: string;
  assembled: boolean;
  force?: number;
}
export interface ErgonomicProfile {
  push_posture: string;
  pull_posture: string;
  moments_decide: boolean;
  population: string;
  duty: string;
}
export interface RunningVerdict {
  feasible: boolean | null; reasons: string[]; pending: string[]; warnings?: string[];
  /** The same lines as data, list by list (docs/protocol.md, "The verdict's findings"). */
  findings?: VerdictFindings;
}
/** A verdict's lines as data: `reasons[i]` is the verdict's `reasons[i]`, and so on. */
export interface VerdictFindings {
  reasons: VerdictLine[]; pending: VerdictLine[]; warnings: VerdictLine[]; zones: VerdictLine[];
  worker?: VerdictLine[];
}
export type FastenerKind = 'stub' | 'connector' | 'clip';
/** The fastener a hand worked at its worst moment. */
export interface WorkedFastener { fastener: FastenerKind; name: string }
/** A hand's load against its limit value (SI), `ratio` = value / limit. */
export interface LoadAgainstLimit { hand: number; load: LoadKind; value: number; limit: number; ratio: number; time: number }
/** One line of a verdict, by its `kind`; the fields not typed here are in docs/protocol.md. */
export type VerdictLine =
  | { kind: 'solver'; doubt: 'out_of_balance' | 'unstable' | 'rolled_back'; [field: string]: unknown }
  | { kind: 'stopped_early'; message: string }
  | { kind: 'hand_force_zone'; hand: number; zone: { kind: LoadKind; magnitude: number; time: number; [field: string]: unknown }; working?: WorkedFastener }
  | ({ kind: 'hand_load_over_limit'; working?: WorkedFastener } & LoadAgainstLimit)
  | { kind: 'moment_above_guide'; hand: number; load: LoadKind; value: number; time: number; guide_hi: number; limit: number; moments_decide: boolean }
  | { kind: 'fastener_not_fitted'; fastener: FastenerKind; name: string; final_state: string }
  | { kind: 'fastener_pending'; fastener: FastenerKind; name: string; state: string }
  | { kind: 'check_violated'; violation: CheckViolation; position?: string }
  | { kind: 'clearance_violated'; hose: string; part: string; gap: number; minimum: number; time: number; coordinate: number; position: string }
  | { kind: 'worker'; finding: { kind: 'out_of_reach' | 'collision'; who: string; time: number; [field: string]: unknown } }
  | { kind: 'posture'; who: string; rula: { score: unknown; time: number }; reba: { score: unknown; time: number } }
  | { kind: 'not_posed'; who: string }
  | { kind: 'motion_extremes'; coordinate: { part: number; part_name: string; kind: string }; from: number; to: number;
      bend_radii: { hose: string; radius: number; allowed: number; coordinate: number }[];
      clearance?: { hose: string; part: string; gap: number; coordinate: number } }
  | { kind: 'contact'; part: string; first_time: number; last_time: number }
  | { kind: 'instability'; note: 'snapped_through' | 'buckled' | 'more' | 'explicit_fallback'; [field: string]: unknown }
  | { kind: 'within_limits'; standard: string; checks: string[]; reached?: string }
  | { kind: 'within_limits_so_far'; worst?: LoadAgainstLimit }
  | { kind: 'checks_passed'; stage: 'running' | 'final' }
  | { kind: 'no_hand_acted'; stage: 'running' | 'final' };
export interface Snapshot {
  type: 'snapshot';
  time: number;
  step: number;
  paused: boolean;
  real_time_factor: number;
  epoch: number;
  /** Per hose: node positions, the hand-load colour value and per-beam fields (SI). */
  hoses: (HoseFields & { positions: Vec3[]; asleep?: boolean })[];
  /** The parts that move (a scripted motion, or moved by `move_part` / `rotate_part`):
   * each part's mesh, sent where the scene placed it, is drawn at rotation · x + translation. */
  part_poses?: PartPose[];
  /** The worker as last posed (absent without a worker). */
  worker?: WorkerSnapshot;
  hands: HandSnapshot[];
  fasteners: FastenerSnapshot[];
  ergonomics?: ErgonomicProfile;
  verdict?: RunningVerdict;
  /** Violations of the running installation checks (bend radius, twist), SI units. */
  checks?: CheckViolation[];
  notice?: string;
}
/** Where a moving part is: `part` indexes the welcome's `parts`; rotation is [x, y, z, w]. */
export interface PartPose { part: number; translation: Vec3; rotation: [number, number, number, number] }
export interface CheckViolation {
  check: 'bend_radius' | 'twist' | 'tension_at_rest' | 'straight_behind_stub';
  hose: number; hose_name: string; arc_length: number; time: number;
  value: number; limit: number; first_time: number; last_time: number; instants: number;
  at: string | null;
}
export interface ErrorMessage { type: 'error'; code: string; message: string }
/** The answer to `report`: the folder the report was written to and its verdict. */
export interface ReportMessage { type: 'report'; folder: string; verdict: { feasible: boolean | null; reasons: string[]; pending: string[]; findings?: VerdictFindings } }
/** One built-in library hose (SI). */
export interface LibraryHose { name: string; description: string; d_inner: number; d_outer: number; min_bend_radius: number }
/** The answer to `scene_source`: the session's scene file as a document to edit. */
export interface SceneSourceMessage {
  type: 'scene_source';
  scene: string;
  source: string;
  length_unit: 'mm' | 'm';
  text: string;
  document: unknown;
  library: LibraryHose[];
}
export type ServerMessage = Welcome | Snapshot | ErrorMessage | ReportMessage | SceneSourceMessage;

export type ClientMessage =
  | { type: 'hello'; version: 1 }
  | { type: 'grab'; hand_id: number; position: Vec3; grip?: Grip }
  | { type: 'move'; hand_id: number; position: Vec3; orientation?: Quat }
  | { type: 'release'; hand_id: number }
  | { type: 'worker_pose'; head?: { position: Vec3; gaze: Vec3 }; hands: [Vec3 | null, Vec3 | null] }
  | { type: 'move_part'; part: string; by?: Vec3; to?: Vec3; duration_s: number }
  | { type: 'rotate_part'; part: string; axis: Vec3; point?: Vec3; by_deg?: number; to_deg?: number; duration_s: number }
  | { type: 'pause' }
  | { type: 'resume' }
  | { type: 'step'; n: number }
  | { type: 'reset' }
  | { type: 'set_ergonomics'; posture?: string; population?: string; duty?: string; moments_decide?: boolean }
  | { type: 'load_scene'; text: string; format?: 'toml' | 'json'; name?: string }
  | { type: 'report' }
  | { type: 'scene_source' };

/** |v| */
export function norm(v: readonly number[]): number {
  let s = 0;
  for (const x of v) s += x * x;
  return Math.sqrt(s);
}
