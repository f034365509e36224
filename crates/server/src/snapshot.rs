//! What clients see: the static scene data sent once in `welcome`, and the snapshot of the
//! newest consistent state the simulation thread published (SPEC I2, I4, I6).

use crate::joints::PartMotionData;
use pliant_assembly::stub::AxialLaw;
use pliant_assembly::{ClipSite, StubSite};
use pliant_core::{HoseEnd, Model};
use pliant_scene::protections::ProtectionSpan;
use pliant_scene::LoadedScene;
use serde::Serialize;
use std::sync::OnceLock;

/// Static data of the session (sent once, in `welcome`).
#[derive(Clone, Debug, Serialize)]
pub struct SceneData {
    pub scene: String,
    pub source: String,
    /// Integrator time step \[s\].
    pub time_step: f64,
    pub hoses: Vec<HoseData>,
    /// The junction bodies (moulded T and Y pieces joining hose ends; welded branch
    /// points are not listed): each drawn where its outlets are in every snapshot.
    pub junction_bodies: Vec<JunctionBodyData>,
    pub parts: Vec<PartData>,
    /// Stubs and clips: where they are, for drawing (same order as the snapshot's
    /// `fasteners`).
    pub fasteners: Vec<FastenerData>,
    /// The ergonomic profile hand loads are judged with.
    pub ergonomics: String,
    /// The twist check's limit relative to the routed hose [rad/m] (`null`: not checked).
    pub twist_limit: Option<f64>,
    pub limits: LimitsData,
    /// The worker (`[worker]`, docs/worker.md): who, and the segments of the body the
    /// snapshot's `worker` poses; absent without a worker.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worker: Option<WorkerData>,
}

/// The worker's fixed data: who, and per capsule its segment and radius.
#[derive(Clone, Debug, Serialize)]
pub struct WorkerData {
    /// "the 5th-percentile woman".
    pub who: String,
    /// Stature \[m\].
    pub stature: f64,
    /// The body's segments ("head", "right forearm", …), in the order of the snapshot's
    /// `worker.capsules`.
    pub segments: Vec<String>,
    /// Each segment's capsule radius \[m\].
    pub radii: Vec<f64>,
}

impl WorkerData {
    /// The data of `settings`' body; `None` if the built-in table cannot make it (the
    /// scene would not have loaded).
    pub fn of(settings: &pliant_assembly::worker::WorkerSettings) -> Option<WorkerData> {
        let body = pliant_worker::body(settings.population).ok()?;
        Some(WorkerData {
            who: settings.population.describe(),
            stature: body.stature,
            segments: pliant_worker::SEGMENTS.iter().map(|s| s.name()).collect(),
            radii: pliant_worker::SEGMENTS
                .iter()
                .map(|s| s.radius(&body.radii))
                .collect(),
        })
    }
}

/// One hose's fixed data.
#[derive(Clone, Debug, Serialize)]
pub struct HoseData {
    pub name: String,
    /// Outer radius at each node \[m\] (the tube is swept through them, SPEC I7).
    pub radii: Vec<f64>,
    /// The minimum bend radius the checks hold it to \[m\] (`null`: not checked).
    pub min_bend_radius: Option<f64>,
    /// Arc length of its centre line \[m\]; the nodes lie at equal spacing along it.
    pub length: f64,
    /// Protections over stretches of it (`from`, `to`: arc length \[m\]).
    pub protections: Vec<ProtectionSpan>,
}

/// A junction body: its name, mass properties and outlets (the hose ends it joins).
#[derive(Clone, Debug, Serialize)]
pub struct JunctionBodyData {
    pub name: String,
    /// Its own mass \[kg\].
    pub mass: f64,
    /// Its centre of mass at rest \[m\] (the outlets' mean when its mass is lumped on
    /// them).
    pub centre_of_mass: [f64; 3],
    /// Its inertia tensor about its centre of mass at rest, world axes, rows \[kg·m²\].
    pub inertia: [[f64; 3]; 3],
    /// Whether its mass is lumped on its outlets (no centre of mass or inertia given).
    pub lumped: bool,
    pub outlets: Vec<OutletData>,
    /// The part (index into `parts`) that is its shape, drawn at the pose the snapshot's
    /// `part_poses` give it (its mesh in `parts` is where it sits with the hoses at
    /// rest); `null`: no shape (drawn as a hub with an arm to each outlet).
    pub shape: Option<usize>,
}

/// One outlet of a junction body: a hose (index into the welcome's `hoses`) and the node
/// of it that sits in the outlet (its first or its last).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct OutletData {
    pub hose: usize,
    pub node: usize,
}

/// One rigid part: its bounding box and its triangle mesh (world frame, metres, where the
/// scene placed it) and how it moves (`joint`, `scripted`, `movable`, `parent`).
#[derive(Clone, Debug, Serialize)]
pub struct PartData {
    pub name: String,
    #[serde(flatten)]
    pub motion: PartMotionData,
    pub bounds_min: [f64; 3],
    pub bounds_max: [f64; 3],
    /// x, y, z of each vertex, flattened.
    pub vertices: Vec<f32>,
    /// Three vertex indices per triangle, flattened.
    pub triangles: Vec<u32>,
}

/// Where a stub or clip is (world frame, metres).
#[derive(Clone, Debug, Serialize)]
pub struct FastenerData {
    pub name: String,
    /// "stub", "connector" or "clip".
    pub kind: pliant_assembly::FastenerKind,
    /// Stub: its mouth; clip: its seat centre.
    pub origin: [f64; 3],
    /// Stub: the push-on direction (mouth towards base); clip: the seated hose's axis.
    pub axis: [f64; 3],
    /// Clip: the direction out through the opening; stub: zero.
    pub opening: [f64; 3],
    /// Stub: the length a hose can be pushed on; clip: zero.
    pub length: f64,
    /// Stub: outer diameter; clip: inner diameter.
    pub diameter: f64,
    /// Clip: width of the opening; stub: zero.
    pub opening_width: f64,
    /// The part it sits on and moves with (index into the welcome's `parts`); `null`: it
    /// stands in the world.
    pub part: Option<usize>,
}

impl FastenerData {
    /// Stubs first, then clips (the order of the snapshot's fasteners).
    pub fn of(stubs: &[StubSite], clips: &[ClipSite]) -> Vec<FastenerData> {
        let stubs = stubs.iter().map(|s| {
            let spec = s.fit.stub();
            FastenerData {
                name: s.name.clone(),
                kind: s.fit.kind(),
                origin: spec.origin().to_array(),
                axis: spec.axis().to_array(),
                opening: [0.0; 3],
                length: spec.length(),
                diameter: spec.diameter(),
                opening_width: 0.0,
                part: s.part,
            }
        });
        let clips = clips.iter().map(|c| FastenerData {
            name: c.name.clone(),
            kind: pliant_assembly::FastenerKind::Clip,
            origin: c.spec.origin().to_array(),
            axis: c.spec.orientation().to_array(),
            opening: c.spec.opening().to_array(),
            length: 0.0,
            diameter: c.spec.inner_diameter(),
            opening_width: c.spec.opening_width(),
            part: c.part,
        });
        stubs.chain(clips).collect()
    }
}

/// The limits clients must keep to.
#[derive(Clone, Debug, Serialize)]
pub struct LimitsData {
    pub max_message_bytes: usize,
    pub max_messages_per_second: f64,
    pub snapshot_hz: f64,
    pub max_hands: usize,
}

impl SceneData {
    pub fn new(
        scene: &LoadedScene,
        model: &Model,
        sites: &(Vec<StubSite>, Vec<ClipSite>),
        snapshot_hz: f64,
    ) -> Self {
        let hoses = model
            .hoses
            .iter()
            .enumerate()
            .map(|(k, h)| HoseData {
                name: h.name.clone(),
                radii: h.nodes().map(|n| model.radius[n]).collect(),
                min_bend_radius: scene
                    .checks
                    .hoses
                    .get(k)
                    .filter(|_| scene.checks.bend_radius)
                    .map(|l| l.min_bend_radius),
                length: scene.hoses.get(k).map_or(0.0, |d| d.length),
                protections: scene
                    .hoses
                    .get(k)
                    .map(|d| d.protections.clone())
                    .unwrap_or_default(),
            })
            .collect();
        // the built junction of a scene's junction (same name), with its mass properties
        let own_of = |spec: &pliant_core::JunctionSpec| {
            model
                .junctions
                .iter()
                .find(|m| m.name == spec.name)
                .map(|m| m.own)
        };
        let junction_bodies = scene
            .junction_bodies
            .iter()
            .filter_map(|&j| scene.junctions.get(j))
            .map(|j| JunctionBodyData {
                name: j.name.clone(),
                mass: j.body_mass,
                centre_of_mass: own_of(j).map_or([0.0; 3], |o| o.centre.to_array()),
                inertia: own_of(j)
                    .map_or([[0.0; 3]; 3], |o| o.inertia.transpose().to_cols_array_2d()),
                lumped: own_of(j).is_none_or(|o| o.lumped),
                shape: j.shape,
                outlets: j
                    .ends
                    .iter()
                    .map(|&(hose, end)| OutletData {
                        hose,
                        node: match end {
                            HoseEnd::Start => 0,
                            HoseEnd::End => model.hoses.get(hose).map_or(1, |h| h.node_count) - 1,
                        },
                    })
                    .collect(),
            })
            .collect();
        let motions = PartMotionData::of(&scene.world.rigid_parts, &scene.timeline);
        let parts = scene
            .world
            .rigid_parts
            .iter()
            .zip(motions)
            .enumerate()
            .map(|(i, (p, motion))| {
                let (lo, hi) = scene
                    .parts
                    .get(i)
                    .map(|info| info.bounds)
                    .unwrap_or_else(|| {
                        p.vertices.iter().fold(
                            (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
                            |(lo, hi), v| (lo.min(*v), hi.max(*v)),
                        )
                    });
                PartData {
                    name: p.name.clone(),
                    motion,
                    bounds_min: lo.to_array(),
                    bounds_max: hi.to_array(),
                    vertices: p
                        .vertices
                        .iter()
                        .flat_map(|v| [v.x as f32, v.y as f32, v.z as f32])
                        .collect(),
                    triangles: p.triangles.iter().flatten().copied().collect(),
                }
            })
            .collect();
        SceneData {
            scene: scene.name.clone(),
            source: scene.source.clone(),
            time_step: model.time_step,
            hoses,
            junction_bodies,
            parts,
            fasteners: FastenerData::of(&sites.0, &sites.1),
            ergonomics: scene.ergonomics.to_string(),
            twist_limit: scene.checks.twist.then_some(scene.checks.twist_limit),
            worker: scene.worker.as_ref().and_then(WorkerData::of),
            limits: LimitsData {
                max_message_bytes: crate::limits::MAX_MESSAGE_BYTES,
                max_messages_per_second: crate::limits::MAX_MESSAGES_PER_SECOND,
                snapshot_hz,
                max_hands: crate::ownership::MAX_HANDS,
            },
        }
    }
}

/// The newest consistent state, as published by the simulation thread.
#[derive(Debug, Default, Serialize)]
pub struct Snapshot {
    /// Simulated time \[s\].
    pub time: f64,
    /// Steps taken since the start or the last reset.
    pub step: u64,
    pub paused: bool,
    /// Simulated seconds per wall-clock second, measured (≤ 1: real time is the target).
    pub real_time_factor: f64,
    /// Resets so far (a `reset` message, or a divergence).
    pub epoch: u64,
    pub hoses: Vec<HoseSnapshot>,
    /// The poses of the parts that move (a scripted motion, or moved by `move_part` /
    /// `rotate_part`), in the welcome's part order; none when every part stands still.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub part_poses: Vec<PartPose>,
    pub hands: Vec<HandSnapshot>,
    /// Stubs and clips (SPEC L6, L7): `final_state` is the state now, `assembled` whether
    /// the hose is fixed on the stub / seated in the clip, `max_force` the peak so far.
    pub fasteners: Vec<FastenerSnapshot>,
    /// The ergonomic profile hand loads are judged with now (changed by `set_ergonomics`).
    pub ergonomics: pliant_assembly::ergonomics::ErgonomicProfile,
    /// Feasible so far or not, and why (SPEC I5).
    pub verdict: pliant_assembly::Verdict,
    /// Violations of the running installation checks since the last reset (SPEC V3:
    /// bend radius, twist), each with hose, arc length, time, value and limit.
    pub checks: Vec<pliant_assembly::checks::Violation>,
    /// Unstable equilibria the static solver met and left since the last reset — buckling
    /// or a snap-through at input time t, which hose and node, the mode shape (the
    /// verdict's reasons say the same in words). Empty for the dynamic
    /// solvers.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub instabilities: Vec<pliant_assembly::workcell::Instability>,
    /// The worker as last posed (docs/worker.md): absent without a worker or before it
    /// was first posed. Sent in every snapshot while there is one: a client that skipped
    /// stale snapshots still draws the newest pose.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worker: Option<WorkerSnapshot>,
    /// Something the viewer should tell the user (e.g. the simulation diverged and was
    /// reset).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub notice: Option<String>,
    /// Divergences rolled back to a healthy recovery point so far in this session
    /// (the hands on the diverging hose were released; the rest went on).
    #[serde(skip_serializing_if = "is_zero")]
    pub rollbacks: u64,
    #[serde(skip)]
    pub(crate) json: OnceLock<String>,
}

/// Where a moving part is: its mesh (sent in the welcome where the scene placed it) is
/// drawn at `rotation · x + translation`.
#[derive(Clone, Debug, Serialize)]
pub struct PartPose {
    /// The part's index in the welcome's `parts`.
    pub part: usize,
    /// Where the part's reference origin went \[m\].
    pub translation: [f64; 3],
    /// The part's rotation as a unit quaternion `[x, y, z, w]`.
    pub rotation: [f64; 4],
}

/// The worker's posed body, its contacts, reach and posture scores at its last posed
/// instant.
#[derive(Clone, Debug, Serialize)]
pub struct WorkerSnapshot {
    /// When it was posed \[s\].
    pub time: f64,
    /// Per segment of the welcome's `worker.segments`: the end points a, b of its
    /// capsule's axis, six numbers `[ax, ay, az, bx, by, bz]` each, flattened \[m\].
    pub capsules: Vec<f64>,
    /// The segments inside a part or a hose at this instant.
    pub contacts: Vec<WorkerContact>,
    /// Per arm (right, left): the hand it follows and how far its grip stays short of
    /// the hand \[m\] (`null`: the arm hangs).
    pub arms: [Option<ArmReach>; 2],
    /// RULA's grand score (1–7) and REBA's score (1–15).
    pub rula: u8,
    pub reba: u8,
    /// The posture class whose rows judge the hand forces.
    pub posture_class: pliant_worker::PostureClass,
    /// Where it stands: the floor point between the feet \[m\] and the horizontal unit
    /// direction it faces; and the steps it took so far (a step or turn changes these).
    pub stance: WorkerStance,
    pub steps: u64,
    /// A seated worker's seat, drawn as a box (absent: standing).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seat: Option<SeatBox>,
}

/// A seat as a box: its centre \[m\], its full lengths along the worker's forward, left
/// and up directions \[m\], and those directions (unit; left = up × forward).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SeatBox {
    pub centre: [f64; 3],
    pub size: [f64; 3],
    pub forward: [f64; 3],
    pub up: [f64; 3],
}

/// The worker's stance.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct WorkerStance {
    pub position: [f64; 3],
    pub forward: [f64; 3],
}

/// A body segment inside a part or a hose now.
#[derive(Clone, Debug, Serialize)]
pub struct WorkerContact {
    /// Index into the welcome's `worker.segments`.
    pub segment: usize,
    /// `"part"` (index into the welcome's `parts`) or `"hose"` (into its `hoses`).
    pub obstacle: &'static str,
    pub index: usize,
    /// How deep \[m\].
    pub depth: f64,
}

/// An arm reaching for a hand.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ArmReach {
    pub hand: usize,
    /// How far the grip centre stays from the hand \[m\] (0: reached).
    pub shortfall: f64,
}

impl WorkerSnapshot {
    /// The snapshot of the worker's last posed instant `now`, its body `body`, seated
    /// on `seat` if any.
    pub fn of(
        body: &pliant_worker::Body,
        seat: Option<pliant_worker::Seat>,
        now: &pliant_assembly::worker::WorkerNow,
    ) -> Self {
        use pliant_assembly::worker::Obstacle;
        let capsules = pliant_worker::capsules(body, &now.posture)
            .iter()
            .flat_map(|c| [c.a.x, c.a.y, c.a.z, c.b.x, c.b.y, c.b.z])
            .collect();
        let contacts = now
            .contacts
            .iter()
            .enumerate()
            .filter_map(|(segment, c)| {
                let c = c.as_ref()?;
                let (obstacle, index) = match c.obstacle {
                    Obstacle::Part(k) => ("part", k),
                    Obstacle::Hose(h) => ("hose", h),
                };
                Some(WorkerContact {
                    segment,
                    obstacle,
                    index,
                    depth: c.depth,
                })
            })
            .collect();
        let arms = [0, 1].map(|i| {
            now.hand[i].map(|hand| ArmReach {
                hand,
                shortfall: now.posture.arms[i].residual,
            })
        });
        WorkerSnapshot {
            time: now.time,
            capsules,
            contacts,
            arms,
            rula: now.scores.rula.grand,
            reba: now.scores.reba.reba,
            posture_class: now.class,
            stance: WorkerStance {
                position: now.placement.position.to_array(),
                forward: now.placement.forward.to_array(),
            },
            steps: now.steps,
            seat: seat.map(|s| {
                let b = s.seat_box(body, &now.placement);
                SeatBox {
                    centre: b.centre.to_array(),
                    size: b.size.to_array(),
                    forward: b.forward.to_array(),
                    up: b.up.to_array(),
                }
            }),
        }
    }
}

/// One hose's state.
#[derive(Clone, Debug, Default, Serialize)]
pub struct HoseSnapshot {
    /// Node positions \[m\].
    pub positions: Vec<[f64; 3]>,
    /// Colour value c = min(|f| / f_max, 1) of the hands holding it (SPEC I4): 0 blue,
    /// 0.5 green, 1 red; 0 when no hand holds it.
    pub colour: f64,
    /// The hose is at rest and not simulated until something moves or touches it
    /// (SPEC I6).
    pub asleep: bool,
    /// Per beam now: `bend_radius_ratio`, `twist` [rad/m], `axial_force` \[N\] (the viewer's
    /// colour modes).
    #[serde(flatten)]
    pub fields: pliant_assembly::checks::BeamFields,
}

/// One hand's state and load (SPEC I2, I3).
#[derive(Clone, Debug, Default, Serialize)]
pub struct HandSnapshot {
    pub hand_id: u32,
    pub hose: usize,
    /// How the hand holds the hose: firm, axial or ball.
    pub grip: pliant_assembly::Grip,
    /// Hand pose: position \[m\] and orientation `[x, y, z, w]`.
    pub position: [f64; 3],
    pub orientation: [f64; 4],
    /// The pose the hand is moving towards (the last `move`).
    pub target: [f64; 3],
    /// Force \[N\] and torque about the hand position \[N·m\] the hand applies.
    pub force: [f64; 3],
    pub torque: [f64; 3],
    /// The worst ratio of the loads that decide feasibility (the force; twist and bending
    /// too when the profile's `moments_decide`); NaN-free (`null` if not assessable).
    pub ratio: Option<f64>,
    /// `push`, `pull`, `twist` or `bending`: which load the ratio belongs to.
    pub kind: Option<pliant_assembly::ergonomics::LoadKind>,
    /// Colour value c = min(ratio, 1).
    pub colour: f64,
    /// The force judged as `push` or `pull`, its limit value \[N\] and |force| / limit.
    pub force_kind: Option<pliant_assembly::ergonomics::LoadKind>,
    pub force_limit: Option<f64>,
    pub force_ratio: Option<f64>,
    /// The moment at the hand with the larger ratio: `twist` (about the hose axis,
    /// screwdriver row of table 3.11) or `bending` (across it, T-handle row), its limit
    /// value \[N·m\] and magnitude / limit. Guidance only unless `moments_decide`.
    pub torque_kind: Option<pliant_assembly::ergonomics::LoadKind>,
    pub torque_limit: Option<f64>,
    pub torque_ratio: Option<f64>,
}

/// One stub or clip: its report so far and the force it applies now.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FastenerSnapshot {
    #[serde(flatten)]
    pub report: pliant_assembly::FastenerReport,
    /// Magnitude of the force the fastener applies to the hose now \[N\].
    pub force: f64,
}

impl Snapshot {
    /// The `snapshot` message as JSON, serialised once however many clients read it.
    pub fn json(&self) -> &str {
        self.json
            .get_or_init(|| crate::protocol::ServerMessage::Snapshot(self).to_json())
    }
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}
