//! The scene file's raw shape (format `pliant-scene`, version 1), exactly as written:
//! lengths still in the file's `length_unit`, moduli in MPa, nothing checked beyond types.
//! [`crate::load`] checks and converts it. The JSON Schema (`docs/scene.schema.json`) is
//! generated from these types, so their doc comments are the schema's descriptions.

use crate::units::LengthUnit;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A 3-vector `[x, y, z]`.
pub type Vec3 = [f64; 3];

/// A whole scene file.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Must be `"pliant-scene"`.
    pub format: FormatTag,
    /// Format version; this build reads version 1.
    #[schemars(range(min = 1, max = 1))]
    pub version: u32,
    /// Name shown in outputs. Default: the file name.
    pub name: Option<String>,
    /// Unit of every length, position and diameter in the file: `"mm"` or `"m"`.
    pub length_unit: LengthUnit,
    /// Global simulation settings (SI, not affected by `length_unit`).
    pub simulation: Option<SimulationSection>,
    /// What to record.
    pub output: Option<OutputSection>,
    /// User materials by name. Names of the built-in library (`hose1` … `hose5`) are
    /// reserved.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialEntry>,
    /// The hoses of the scene (at least one).
    #[schemars(length(min = 1))]
    pub hoses: Vec<HoseEntry>,
    /// Junctions joining hose ends into networks — a harness's branch points, a moulded
    /// T or Y piece (SPEC N1).
    #[serde(default)]
    pub junctions: Vec<JunctionEntry>,
    /// Rigid parts of the environment (triangle meshes from files, or primitives).
    #[serde(default)]
    pub parts: Vec<PartEntry>,
    /// Connector stubs hose ends are pushed onto (SPEC L6).
    #[serde(default)]
    pub stubs: Vec<StubEntry>,
    /// Connectors: a plug on a hose end pushed into its counterpart against a measured
    /// mating force until it latches.
    #[serde(default)]
    pub connectors: Vec<ConnectorEntry>,
    /// Clips hoses are snapped into (SPEC L7).
    #[serde(default)]
    pub clips: Vec<ClipEntry>,
    /// Which rows and columns of the ergonomic tables judge hand loads (SPEC I3).
    /// Default: standing, women, occasional duty.
    pub ergonomics: Option<ErgonomicsSection>,
    /// Installation checks (SPEC V3): which run and their limits. Absent: all on, with
    /// the defaults.
    pub checks: Option<ChecksSection>,
    /// The worker who does the assembly (SPEC E1–E2): a manikin that follows the hands,
    /// whose reach, body collisions and posture (RULA, REBA) are judged. Absent: nobody
    /// is modelled.
    pub worker: Option<WorkerSection>,
    /// A range-of-motion study (SPEC K2): the checks, fixing forces and clearances
    /// recorded against a moving part's motion coordinate (`motion.csv`).
    pub sweep: Option<SweepSection>,
    /// Scripted actions, executed in order.
    #[serde(default)]
    pub timeline: Vec<ActionEntry>,
}

/// The value of `format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
pub enum FormatTag {
    /// The only value.
    #[serde(rename = "pliant-scene")]
    PliantScene,
}

/// `[simulation]`: global settings, all optional, all SI.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SimulationSection {
    /// Gravitational acceleration (m/s²). Default `[0, 0, -9.81]`; `[0, 0, 0]` switches
    /// gravity off.
    pub gravity: Option<Vec3>,
    /// Mass-proportional Rayleigh damping α (1/s), ≥ 0. Default 1.0.
    pub damping_mass_per_s: Option<f64>,
    /// Stiffness-proportional Rayleigh damping β (s), ≥ 0. Default: chosen automatically
    /// by the physics core.
    pub damping_stiffness_s: Option<f64>,
    /// Safety factor on the stable explicit time step, in (0, 1]. Default 0.5.
    pub time_step_safety: Option<f64>,
    /// Fixed time step (s), > 0. Default: computed from the model.
    pub time_step_s: Option<f64>,
    /// Solver: `explicit` (default; the dissertation's central differences), `implicit`
    /// (HHT-α with Newton, large steps) or `static` (the equilibrium at each input).
    pub solver: Option<String>,
    /// Implicit solver's time step (s), in (0, 1]. Default 0.01.
    pub implicit_time_step_s: Option<f64>,
    /// Static solver: simulated time between equilibrium solves (s), in (0, 1]. Default 0.01.
    pub static_input_step_s: Option<f64>,
    /// Static solver: Newton iterations allowed per equilibrium, 1 … 10 000. Default 60.
    pub static_max_iterations: Option<u64>,
    /// Static solver: explicit steps the snap relaxation (the fallback of a step Newton
    /// does not converge) may take over the whole run, ≥ 0. Default 10 000 000. Once spent,
    /// such a step is reported unconverged (the verdict uncertain).
    pub static_relaxation_budget: Option<u64>,
    /// Which pairs of beams press on each other: `all` (default), `apart_at_rest` (all
    /// but those overlapping in the shape as drawn — bundles a CAD route draws through
    /// one another) or `off`.
    pub hose_contact: Option<String>,
    /// Mass scaling s, 1 … 10 000 (default 1): inertia s times the mass, weight and mass
    /// damping unchanged, the explicit step √s longer. For quasi-static timelines; the
    /// equilibria are unchanged, inertial forces s times larger.
    pub mass_scaling: Option<f64>,
}

/// `[output]`: what to record.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Interval between recorded states (s), ≥ 0; 0 records every step. Default 0.01.
    pub record_interval_s: Option<f64>,
}

/// `[ergonomics]`: the worker the hand loads are judged for (SPEC I3). Names are
/// case-insensitive; `-` and spaces count as `_`.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ErgonomicsSection {
    /// `standing`, `crouching` or `sitting`: sets the push row (same name) and the pull
    /// row (`standing_lever`, `crouching_lever`, `handle`). Default `standing`.
    pub posture: Option<String>,
    /// Push row, overriding `posture`: `standing`, `crouching` or `sitting`.
    pub push: Option<String>,
    /// Pull row, overriding `posture`: `standing_lever`, `crouching_lever` or `handle`.
    pub pull: Option<String>,
    /// `women` or `men`. Default `women` (the lower limits).
    pub population: Option<String>,
    /// `continuous` (held over a minute) or `occasional`. Default `occasional`.
    pub duty: Option<String>,
    /// Whether the hand's twist (about the hose axis: screwdriver row of tables 3.10 /
    /// 3.11) and bending moment (across it: T-handle row) count towards feasibility.
    /// Default `false`: the dissertation (section 3.3.3) calls them "never reasons for an
    /// installation to fail"; they are reported as warnings.
    pub moments_decide: Option<bool>,
    /// Which standard judges push and pull: `dissertation` (tables 3.6–3.9, default) or
    /// `en1005-3` (EN 1005-3:2002+A1:2008: recommended force limit F_R and risk zones;
    /// data with sources in `crates/assembly/data/en1005_3.toml`). The keys below apply
    /// only to `en1005-3`.
    pub standard: Option<String>,
    /// EN 1005-3 action (Table 1 push and pull rows): `whole_body` (standing, default),
    /// `arm_trunk_support` (sitting, one arm, with trunk support) or `arm` (without).
    pub action: Option<String>,
    /// EN 1005-3 user population: `professional` (15th percentile, default) or
    /// `domestic` (1st percentile).
    #[serde(rename = "use")]
    pub user_population: Option<String>,
    /// EN 1005-3: percentile of the user population whose capacity counts, in [1, 50];
    /// overrides `use`. Default 15.
    pub percentile: Option<f64>,
    /// EN 1005-3 velocity multiplier m_v: `low` (static or slow, default) or `high`.
    pub velocity: Option<String>,
    /// EN 1005-3 frequency multiplier m_f: actions per minute, in [0, 20]. Default 0.2.
    pub frequency_per_min: Option<f64>,
    /// EN 1005-3 frequency multiplier m_f: duration of one action (s); up to 3 s counts
    /// as short. Default 3.
    pub action_time_s: Option<f64>,
    /// EN 1005-3 duration multiplier m_d: hours of this work per day, in [0, 8]. Default 1.
    pub duration_h: Option<f64>,
}

/// `[sweep]`: a range-of-motion study (SPEC K2). The part's own `motion` moves it through
/// its range as the timeline runs (a static solver sees a sequence of poses, a dynamic
/// one the speed of its keyframes); every checked instant is recorded against the
/// part's motion coordinate.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepSection {
    /// The moving part whose coordinate the results are given against (its `name`): a
    /// hinge's angle, a slide's travel, a periodic motion's phase, a path's time.
    pub part: String,
    /// The parts whose clearance to every hose is recorded (names). Default: every part.
    pub clearance_to: Option<Vec<String>>,
    /// Smallest clearance allowed between a hose and those parts (length unit): a hose
    /// coming nearer is a violation, which decides as the installation checks do.
    pub min_clearance: Option<f64>,
    /// Voxel size of the swept envelopes (length unit), > 0. Default: the smaller of
    /// 5 mm and half the thinnest hose's outer radius. Refused when the envelopes' grid
    /// over the hoses as placed would already exceed 400 million cells.
    pub envelope_voxel: Option<f64>,
}

/// `[checks]`: the installation checks (SPEC V3; cf. DIN 20066) — which run, their
/// limits, and whether a violation makes the study infeasible. Every key is optional.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ChecksSection {
    /// Bend radius of the centre line ≥ the material's minimum, everywhere and at every
    /// checked instant. Default true.
    pub bend_radius: Option<bool>,
    /// Twist relative to the routed hose ≤ `twist_limit_deg_per_m`. Default true.
    pub twist: Option<bool>,
    /// No axial tension at rest after assembly: axial strain at the end ≤
    /// `rest_strain_limit`. Default true.
    pub tension_at_rest: Option<bool>,
    /// A straight length behind each stub at the end. Default true.
    pub straight_behind_stub: Option<bool>,
    /// Whether a violation makes the verdict NOT FEASIBLE (else it is a warning).
    /// Default true.
    pub decide: Option<bool>,
    /// Twist limit (°/m), > 0. Default 10.
    pub twist_limit_deg_per_m: Option<f64>,
    /// Largest axial strain at rest, > 0. Default 0.005.
    pub rest_strain_limit: Option<f64>,
    /// Straight length behind a stub in outer diameters, > 0. Default 1.5.
    pub straight_length_d_outer: Option<f64>,
    /// Bend radius that counts as straight, in minimum bend radii, > 0. Default 10.
    pub straight_radius_factor: Option<f64>,
}

/// `[worker]`: the manikin (SPEC E1–E2; docs/worker.md). Sized from ANSUR II stature and
/// segment proportions of stature (sources in `crates/worker/data/anthropometry.toml`).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WorkerSection {
    /// `female` or `male`, optionally followed by the percentile of stature:
    /// `"female 5"`, `"male 50"`, `"male 95"`.
    pub population: String,
    /// Percentile of stature, in [1, 99], when `population` names only the sex. Default 50.
    pub percentile: Option<f64>,
    /// Where the worker stands: `[x, y, z]`, the floor point between the feet (seated:
    /// under the pelvis, where the seat stands) in `length_unit`, or `"auto"` (default):
    /// in front of the first point a hand holds, which is then 0.6 of the arm's reach
    /// ahead of that floor point.
    pub position: Option<WorkerPosition>,
    /// The direction the worker faces (its horizontal part counts). Default `[1, 0, 0]`.
    pub facing: Option<Vec3>,
    /// Height of the floor along the vertical (against gravity) for `position = "auto"`,
    /// in `length_unit`. Default 0.
    pub floor: Option<f64>,
    /// `standing` (default: feet on the floor, knees straight) or `sitting` (on a seat
    /// under the pelvis, thighs horizontal, feet on the floor; no steps).
    pub posture: Option<String>,
    /// Seated: the height of the seat surface above the floor, in `length_unit`, > 0 and
    /// below the height that would put the hips as high as standing. Default: the
    /// worker's popliteal height (ANSUR II, the same percentile as the stature).
    pub seat_height: Option<f64>,
    /// REBA's coupling, how well the hand holds the hose: `good`, `fair` (default),
    /// `poor` or `unacceptable`.
    pub coupling: Option<String>,
    /// Whether a hand target out of reach or a body segment inside a part makes the study
    /// NOT FEASIBLE (else they are warnings). Default true.
    pub decide: Option<bool>,
    /// Whether the worker may step towards a hand target out of reach with the feet
    /// kept: at most one step (0.4 of stature) from where it was placed, reported as a
    /// step; out of reach only when still so after it. Default false.
    pub steps: Option<bool>,
}

/// `[worker] position`: a point or `"auto"`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum WorkerPosition {
    /// `"auto"`: in front of the first grab point.
    Auto(AutoWord),
    /// The floor point between the feet, in `length_unit`.
    At(Vec3),
}

/// The word `"auto"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
pub enum AutoWord {
    /// The only value.
    #[serde(rename = "auto")]
    Auto,
}

/// Which end of a hose: its first node or its last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HoseEndName {
    /// The first node (at the hose's `start`).
    Start,
    /// The last node.
    End,
}

/// `[[stubs]]`: a rigid connector stub (SPEC L6), a cylinder a hose end is pushed onto.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StubEntry {
    /// Unique, non-empty name (shared namespace with clips).
    pub name: String,
    /// The part the stub sits on (a part's `name`): it goes with the part as the part
    /// moves; its position and directions are given where the part's `position` and
    /// `rotation` put it. Default: fixed in the world.
    #[serde(default)]
    pub part: Option<String>,
    /// The stub's mouth: the centre of its free end, where a hose first meets it
    /// (length unit).
    pub origin: Vec3,
    /// Push-on direction, from the mouth towards the stub's base; any non-zero length
    /// (normalised on loading).
    pub axis: Vec3,
    /// Length a hose can be pushed on (length unit), > 0.
    pub length: f64,
    /// Outer diameter d_s (length unit), > 0.
    pub diameter: f64,
    /// Coulomb friction of the hose on the stub. Default static 0.6, sliding 0.4
    /// (assumption: rubber on plastic).
    pub friction: Option<FrictionEntry>,
    /// The hose meant to go onto this stub. Requires `end`.
    pub hose: Option<String>,
    /// Which end of `hose` goes onto the stub: `"start"` or `"end"`. Requires `hose`.
    pub end: Option<HoseEndName>,
    /// A bead (ring) on the stub that makes pulling off harder than pushing on (SPEC V4).
    /// Shorthand for a `profile` of one; not together with `profile`.
    pub bead: Option<BeadEntry>,
    /// The stub's profile: beads or barbs along the axis from the mouth inwards (each
    /// starting after the previous one ends; at most 8), e.g. a barb = a gentle entry
    /// flank, a narrow crest and a steep back flank.
    pub profile: Option<Vec<BeadEntry>>,
}

/// `[[connectors]]`: a plug on a hose end and its counterpart. The plug is pushed from the
/// counterpart's mouth along `axis` by up to `travel`, against the measured force
/// `mating_force`, until its latch clicks at `latch_at`; latched, it holds up to
/// `retention_force_n` against pulling.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ConnectorEntry {
    /// Unique, non-empty name (shared namespace with stubs and clips).
    pub name: String,
    /// The part the connector's counterpart sits on (a part's `name`): it goes with the part as the part
    /// moves; its position and directions are given where the part's `position` and
    /// `rotation` put it. Default: fixed in the world.
    #[serde(default)]
    pub part: Option<String>,
    /// The counterpart's mouth: where the plug's end starts to engage (length unit).
    pub origin: Vec3,
    /// Mating direction, from the mouth into the counterpart; any non-zero length.
    pub axis: Vec3,
    /// Mating travel from the mouth to fully home (length unit), ≥ 1 mm.
    pub travel: f64,
    /// The mating force over the travel: `[[travel, force_n], …]`, travel in the length
    /// unit from the mouth, increasing, within `travel`; 1 to 16 points, linear between
    /// them (a connector's datasheet or a measured engage-force curve).
    pub mating_force: Vec<[f64; 2]>,
    /// Travel at which the latch clicks (length unit), in (0, `travel`]. Default: `travel`.
    pub latch_at: Option<f64>,
    /// Force a latched connector holds against pulling out \[N\], ≥ 0.
    pub retention_force_n: f64,
    /// The plug's size (length unit), > 0: the plug is taken into the mouth when its end is
    /// within half of it from the axis. Default: twice the hose's outer diameter there.
    pub size: Option<f64>,
    /// The hose whose end carries the plug. Requires `end`.
    pub hose: Option<String>,
    /// Which end of `hose` carries the plug: `"start"` or `"end"`. Requires `hose`.
    pub end: Option<HoseEndName>,
}

/// `bead` of a stub: a ring of `height` on the stub starting `at` from the mouth, a crest
/// of `width`, a gentle entry flank and a steep back flank (angles to the stub axis).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BeadEntry {
    /// Depth of the start of the entry flank from the mouth (length unit), ≥ 0.
    pub at: f64,
    /// Radial height above the stub (length unit), > 0.
    pub height: f64,
    /// Width of the crest (length unit), > 0.
    pub width: f64,
    /// Angle of the entry flank to the axis (degrees), in (0, 90).
    pub entry_angle_deg: f64,
    /// Angle of the back flank to the axis (degrees), in (0, 90).
    pub back_angle_deg: f64,
}

/// `[[clips]]`: a clip a hose is snapped into (SPEC L7).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ClipEntry {
    /// Unique, non-empty name (shared namespace with stubs).
    pub name: String,
    /// The part the clip sits on (a part's `name`): it goes with the part as the part
    /// moves; its position and directions are given where the part's `position` and
    /// `rotation` put it. Default: fixed in the world.
    #[serde(default)]
    pub part: Option<String>,
    /// Seat centre: where a seated hose's centre line passes (length unit).
    pub origin: Vec3,
    /// Direction from the seat out through the opening (the hose comes in against it);
    /// any non-zero length (normalised on loading).
    pub opening: Vec3,
    /// Direction of a seated hose's axis through the clip; roughly perpendicular to
    /// `opening` (its part along `opening` is removed); any non-zero length.
    pub orientation: Vec3,
    /// Opening width d₁ (length unit), > 0 and < `inner_diameter`.
    pub opening_width: f64,
    /// Inner (seat) diameter d₂ (length unit), > 0.
    pub inner_diameter: f64,
    /// Snap force k (N), ≥ 0: the force against the hose at the opening. Required except
    /// for a cable tie (which has no snap; default 0).
    pub snap_force_n: Option<f64>,
    /// The hose meant to be snapped into this clip. Optional.
    pub hose: Option<String>,
    /// The fixing's type, which decides the degrees of freedom it leaves free in its VEC
    /// frame (X = Y × Z, Y = `orientation`, Z = `opening`). Default `fixed`.
    #[serde(rename = "type", default)]
    pub kind: ClipType,
    /// Coulomb coefficient μ of a sliding guide along the hose, ≥ 0. Default 0.4
    /// (assumption: rubber on plastic, as a stub's sliding friction). Only for `sliding`.
    pub friction: Option<f64>,
    /// Pull-out force (N), > 0: a seated hose pulled out of the seat (along `opening`)
    /// harder than this comes loose. Default: it holds whatever the pull.
    pub holding_force_n: Option<f64>,
    /// The clip takes the hose only when a hand presses it in through its opening: a hose
    /// drawn through it, passing by, or carried into the jaws from behind is not held — a
    /// fixing on a harness that the worker pushes into its hole. Default false: a hose
    /// drawn in the seat starts seated, and one that comes into the jaws snaps in.
    #[serde(default)]
    pub by_hand: bool,
}

/// `type` of a clip: a fixing by the degrees of freedom it leaves free.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ClipType {
    /// All six degrees of freedom fixed.
    #[default]
    Fixed,
    /// Free to turn about the clip's Z axis (`opening`): a clip turning on its mount.
    Rotating,
    /// Free to slide along the hose (Y, `orientation`) against Coulomb friction.
    Sliding,
    /// A cable tie around the hose to a part: all six fixed, no snap.
    CableTie,
}

/// `[materials.NAME]`: a user material.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialEntry {
    /// Young's modulus in tension E_t (MPa), > 0.
    pub e_tension_mpa: f64,
    /// Young's modulus in compression E_c (MPa), > 0.
    pub e_compression_mpa: f64,
    /// Bending modulus (MPa), > 0. Default: the reduced bimodular modulus
    /// E_b = 4 E_t E_c / (√E_t + √E_c)².
    pub e_bending_mpa: Option<f64>,
    /// Poisson's ratio ν, in (−1, 0.5).
    pub poisson: f64,
    /// Density ρ (kg/m³), > 0.
    pub density_kg_m3: f64,
    /// Smallest bend radius of the centre line (mm), > 0, for the bend-radius check.
    /// Default: 6 × d_inner + d_outer / 2 of the hose's section (the rule for
    /// mandrel-built rubber hoses, 6 × d_inner to the inside of the bend; an assumption).
    pub min_bend_radius_mm: Option<f64>,
    /// Yield stress σ_y in uniaxial tension (MPa), > 0: the material yields (von Mises,
    /// fibres of the tube wall in bending and torsion) and keeps a permanent set.
    /// Default: elastic for ever. Needs the section's diameters (no given stiffness).
    pub yield_stress_mpa: Option<f64>,
    /// Linear (kinematic) hardening modulus H (MPa), ≥ 0: the slope of the stress over
    /// the plastic strain past yield. Only with `yield_stress_mpa`. Default: 0 (perfectly
    /// plastic).
    pub hardening_modulus_mpa: Option<f64>,
    /// The moduli relax under held strain (rubber, linear viscoelasticity): every modulus
    /// above is the instantaneous one E₀ and relaxes as
    /// E(t) = E₀ (1 − Σ weight (1 − e^{−t/time_s})), a Prony series of up to 8 terms,
    /// weights in (0, 1) summing below 1. Default: elastic for ever. Not with
    /// `yield_stress_mpa`.
    #[serde(default)]
    pub relaxation: Vec<PronyEntry>,
    /// Friction in bending and torsion (a wire bundle, a braided hose): a moment per
    /// element following Dahl's law, which traces a hysteresis loop under cycled
    /// bending. Default: none. Not with `yield_stress_mpa` or `relaxation`.
    pub hysteresis: Option<HysteresisEntry>,
}

/// `hysteresis` of a material: Dahl friction moments (docs/physics.md). The moments are
/// those of the section the material is used with.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HysteresisEntry {
    /// Saturated friction moment in bending M_s (N·m), > 0: half the height of a wide
    /// bending loop.
    pub bending_moment_n_m: f64,
    /// Curvature scale κ_s (1/m), > 0: the friction moment builds up over a few κ_s
    /// after each reversal (its initial stiffness is M_s/κ_s).
    pub bending_curvature_1_m: f64,
    /// Saturated friction moment in torsion (N·m), > 0. Default: no friction in torsion.
    pub torsion_moment_n_m: Option<f64>,
    /// Twist-rate scale in torsion (1/m), > 0. Required with `torsion_moment_n_m`.
    pub torsion_curvature_1_m: Option<f64>,
}

/// One term of a relaxing modulus (`relaxation` of a material).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PronyEntry {
    /// Relative weight g of the term, in (0, 1).
    pub weight: f64,
    /// Relaxation time τ (s), > 0.
    pub time_s: f64,
}

/// `[[hoses]]`: one hose.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HoseEntry {
    /// Unique, non-empty name; timeline actions refer to the hose by it.
    pub name: String,
    /// A library material (`hose1` … `hose5`) or a key of `[materials]`.
    pub material: String,
    /// Tube cross-section (length unit). Optional for a library material, whose
    /// diameters are the default; required otherwise.
    pub section: Option<SectionEntry>,
    /// Number of beam elements, ≥ 1. Excludes `element_length`.
    pub elements: Option<u32>,
    /// Target element length (length unit), > 0. Excludes `elements`. Default when
    /// neither is given: 1.5 × d_outer.
    pub element_length: Option<f64>,
    /// First point of the centre line (length unit). Required with `path`; not with
    /// `route` (the route's first point is the start).
    pub start: Option<Vec3>,
    /// Centre-line segments, each starting where the previous one ended. Give either
    /// `start` and `path`, or `route`.
    #[serde(default)]
    pub path: Vec<SegmentEntry>,
    /// The centre line from CAD instead of `start` and `path`: a curve of a STEP file,
    /// or a list of points in a CSV file.
    pub route: Option<RouteEntry>,
    /// Offsets of rest-shape nodes (length unit), applied after discretisation.
    #[serde(default)]
    pub imperfection: Vec<ImperfectionEntry>,
    /// Direction of the cross-section's axis 1 (the node frame's y axis) at the first
    /// node; must not be parallel to the hose's first tangent. Default: any normal
    /// direction. Required when a section has EI1 ≠ EI2 (it orients the section).
    pub normal_hint: Option<Vec3>,
    /// Stiffened (rigid) sections, e.g. a metal tube joining two flexible parts
    /// (SPEC M6): each a span of nodes that moves as one rigid body.
    #[serde(default)]
    pub stiffened: Vec<StiffenedEntry>,
    /// Spans with a cross-section of their own (a hose whose section varies along it);
    /// elsewhere `section` holds. Spans must not overlap.
    #[serde(default)]
    pub spans: Vec<SpanEntry>,
    /// Protections over stretches of the hose (a harness segment's tape, corrugated tube
    /// or sleeve), by arc length as `spans`: what covers the bundle where, for drawing and
    /// reports. Their stiffness, diameter and mass are a span's `section`. Protections of
    /// one kind must not overlap; different kinds may lie over one another (tape under a
    /// corrugated tube).
    #[serde(default)]
    pub protections: Vec<ProtectionEntry>,
    /// The shape the hose was delivered in, its stress-free shape (pre-deformation):
    /// `"straight"`, `{ coil = { radius, pitch } }` or `{ path = [...] }` (length unit).
    /// The hose starts routed along `path`/`route`, holding the difference as strain.
    /// Default: the routed shape is stress-free.
    pub delivered: Option<DeliveredEntry>,
    /// Minimum bend radius of the centre line (length unit), > 0, for the bend-radius
    /// check; overrides the material's (e.g. a harness segment's, from its wires and
    /// protection).
    pub min_bend_radius: Option<f64>,
}

/// `[[junctions]]`: hose ends joined into one rigid junction (SPEC N1).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JunctionEntry {
    /// Unique, non-empty name.
    pub name: String,
    /// The hose ends joined here, at least two. Without `body` they must meet at one
    /// point (a welded branch point).
    #[schemars(length(min = 2))]
    pub ends: Vec<JunctionEndEntry>,
    /// A junction body (a moulded T or Y piece) whose outlets are the ends, which may
    /// then lie apart. Absent: a welded branch point.
    pub body: Option<JunctionBodyEntry>,
}

/// One hose end of a junction.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JunctionEndEntry {
    /// The hose's name.
    pub hose: String,
    /// Which end.
    pub end: HoseEndName,
}

/// A junction body.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JunctionBodyEntry {
    /// The body's own mass \[kg\], ≥ 0; > 0 with `centre_of_mass` or `inertia_kg_m2`.
    /// Without either, lumped onto its outlets in equal shares.
    #[serde(default)]
    pub mass_kg: f64,
    /// The body's centre of mass, a point in the scene's coordinates (length unit) as
    /// the hoses lie at rest. Default with `inertia_kg_m2`: the outlets' mean.
    pub centre_of_mass: Option<Vec3>,
    /// The body's inertia about its centre of mass \[kg·m²\], in the scene's axes:
    /// principal moments `[Jxx, Jyy, Jzz]` or a full symmetric tensor
    /// `[[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], [Jxz, Jyz, Jzz]]`; positive definite, its
    /// principal moments satisfying the triangle inequality. Default with
    /// `centre_of_mass`: zero (a point mass there).
    pub inertia_kg_m2: Option<InertiaEntry>,
    /// The body's shape: the `name` of a part of `[[parts]]` (mesh, STEP solid or
    /// primitive), placed where it sits while the hoses lie as the scene gives them. It
    /// then rides on the body and hoses touch it (explicit solver only). The part must
    /// have no `motion` and no `parent`, be moved by no timeline action, carry no other
    /// part and be the shape of no other junction. Absent: no shape (the viewer draws
    /// a hub with an arm to each outlet).
    pub part: Option<String>,
}

/// An inertia tensor \[kg·m²\]: its diagonal or all of it.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum InertiaEntry {
    /// `[Jxx, Jyy, Jzz]`: the scene's axes are principal axes.
    Principal(Vec3),
    /// `[[Jxx, Jxy, Jxz], [Jyx, Jyy, Jyz], [Jzx, Jzy, Jzz]]`, symmetric.
    Tensor([Vec3; 3]),
}

/// A stiffened span of a hose: nodes `first` to `last` (inclusive) are rigid together.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StiffenedEntry {
    /// First node; negative counts from the end (−1 = last node).
    pub first: i64,
    /// Last node (inclusive), after `first`; negative counts from the end.
    pub last: i64,
}

/// A cross-section: inner and outer diameter (length unit) — the contact envelope and,
/// by default, with the material the source of stiffness and mass — and optionally any
/// of the stiffnesses and the mass per length given directly (SI), for cables, flat
/// ribbons and bundles. Section axis 1 is the hose's `normal_hint` direction at its
/// first node, carried along the hose; axis 2 completes the right-handed frame with the
/// hose tangent.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SectionEntry {
    /// Inner diameter d_i, ≥ 0 (0 for a solid rod) and < d_outer.
    pub d_inner: f64,
    /// Outer diameter d_a, > 0.
    pub d_outer: f64,
    /// Axial stiffness EA (N), > 0, the same in tension and compression. Default: the
    /// material's E_t A and E_c A.
    pub ea_n: Option<f64>,
    /// Bending stiffness about section axis 1 (N·m²), > 0. Default: E_b I.
    pub ei1_n_m2: Option<f64>,
    /// Bending stiffness about section axis 2 (N·m²), > 0. Default: E_b I. A section
    /// with EI1 ≠ EI2 needs the hose's `normal_hint`.
    pub ei2_n_m2: Option<f64>,
    /// Torsional stiffness GJ (N·m²), > 0. Default: G J of the tube.
    pub gj_n_m2: Option<f64>,
    /// Mass per length (kg/m), > 0. Default: ρ A.
    pub mass_kg_m: Option<f64>,
}

/// A span of a hose with its own cross-section, by arc length along the centre line
/// (length unit): the elements whose middle lies in `from ≤ s < to` take `section` (a
/// span end inside an element rounds to the nearer node).
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpanEntry {
    /// Arc length where the span starts, ≥ 0.
    pub from: f64,
    /// Arc length where the span ends, > from and ≤ the hose's length.
    pub to: f64,
    /// The span's cross-section.
    pub section: SectionEntry,
    /// Minimum bend radius of the centre line over the span (length unit), > 0, for the
    /// bend-radius check (a protected stretch of a harness: the larger of its wires' and
    /// its protection's). Default: the hose's.
    pub min_bend_radius: Option<f64>,
}

/// A protection over a stretch of a hose, by arc length along the centre line (length
/// unit), addressed as a span is.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProtectionEntry {
    /// What covers the stretch.
    pub kind: ProtectionKindName,
    /// Arc length where it starts, ≥ 0.
    pub from: f64,
    /// Arc length where it ends, > from and ≤ the hose's length.
    pub to: f64,
}

/// The kinds of protection over a wire bundle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ProtectionKindName {
    /// Film tape (PVC, …) wound over the bundle.
    Tape,
    /// Fleece (textile) tape.
    FleeceTape,
    /// Corrugated tube.
    CorrugatedTube,
    /// Braided or woven sleeve, or a smooth tube.
    Sleeve,
    /// Anything else.
    Other,
}

impl ProtectionKindName {
    /// The name as written in the scene file.
    pub fn key(self) -> &'static str {
        match self {
            ProtectionKindName::Tape => "tape",
            ProtectionKindName::FleeceTape => "fleece_tape",
            ProtectionKindName::CorrugatedTube => "corrugated_tube",
            ProtectionKindName::Sleeve => "sleeve",
            ProtectionKindName::Other => "other",
        }
    }
}

/// `route = { step = "bay.step", curve = "hose_route" }`, `route = { step = "bay.step",
/// index = 0 }` or `route = { csv = "route.csv" }`: a hose's centre line from CAD.
/// The hose's nodes lie on the polyline through the route's points (for `smooth = true`
/// on a Catmull-Rom spline through them).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RouteEntry {
    /// STEP file (AP203/AP214/AP242) holding the curve: an edge or wire that is not
    /// the boundary of a face (a B-spline, polyline, line, circle…). Excludes `csv`.
    pub step: Option<String>,
    /// The curve's name in the STEP file (its product or shape name). Excludes `index`.
    pub curve: Option<String>,
    /// The curve's index among the file's free curves (0 = first), when unnamed.
    pub index: Option<u32>,
    /// Sampling tolerance of the STEP curve (length unit), > 0: the largest distance of
    /// the polyline through the samples from the CAD curve. Default 0.01 mm.
    pub tolerance: Option<f64>,
    /// CSV file of points, one `x,y,z` per line, in order; an optional header line
    /// names the columns and may give the unit (`x_mm,y_mm,z_mm` or `x [in],…`).
    /// Excludes `step`.
    pub csv: Option<String>,
    /// Unit of the CSV's coordinates: `"mm"`, `"cm"`, `"m"` or `"in"`. Default: the
    /// header's unit, else the scene's `length_unit`.
    pub units: Option<String>,
    /// Catmull-Rom spline through the points instead of straight lines between them
    /// (for a few points exported from a sketch). Default false.
    #[serde(default)]
    pub smooth: bool,
}

/// One centre-line segment: exactly one of `line`, `arc`, `spline`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum SegmentEntry {
    /// Straight line to `to`.
    Line {
        /// End point (length unit).
        to: Vec3,
    },
    /// Circular arc from the segment's start through `via` to `to`.
    Arc {
        /// A point on the arc between start and end (length unit).
        via: Vec3,
        /// End point (length unit).
        to: Vec3,
    },
    /// Uniform Catmull-Rom spline from the segment's start through `through` to `to`.
    Spline {
        /// Interior points the curve passes through, in order (length unit).
        #[serde(default)]
        through: Vec<Vec3>,
        /// End point (length unit).
        to: Vec3,
    },
}

/// `[[parts]]`: one rigid, fixed part: exactly one of `mesh`, `step`, `box`,
/// `cylinder`, `sphere`, placed by `position` and `rotation` (a STEP assembly gives one
/// part per solid, all placed together).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PartEntry {
    /// Unique, non-empty name.
    pub name: String,
    /// Mesh file (`.obj`, `.stl`, `.gltf`, `.glb`), relative to the scene file's
    /// directory or absolute.
    pub mesh: Option<String>,
    /// Unit of the mesh file's coordinates: `"mm"` or `"m"`. Default: `"m"` for glTF/GLB
    /// (glTF is defined in metres), the scene's `length_unit` for OBJ and STL. Only with
    /// `mesh`.
    pub mesh_unit: Option<LengthUnit>,
    /// STEP file (AP203, AP214, AP242), relative to the scene file's directory or
    /// absolute: every solid of the assembly becomes a part named `NAME/solid path`,
    /// with the file's own names, placements and length unit. Converted once with
    /// OpenCASCADE into `.pliant-cache/` beside the scene and reused while the STEP
    /// file is unchanged (`pliant import` converts ahead).
    pub step: Option<String>,
    /// Chord tolerance of the STEP tessellation (length unit), > 0: the largest
    /// distance of a triangle from the CAD surface. Default 0.5 mm. Only with `step`.
    pub chord_tolerance: Option<f64>,
    /// A box centred at `position`.
    #[serde(rename = "box")]
    pub box_: Option<BoxEntry>,
    /// A closed cylinder along the part's local z axis, centred at `position`.
    pub cylinder: Option<CylinderEntry>,
    /// A sphere centred at `position`.
    pub sphere: Option<SphereEntry>,
    /// Where the part's local origin goes (length unit). Default `[0, 0, 0]`.
    pub position: Option<Vec3>,
    /// Rotation of the part about its local origin, applied before `position`.
    /// Default: none.
    pub rotation: Option<RotateEntry>,
    /// Coulomb friction of hoses on this part. Default static 0.5, sliding 0.4.
    pub friction: Option<FrictionEntry>,
    /// How the part moves over time (a hinge, a slide, a periodic rocking, a sampled
    /// path), from where `position` and `rotation` put it. Default: it stands still.
    pub motion: Option<MotionEntry>,
    /// The name of the part this one moves with (a door on a body): its `motion`, if
    /// any, is carried by the parent's. Default: none.
    pub parent: Option<String>,
    /// Whether a live client or a script may move the part (`move_part`, `rotate_part`):
    /// contact then treats it as a moving part from the start. A part the timeline moves
    /// is movable without it. Not with `motion`. Default false.
    pub movable: Option<bool>,
}

/// `motion = { kind = "hinge" | "slide" | "periodic" | "path", … }`: the fields each kind
/// takes are listed with them; lengths in the scene's length unit, angles in degrees,
/// times in seconds, frequencies in Hz.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MotionEntry {
    /// `"hinge"` (turns about `axis` through `point` by `angle_deg`), `"slide"` (moves
    /// along `direction` by `distance`), `"periodic"` (oscillates about `centre`: `x`,
    /// `y`, `z`, `roll`, `pitch`, `yaw`), `"path"` (follows the poses of the CSV `file`,
    /// turning about `centre`).
    pub kind: String,
    /// Hinge: the axis direction (any non-zero length; right-hand rule).
    pub axis: Option<Vec3>,
    /// Hinge: a point on the axis (length unit).
    pub point: Option<Vec3>,
    /// Hinge: the angle over time (degrees).
    pub angle_deg: Option<KeyframesEntry>,
    /// Slide: the direction of travel (any non-zero length).
    pub direction: Option<Vec3>,
    /// Slide: the distance travelled over time (length unit).
    pub distance: Option<KeyframesEntry>,
    /// Periodic, path: the point turns are about (length unit). Default `[0, 0, 0]`.
    pub centre: Option<Vec3>,
    /// Periodic: oscillation along x, y, z (amplitude in the length unit).
    pub x: Option<OscillationEntry>,
    pub y: Option<OscillationEntry>,
    pub z: Option<OscillationEntry>,
    /// Periodic: oscillation about x (roll), y (pitch), z (yaw) through `centre`
    /// (amplitude in degrees), composed as yaw · pitch · roll.
    pub roll: Option<OscillationEntry>,
    pub pitch: Option<OscillationEntry>,
    pub yaw: Option<OscillationEntry>,
    /// Path: a CSV file, relative to the scene file's directory or absolute, one pose a
    /// line: `time_s, x, y, z, roll_deg, pitch_deg, yaw_deg` — the displacement of
    /// `centre` (length unit) and the turn about it (degrees, yaw · pitch · roll). Lines
    /// that do not start with a number (a header) are skipped; times must increase.
    pub file: Option<String>,
}

/// `{ times_s = [...], values = [...], smooth = true }`: a coordinate at increasing
/// times, held before the first and after the last; between two keyframes linear, or
/// with `smooth` a quintic smooth-step (at rest at every keyframe). Default `smooth = true`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct KeyframesEntry {
    pub times_s: Vec<f64>,
    pub values: Vec<f64>,
    pub smooth: Option<bool>,
}

/// `{ amplitude, frequency_hz, phase_deg }`: amplitude · sin(2π f t + phase).
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OscillationEntry {
    /// Amplitude (length unit for x, y, z; degrees for roll, pitch, yaw).
    pub amplitude: f64,
    /// Frequency (Hz), ≥ 0.
    pub frequency_hz: f64,
    /// Phase (degrees). Default 0.
    pub phase_deg: Option<f64>,
}

/// `box = { size = [x, y, z] }`.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxEntry {
    /// Edge lengths along the local x, y, z axes (length unit), each > 0.
    pub size: Vec3,
}

/// `cylinder = { radius, height, segments }`.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CylinderEntry {
    /// Radius (length unit), > 0.
    pub radius: f64,
    /// Height along the local z axis (length unit), > 0.
    pub height: f64,
    /// Number of sides of the inscribed prism, ≥ 3. Default 32.
    pub segments: Option<u32>,
}

/// `sphere = { radius, subdivisions }`.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SphereEntry {
    /// Radius (length unit), > 0.
    pub radius: f64,
    /// Subdivisions of an icosahedron (20·4ⁿ triangles). Default 3 (1280 triangles).
    pub subdivisions: Option<u32>,
}

/// `friction = { static, sliding }`: Coulomb coefficients, 0 ≤ sliding ≤ static.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionEntry {
    /// Static coefficient (before sliding), ≥ 0.
    #[serde(rename = "static")]
    pub static_: f64,
    /// Sliding coefficient, ≥ 0 and ≤ `static`.
    pub sliding: f64,
}

/// `delivered` of a hose: the shape it was delivered in.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum DeliveredEntry {
    /// `"straight"`: straight stock.
    Named(DeliveredName),
    /// `{ coil = { radius, pitch } }`: a coil (a helix; a flat coil with pitch 0).
    Coil { coil: CoilEntry },
    /// `{ path = [...] }`: a centre line as `path` gives one (from the origin; only its
    /// shape counts), of the hose's length within 1 % (scaled to it exactly).
    Path { path: Vec<SegmentEntry> },
}

/// A delivered shape by name.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DeliveredName {
    /// Straight stock: the routed hose is bent from straight.
    Straight,
}

/// `coil` of `delivered`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CoilEntry {
    /// Radius of the coil's centre line (length unit), > 0.
    pub radius: f64,
    /// Rise per turn (length unit), ≥ 0. Default 0 (a flat coil).
    #[serde(default)]
    pub pitch: f64,
}

/// A rest-shape node offset.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ImperfectionEntry {
    /// Node index; negative counts from the end (−1 = last node).
    pub node: i64,
    /// Offset added to the node's rest position (length unit).
    pub offset: Vec3,
}

/// One point or a list of points.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Points {
    /// A single point `[x, y, z]`.
    One(Vec3),
    /// Several points `[[x, y, z], …]`.
    Many(Vec<Vec3>),
}

impl Points {
    /// The points as a list.
    pub fn to_vec(&self) -> Vec<Vec3> {
        match self {
            Points::One(p) => vec![*p],
            Points::Many(ps) => ps.clone(),
        }
    }
}

/// A rotation about an axis.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RotateEntry {
    /// Rotation axis in the global frame (for a part: through its position); any
    /// non-zero length.
    pub axis: Vec3,
    /// Angle in degrees (right-hand rule); may exceed 360.
    pub angle_deg: f64,
}

/// `[[timeline]]`: one action, chosen by `action`; the other fields depend on it.
// Deserialised by hand (module `action_de`) so that errors inside an action keep their
// full field path; the serde attributes here describe the shape for the schema.
#[derive(Clone, Debug, JsonSchema)]
#[serde(tag = "action", rename_all = "snake_case", deny_unknown_fields)]
pub enum ActionEntry {
    /// Hold the node in all six degrees of freedom where it is now (on a part: carried
    /// with it, as `mount`).
    Fix(FixEntry),
    /// Hold the node to a part where it is now; it moves with the part.
    Mount(MountEntry),
    /// Drive the node along waypoints and/or rotate it; it stays held afterwards.
    Move(MoveEntry),
    /// Add a force and/or moment (global frame) at the node, at once or over a ramp.
    Load(LoadEntry),
    /// Remove the load called `name` from the node, or all its loads.
    Unload(UnloadEntry),
    /// Remove the fix / drive from the node.
    Release(NodeEntry),
    /// A cable tie bundles two hoses: the node and `to` are held at the distance they
    /// have now, for the rest of the run.
    Tie(TieEntry),
    /// A hand grabs the beam nearest to `at` (SPEC I1); its two nodes follow the hand.
    Grab(GrabEntry),
    /// Move a hand (holding a beam) along waypoints and/or turn it.
    MoveHand(MoveHandEntry),
    /// Turn a hand so that the beam it holds points along a direction.
    AlignHand(AlignHandEntry),
    /// A hand heads for a pose at bounded speed, as a live hand does (the timeline goes
    /// on at once; what `pliant replay --timeline` writes for a live session's moves).
    AimHand(AimHandEntry),
    /// A hand lets go of its beam.
    ReleaseHand(HandEntry),
    /// Move a part (shift it by or to an offset) over a duration, smooth start and stop.
    MovePart(MovePartEntry),
    /// Turn a part about an axis (by or to an angle) over a duration, smooth start and
    /// stop.
    RotatePart(RotatePartEntry),
    /// Simulate for a while.
    Run(RunEntry),
    /// Relax to static equilibrium: the residual force and moment within their tolerances, nothing moving, the kinetic energy below its threshold.
    Settle(SettleEntry),
}

/// The names of the `action` values, in the order of [`ActionEntry`].
pub const ACTION_NAMES: [&str; 16] = [
    "fix",
    "mount",
    "move",
    "load",
    "unload",
    "release",
    "tie",
    "grab",
    "move_hand",
    "align_hand",
    "aim_hand",
    "release_hand",
    "move_part",
    "rotate_part",
    "run",
    "settle",
];

/// `fix`: a node of a hose held where it is, in the world or on a part.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FixEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
    /// The part the node is fixed to (a part's `name`): it is carried with the part as
    /// `mount` carries it. Default: fixed in the world.
    #[serde(default)]
    pub part: Option<String>,
}

/// `unload`, `release`: a node of a hose.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NodeEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
}

/// `mount`: a node held to a part, carried with it as the part moves.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MountEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
    /// The part's name.
    pub part: String,
}

/// `tie`: a cable tie between a node of one hose and a node of another.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TieEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
    /// The node of the other hose it is tied to.
    pub to: NodeEntry,
}

/// `move`: drive a node along waypoints and/or rotate it.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MoveEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
    /// Absolute waypoints (length unit); the last is the target. Excludes `by`.
    pub to: Option<Points>,
    /// Waypoints as offsets from the node's position when the move starts (length
    /// unit). Excludes `to`.
    pub by: Option<Points>,
    /// Rotation applied on top of the node's orientation over the move.
    pub rotate: Option<RotateEntry>,
    /// Duration of the move (s), > 0.
    pub duration_s: f64,
    /// Whether the timeline waits for the move to end. Default true.
    pub wait: Option<bool>,
}

/// `grab`: a hand takes hold of the beam nearest to a point, or of a hose at a node.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GrabEntry {
    /// Hand index, 0 … 7.
    #[schemars(range(min = 0, max = 7))]
    pub hand: i64,
    /// Where the hand grabs (length unit): the beam nearest to it is taken, and the
    /// hand's frame starts here. Excludes `hose` and `node`.
    pub at: Option<Vec3>,
    /// With `node`: the hand takes this hose at that node, wherever the node is when
    /// the grab runs (for an end node: its end beam). Excludes `at`.
    pub hose: Option<String>,
    /// Node index of `hose`; negative counts from the end (−1 = last).
    pub node: Option<i64>,
    /// How the hand holds the hose: `firm` (default; the beam turns with the hand),
    /// `axial` (position held, the hose may turn about its own axis in the hand) or
    /// `ball` (position held, free to turn about every axis).
    #[serde(default)]
    pub grip: GripName,
}

/// `align_hand`: turn a hand so that the beam it holds points along a direction, in place
/// or while moving it.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AlignHandEntry {
    /// Hand index, 0 … 7; it must be holding a beam.
    #[schemars(range(min = 0, max = 7))]
    pub hand: i64,
    /// Where the held beam's axis ends up pointing (any non-zero length), the axis taken
    /// towards the nearer end of its hose.
    pub direction: Vec3,
    /// Absolute waypoints (length unit) the hand moves through while it turns; the last
    /// is the target. Excludes `by`. Without either it turns where it is.
    pub to: Option<Points>,
    /// Waypoints as offsets from the hand's position when the turn starts (length unit).
    /// Excludes `to`.
    pub by: Option<Points>,
    /// Duration of the turn (s), > 0.
    pub duration_s: f64,
}

/// `grip` of a grab.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GripName {
    /// Six degrees of freedom.
    #[default]
    Firm,
    /// Free to turn about the hose's own axis.
    Axial,
    /// Free to turn about every axis (a ball joint).
    Ball,
}

/// `move_hand`: drive a hand along waypoints and/or rotate it.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MoveHandEntry {
    /// Hand index, 0 … 7; it must be holding a beam (an earlier `grab`, not released).
    #[schemars(range(min = 0, max = 7))]
    pub hand: i64,
    /// Absolute waypoints (length unit); the last is the target. Excludes `by`.
    pub to: Option<Points>,
    /// Waypoints as offsets from the hand's position when the move starts (length
    /// unit). Excludes `to`.
    pub by: Option<Points>,
    /// Rotation applied on top of the hand's orientation over the move.
    pub rotate: Option<RotateEntry>,
    /// Duration of the move (s), > 0. Give either this or `speed_m_s`.
    pub duration_s: Option<f64>,
    /// Mean speed along the path (m/s, always SI), > 0: the duration is the path's length
    /// divided by it. Give either this or `duration_s`.
    pub speed_m_s: Option<f64>,
    /// Move along a Catmull-Rom spline through the waypoints instead of straight lines.
    /// Default false.
    pub spline: Option<bool>,
    /// Whether the timeline waits for the move to end. Default true.
    pub wait: Option<bool>,
}

/// `aim_hand`: a hand heads for a pose at bounded speed and acceleration (2 m/s,
/// 20 m/s², 4π rad/s), as a hand steered by a pointer or a VR controller does.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AimHandEntry {
    /// Hand index (0 … 7).
    #[schemars(range(min = 0, max = 7))]
    pub hand: i64,
    /// Target position, in the scene's length unit.
    pub position: Vec3,
    /// Target orientation as a unit quaternion [w, x, y, z] (global frame); omitted: the
    /// orientation the hand aims at now.
    pub orientation_wxyz: Option<[f64; 4]>,
}

/// `move_part`: a part shifted over a duration (smooth start and stop), with everything
/// mounted on it and the parts it carries. The part must not have a `motion`; a part a
/// timeline moves is made `movable` by the loader.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MovePartEntry {
    /// The part's name.
    pub part: String,
    /// Offset from where the part is when the action starts (length unit; the parent's
    /// axes for a part with a parent). Excludes `to`.
    pub by: Option<Vec3>,
    /// Offset of the part's centre (its bounding box's) from where the scene placed it
    /// (length unit): `[0, 0, 0]` brings the centre back. Excludes `by`.
    pub to: Option<Vec3>,
    /// Duration of the move (s), > 0.
    pub duration_s: f64,
    /// Whether the timeline waits for the move to end. Default true.
    pub wait: Option<bool>,
}

/// `rotate_part`: a part turned about an axis over a duration (smooth start and stop).
/// The part must not have a `motion`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RotatePartEntry {
    /// The part's name.
    pub part: String,
    /// Rotation axis (any non-zero length; the parent's axes for a part with a parent).
    pub axis: Vec3,
    /// A point on the axis, where the scene placed the part (length unit): it is carried
    /// with the part, as a hinge pin. Default: the centre of the part's bounding box.
    pub point: Option<Vec3>,
    /// Angle to turn by from where the part is (degrees, right-hand rule). Excludes
    /// `to_deg`.
    pub by_deg: Option<f64>,
    /// Angle about `axis` from where the scene placed the part (degrees): `0` turns it
    /// back. Needs every earlier turn of the part to be about the same axis. Excludes
    /// `by_deg`.
    pub to_deg: Option<f64>,
    /// Duration of the turn (s), > 0.
    pub duration_s: f64,
    /// Whether the timeline waits for the turn to end. Default true.
    pub wait: Option<bool>,
}

/// `release_hand`: a hand lets go.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HandEntry {
    /// Hand index, 0 … 7; it must be holding a beam.
    #[schemars(range(min = 0, max = 7))]
    pub hand: i64,
}

/// `load`: a constant force and/or moment at a node.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
    /// Force (N) in the global frame. Default zero; give `force_n` and/or `moment_nm`.
    pub force_n: Option<Vec3>,
    /// Moment (N·m) in the global frame. Default zero; give `force_n` and/or `moment_nm`.
    pub moment_nm: Option<Vec3>,
    /// The load rises linearly from zero to its full value over this many seconds
    /// (default 0: in full at once).
    pub ramp_s: Option<f64>,
    /// A name for this load, so that `unload` with this `name` removes it alone (unique
    /// among the loads acting at a time).
    pub name: Option<String>,
}

/// `unload`: remove the dead load called `name` from the node, or every dead load on it.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct UnloadEntry {
    /// Hose name.
    pub hose: String,
    /// Node index; negative counts from the end (−1 = last).
    pub node: i64,
    /// The name an earlier `load` on this node gave; default: remove all its loads.
    pub name: Option<String>,
}

/// `run`: simulate for a while.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RunEntry {
    /// Duration (s), > 0.
    pub duration_s: f64,
}

/// `settle`: relax to static equilibrium (the residual force and moment within their
/// tolerances, nothing moving, the kinetic energy below its threshold).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SettleEntry {
    /// Largest out-of-balance force on a free node at rest (N), > 0. Default 1e-3.
    pub force_tolerance_n: Option<f64>,
    /// Largest out-of-balance moment on a free node at rest (N·m), > 0. Default 1e-4.
    pub moment_tolerance_nm: Option<f64>,
    /// Rest also needs the total kinetic energy below this (J), > 0. Default 1e-6.
    pub kinetic_energy_j: Option<f64>,
    /// Give up after this long (s), > 0. Default 30.
    pub max_duration_s: Option<f64>,
    /// How rest is reached: `dynamic` (default) relaxes with the scene's solver all the
    /// way; `static` relaxes until the hands and fasteners are done, then takes the
    /// quasi-static solver's stable equilibrium from there, confirmed by the same rest
    /// criterion (relaxing on where it is not met or the static solve fails);
    /// `static_equilibrium` the same up to the static solve, and at rest at its stable
    /// equilibrium, unconfirmed by the scene's solver.
    pub finish: Option<SettleFinishName>,
}

/// `finish` of a settle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SettleFinishName {
    /// Dynamic relaxation all the way.
    #[default]
    Dynamic,
    /// The quasi-static solver finishes once the hands and fasteners are done.
    Static,
    /// As `static`, at rest at the static solver's stable equilibrium (unconfirmed).
    StaticEquilibrium,
}
