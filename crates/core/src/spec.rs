//! What a caller hands the core to build a [`crate::Model`]: plain SI data, already
//! validated by the scene loader (or by code using the library directly).

use crate::contact::HoseContactRule;
use crate::{Material, Section};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// One hose, discretised: its stress-free rest shape as a polyline of nodes.
///
/// The rest shape is stress-free: an imperfection is expressed by moving rest nodes
/// (SPEC §7), not by a load. Node material frames are built by the core from the
/// polyline (tangent = mean of adjacent chords, cross-section axes by parallel transport
/// starting from `normal_hint`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HoseSpec {
    /// Name shown in outputs.
    pub name: String,
    /// Wall material.
    pub material: Material,
    /// Rest positions of the nodes \[m\]; at least 2, consecutive nodes distinct.
    pub nodes: Vec<DVec3>,
    /// Cross-section per element (`nodes.len() − 1` entries, element `e` between nodes
    /// `e` and `e + 1`), or one entry for a uniform hose.
    pub sections: Vec<Section>,
    /// Preferred direction of the first node's local y axis; `None` → any axis normal
    /// to the first tangent. Only affects how orientations are reported.
    pub normal_hint: Option<DVec3>,
}

/// A hose's stress-free shape when it differs from the shape it is routed in (SPEC X2,
/// pre-deformation): the hose as delivered — straight stock, a coil, a folded hose —
/// whose set the routed hose keeps. Applied by [`crate::Model::with_delivered_shapes`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DeliveredShape {
    /// The hose (index into [`WorldSpec::hoses`]).
    pub hose: usize,
    /// The delivered shape's nodes \[m\], as many as the hose's; where it lies does not
    /// matter, only its shape.
    pub nodes: Vec<DVec3>,
    /// Preferred direction of the first node's local y axis in the delivered shape (the
    /// material frames follow both shapes by parallel transport from it).
    pub normal_hint: Option<DVec3>,
}

impl HoseSpec {
    /// The section of element `e` (between nodes `e` and `e + 1`).
    pub fn element_section(&self, e: usize) -> &Section {
        &self.sections[e.min(self.sections.len() - 1)]
    }

    /// The section a node sits in: the thicker of its (one or two) elements — what a
    /// clip or stub at the node grips, and the radius contact sees there.
    pub fn node_section(&self, i: usize) -> &Section {
        let before = self.element_section(i.saturating_sub(1));
        let after = self.element_section(i.min(self.nodes.len().saturating_sub(2)));
        if after.d_outer > before.d_outer {
            after
        } else {
            before
        }
    }
}

/// Global simulation settings (SPEC P4, P6). All SI.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimSettings {
    /// Gravitational acceleration [m/s²]; zero vector switches gravity off.
    pub gravity: DVec3,
    /// Mass-proportional Rayleigh damping α \[1/s\].
    pub damping_mass: f64,
    /// Stiffness-proportional Rayleigh damping β \[s\]; `None` → automatic default.
    pub damping_stiffness: Option<f64>,
    /// Safety factor on the stable time step (the thesis uses 0.5).
    pub time_step_safety: f64,
    /// Fixed time step \[s\]; `None` → computed from the model. A fixed step larger than the
    /// stable one is refused when the model is built.
    pub time_step: Option<f64>,
    /// Which solver advances the simulation, and its steps.
    #[serde(default)]
    pub solver: crate::settings::SolverSettings,
    /// Threads the explicit step may use; `None` → 1 for a single hose, the
    /// machine's logical cores for several. The environment variable `PLIANT_THREADS`
    /// overrides both. Results are the same for any number ([`crate::parallel`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub threads: Option<usize>,
    /// Which pairs of beams hose–hose contact considers (all; all but those overlapping
    /// in the drawn shape; none).
    #[serde(default, skip_serializing_if = "HoseContactRule::is_default")]
    pub hose_contact: HoseContactRule,
    /// Most beam pairs hose–hose contact may list at once (16 B each,
    /// [`crate::contact::BYTES_PER_CONTACT_PAIR`]): a run whose hoses pile up beyond it
    /// is declared diverged ([`crate::health::DivergenceKind::ContactPairs`]) instead of
    /// growing the list without bound. A scene loader sets it to what its memory limit
    /// leaves room for.
    #[serde(
        default = "default_max_contact_pairs",
        skip_serializing_if = "is_default_max_contact_pairs"
    )]
    pub max_contact_pairs: usize,
    /// Mass scaling s ≥ 1 for quasi-static runs ([`crate::model::Model::mass_scaling`]):
    /// every node's and body's inertia is s times its mass, its weight and mass damping
    /// stay as they are. 1 (the default): the physical dynamics.
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub mass_scaling: f64,
}

fn one() -> f64 {
    1.0
}

fn is_one(s: &f64) -> bool {
    *s == 1.0
}

/// Default of [`SimSettings::max_contact_pairs`]: the pairs 4 GiB hold.
pub const DEFAULT_MAX_CONTACT_PAIRS: usize = 1 << 28;

fn default_max_contact_pairs() -> usize {
    DEFAULT_MAX_CONTACT_PAIRS
}

fn is_default_max_contact_pairs(n: &usize) -> bool {
    *n == DEFAULT_MAX_CONTACT_PAIRS
}

impl Default for SimSettings {
    fn default() -> Self {
        Self {
            gravity: DVec3::new(0.0, 0.0, -9.81),
            damping_mass: 1.0,
            damping_stiffness: None,
            time_step_safety: 0.5,
            time_step: None,
            solver: Default::default(),
            threads: None,
            hose_contact: HoseContactRule::All,
            max_contact_pairs: DEFAULT_MAX_CONTACT_PAIRS,
            mass_scaling: 1.0,
        }
    }
}

/// A rigid part of the environment (CAD part, sheet, primitive) as a triangle mesh in
/// world coordinates — the loader has already applied the part's pose and unit. That is
/// its reference placement: a part with a `motion` (or a moving `parent`) is carried from
/// it by its pose over time ([`crate::kinematics`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RigidPartSpec {
    /// Name shown in outputs.
    pub name: String,
    /// Vertex positions \[m\], world frame.
    pub vertices: Vec<DVec3>,
    /// Triangles as indices into `vertices` (orientation may be inconsistent; contact
    /// must not rely on it).
    pub triangles: Vec<[u32; 3]>,
    /// Coulomb friction coefficient before sliding (static) against hoses.
    pub friction_static: f64,
    /// Coulomb friction coefficient while sliding.
    pub friction_sliding: f64,
    /// How the part moves (in its parent's reference placement); `None`: it stands still
    /// (or moves only with its parent).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<crate::kinematics::PartMotion>,
    /// The part (index into the world's parts) this one is carried by.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parent: Option<usize>,
    /// Whether inputs may move the part ([`crate::kinematics::PartMoves`]): contact
    /// then treats it as a moving part from the start.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub movable: bool,
}

impl RigidPartSpec {
    /// A standing box from corner `lo` to corner `hi` \[m\] (12 triangles), with Coulomb
    /// coefficients (μ_s, μ_k).
    pub fn cuboid(name: &str, lo: DVec3, hi: DVec3, (mu_static, mu_sliding): (f64, f64)) -> Self {
        let corner = |i: usize| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        };
        Self {
            name: name.into(),
            vertices: (0..8).map(corner).collect(),
            triangles: vec![
                [0, 2, 3],
                [0, 3, 1],
                [4, 5, 7],
                [4, 7, 6],
                [0, 1, 5],
                [0, 5, 4],
                [2, 6, 7],
                [2, 7, 3],
                [0, 4, 6],
                [0, 6, 2],
                [1, 3, 7],
                [1, 7, 5],
            ],
            friction_static: mu_static,
            friction_sliding: mu_sliding,
            motion: None,
            parent: None,
            movable: false,
        }
    }
}

/// A whole world to simulate.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WorldSpec {
    pub hoses: Vec<HoseSpec>,
    /// Rigid environment (SPEC L4); empty → no contact with parts.
    #[serde(default)]
    pub rigid_parts: Vec<RigidPartSpec>,
    pub settings: SimSettings,
}
