//! The Model: what the world is (topology, rest geometry, stiffness, masses, settings),
//! fixed after building, in the spirit of MuJoCo's mjModel.

use crate::contact::{HoseContactModel, RigidEnvironment};
use crate::junction::Junction;
use crate::kinematics::PartKinematics;
use crate::rod::element::BeamElement;
use crate::rod::element_block::PackedElements;
use crate::rod::frames::{curve_frames, node_frames};
use crate::rod::inelastic::InelasticElements;
use crate::rod::mass::half_element_mass;
use crate::rod::stiffened::{RigidBody, StiffenedSpan};
use crate::rod::timestep::{stable_time_step, TimeStepReport};
use crate::section::SectionProperties;
use crate::settings::SolverSettings;
use crate::spec::{DeliveredShape, HoseSpec, RigidPartSpec, SimSettings, WorldSpec};
use glam::{DQuat, DVec3};
use serde::Serialize;

/// Where one hose's nodes and elements lie in the model's flat arrays.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HoseInfo {
    pub name: String,
    pub first_node: usize,
    pub node_count: usize,
    pub first_element: usize,
    pub element_count: usize,
}

impl HoseInfo {
    /// Global index of local node `i` of this hose.
    pub fn node(&self, i: usize) -> usize {
        self.first_node + i
    }
    pub fn nodes(&self) -> std::ops::Range<usize> {
        self.first_node..self.first_node + self.node_count
    }
}

/// The built world. Nodes of all hoses are stored in one flat array.
#[derive(Clone, Debug)]
pub struct Model {
    pub hoses: Vec<HoseInfo>,
    pub elements: Vec<BeamElement>,
    /// Lumped translational mass per node \[kg\], times [`Self::mass_scaling`]: the
    /// inertia the solvers move.
    pub mass: Vec<f64>,
    /// Lumped isotropic rotational inertia per node \[kg·m²\] (see [`crate::rod::mass`]),
    /// times [`Self::mass_scaling`].
    pub inertia: Vec<f64>,
    /// Outer radius per node \[m\] (for drawing and contact).
    pub radius: Vec<f64>,
    /// Rest positions \[m\] and rest material frames.
    pub rest_x: Vec<DVec3>,
    pub rest_q: Vec<DQuat>,
    /// Gravity per unit of [`Self::mass`] \[m/s²\]: g / s, so that `mass · gravity` is
    /// the physical weight m g whatever the mass scaling s.
    pub gravity: DVec3,
    /// Mass-proportional Rayleigh damping per unit of [`Self::mass`] \[1/s\]: α / s, so
    /// that the damping force α m v is the one the scene asks for.
    pub damping_mass: f64,
    /// Mass scaling s ≥ 1 ([`crate::spec::SimSettings::mass_scaling`]): the inertia of
    /// every node and body is s times its mass, its weight and mass damping are not. The
    /// explicit step grows by √s (every natural frequency falls by √s) while the
    /// equilibria stay exactly the same — the standard device for quasi-static processes
    /// in explicit dynamics (Belytschko, Liu & Moran, "Nonlinear Finite Elements", §6.5;
    /// Olovsson, Simonsson & Unosson 2005): inertial forces grow by s, so it is right only
    /// while they stay small against the static ones, which a study checks by running
    /// some of its variants again unscaled.
    pub mass_scaling: f64,
    /// Stiffness-proportional Rayleigh damping β \[s\] (resolved default if not given).
    pub damping_stiffness: f64,
    /// The time step used \[s\].
    pub time_step: f64,
    /// How the time step was chosen.
    pub time_step_report: TimeStepReport,
    /// Rigid parts hoses collide with (SPEC L4); empty when the scene has none.
    pub environment: RigidEnvironment,
    /// How the parts move (SPEC K1); every part still when none has a motion.
    pub kinematics: PartKinematics,
    /// Stiffened sections (SPEC M6), and for each node the body it belongs to.
    pub bodies: Vec<RigidBody>,
    pub body_of: Vec<Option<usize>>,
    /// Junctions joining hose ends into networks (SPEC N1; [`crate::junction`]).
    pub junctions: Vec<Junction>,
    /// The parts that ride on junction bodies as their shapes
    /// ([`crate::junction_shape`]).
    pub junction_shapes: crate::junction_shape::JunctionShapes,
    /// Per hose: its network, the smallest index of the hoses joined to it through
    /// junctions (its own index when it joins none).
    pub hose_network: Vec<usize>,
    /// The solver the scene asks for; callers may choose another.
    pub solver: SolverSettings,
    /// Per-beam constants of hose–hose contact (SPEC L5).
    pub hose_contact: HoseContactModel,
    /// The elements in blocks of four for the explicit solver's kernel
    /// ([`crate::rod::element_block`]); built with the model.
    pub packed: PackedElements,
    /// The elements that yield or relax and their laws (SPEC X1, X2,
    /// [`crate::rod::inelastic`]); empty when every material is elastic.
    pub inelastic: InelasticElements,
    /// Threads the explicit step may use ([`SimSettings::threads`], resolved; a caller
    /// may change it — results do not depend on it).
    pub threads: usize,
    /// Groups of consecutive hoses (ranges of hose indices) that the explicit step hands
    /// to its threads as one piece of work each.
    pub hose_chunks: Vec<std::ops::Range<usize>>,
}

/// The environment variable that sets the explicit step's thread count, overriding the
/// settings (`pliant … --threads N` sets it).
pub const THREADS_ENV: &str = "PLIANT_THREADS";

/// Largest mass scaling accepted: the explicit step grows by √s, 100 × at most.
pub const MAX_MASS_SCALING: f64 = 1e4;

/// Most Newton iterations the static solver may be allowed per equilibrium (each costs
/// one assembly and factorisation: 10 000 bound the work of one input).
pub const MAX_STATIC_ITERATIONS: usize = 10_000;

/// Threads for a world of `hoses` hoses: `PLIANT_THREADS` if set to a positive number,
/// else `setting`, else 1 for one hose and the logical cores for several.
pub fn resolve_threads(setting: Option<usize>, hoses: usize) -> usize {
    let env = std::env::var(THREADS_ENV)
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .filter(|&n| n > 0);
    env.or(setting.filter(|&n| n > 0)).unwrap_or(if hoses > 1 {
        crate::parallel::available_cores()
    } else {
        1
    })
}

/// Consecutive hoses grouped into pieces of at least max(total/(4 · cores), 32) elements
/// (the last piece may be smaller): enough pieces to balance two or more threads, few
/// enough that handing them out costs nothing.
fn hose_chunks(hoses: &[HoseInfo]) -> Vec<std::ops::Range<usize>> {
    let total: usize = hoses.iter().map(|h| h.element_count).sum();
    let target = (total / (4 * crate::parallel::available_cores())).max(32);
    let mut chunks = Vec::new();
    let (mut start, mut size) = (0, 0);
    for (h, info) in hoses.iter().enumerate() {
        size += info.element_count;
        if size >= target {
            chunks.push(start..h + 1);
            (start, size) = (h + 1, 0);
        }
    }
    if start < hoses.len() {
        chunks.push(start..hoses.len());
    }
    chunks
}

/// Why a world spec could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    #[error("hose '{hose}': {reason}")]
    Hose { hose: String, reason: String },
    #[error("settings: {0}")]
    Settings(String),
    #[error("the world has no hose")]
    Empty,
    #[error("{0}")]
    RigidPart(String),
    #[error("junction '{junction}': {reason}")]
    Junction { junction: String, reason: String },
}

fn finite(v: DVec3) -> bool {
    v.is_finite()
}

fn check_hose(h: &HoseSpec) -> Result<(), ModelError> {
    let err = |reason: String| {
        Err(ModelError::Hose {
            hose: h.name.clone(),
            reason,
        })
    };
    if h.nodes.len() < 2 {
        return err(format!("needs at least 2 nodes, has {}", h.nodes.len()));
    }
    if h.sections.len() != 1 && h.sections.len() != h.nodes.len() - 1 {
        return err(format!(
            "has {} sections for {} elements (give 1 or one per element)",
            h.sections.len(),
            h.nodes.len() - 1
        ));
    }
    for (i, p) in h.nodes.iter().enumerate() {
        if !finite(*p) {
            return err(format!("node {i} position is not finite: {p:?}"));
        }
        if i > 0 && (h.nodes[i] - h.nodes[i - 1]).length() <= 1e-9 {
            return err(format!(
                "nodes {} and {i} coincide (zero-length element)",
                i - 1
            ));
        }
    }
    for (i, s) in h.sections.iter().enumerate() {
        if !(s.d_outer > 0.0 && s.d_outer.is_finite() && s.d_inner >= 0.0 && s.d_inner < s.d_outer)
        {
            return err(format!(
                "section {i} invalid: d_inner {} m, d_outer {} m",
                s.d_inner, s.d_outer
            ));
        }
        for (name, value) in s.given.named() {
            if value.is_some_and(|v| !(v > 0.0 && v.is_finite())) {
                return err(format!(
                    "section {i}: {name} must be positive and finite, is {}",
                    value.unwrap_or_default()
                ));
            }
        }
    }
    let m = &h.material;
    let positive = |v: f64| v > 0.0 && v.is_finite();
    if !positive(m.e_tension) || !positive(m.e_compression) || !positive(m.density) {
        return err("material moduli and density must be positive and finite".into());
    }
    if let Some(eb) = m.e_bending {
        if !positive(eb) {
            return err(format!("bending modulus must be positive, is {eb}"));
        }
    }
    if !(m.poisson > -1.0 && m.poisson < 0.5) {
        return err(format!("Poisson's ratio {} outside (−1, 0.5)", m.poisson));
    }
    if m.plasticity.is_some() && !m.relaxation.is_empty() {
        return err("a material either yields or relaxes, not both".into());
    }
    for (i, p) in m.relaxation.iter().enumerate() {
        if !(p.weight > 0.0 && p.weight < 1.0 && positive(p.time)) {
            return err(format!(
                "relaxation term {i}: needs a weight in (0, 1) and a positive finite time, \
                 has {} and {} s",
                p.weight, p.time
            ));
        }
    }
    let weights: f64 = m.relaxation.iter().map(|p| p.weight).sum();
    if weights >= 1.0 {
        return err(format!(
            "relaxation weights sum to {weights}: the long-term modulus E₀ (1 − Σ g) must stay \
             positive (Σ g < 1)"
        ));
    }
    if let Some(law) = &m.plasticity {
        if !positive(law.yield_stress) {
            return err(format!(
                "yield stress must be positive and finite, is {} Pa",
                law.yield_stress
            ));
        }
        if !(law.hardening_modulus >= 0.0 && law.hardening_modulus.is_finite()) {
            return err(format!(
                "hardening modulus must be ≥ 0 and finite, is {} Pa",
                law.hardening_modulus
            ));
        }
        if let Some(i) = h.sections.iter().position(|s| s.given.any()) {
            return err(format!(
                "section {i} gives its stiffness or mass directly, but a yielding material \
                 takes them from the tube (give the diameters only)"
            ));
        }
    }
    Ok(())
}

impl Model {
    /// Builds the model: node frames by parallel transport, elements, lumped masses, the
    /// stable time step and damping defaults.
    pub fn build(spec: &WorldSpec) -> Result<Model, ModelError> {
        if spec.hoses.is_empty() {
            return Err(ModelError::Empty);
        }
        check_settings(&spec.settings)?;
        let total_nodes: usize = spec.hoses.iter().map(|h| h.nodes.len()).sum();
        let mut model = Model {
            hoses: Vec::with_capacity(spec.hoses.len()),
            elements: Vec::with_capacity(total_nodes),
            mass: vec![0.0; total_nodes],
            inertia: vec![0.0; total_nodes],
            radius: Vec::with_capacity(total_nodes),
            rest_x: Vec::with_capacity(total_nodes),
            rest_q: Vec::with_capacity(total_nodes),
            gravity: spec.settings.gravity / spec.settings.mass_scaling,
            damping_mass: spec.settings.damping_mass / spec.settings.mass_scaling,
            mass_scaling: spec.settings.mass_scaling,
            damping_stiffness: 0.0,
            time_step: 0.0,
            time_step_report: TimeStepReport::default(),
            environment: RigidEnvironment::build(&spec.rigid_parts)
                .map_err(ModelError::RigidPart)?,
            kinematics: part_kinematics(&spec.rigid_parts).map_err(ModelError::RigidPart)?,
            bodies: Vec::new(),
            body_of: vec![None; total_nodes],
            junctions: Vec::new(),
            junction_shapes: Default::default(),
            hose_network: (0..spec.hoses.len()).collect(),
            solver: spec.settings.solver,
            hose_contact: HoseContactModel::default(),
            packed: PackedElements::default(),
            inelastic: InelasticElements::new(),
            threads: 1,
            hose_chunks: Vec::new(),
        };
        for h in &spec.hoses {
            check_hose(h)?;
            model.add_hose(h);
        }
        for m in model.mass.iter_mut().chain(model.inertia.iter_mut()) {
            *m *= model.mass_scaling;
        }
        let report = stable_time_step(&model, &spec.settings)?;
        model.damping_stiffness = report.damping_stiffness;
        model.time_step = report.chosen;
        model.time_step_report = report;
        model.hose_contact = HoseContactModel::new(&model, spec.settings.hose_contact);
        model.hose_contact.max_pairs = spec.settings.max_contact_pairs;
        model.packed = PackedElements::new(&model.elements, &model.hoses);
        model.threads = resolve_threads(spec.settings.threads, model.hoses.len());
        model.hose_chunks = hose_chunks(&model.hoses);
        Ok(model)
    }

    fn add_hose(&mut self, h: &HoseSpec) {
        let first_node = self.rest_x.len();
        let first_element = self.elements.len();
        let frames = node_frames(&h.nodes, h.normal_hint);
        for (i, (x, q)) in h.nodes.iter().zip(&frames).enumerate() {
            self.rest_x.push(*x);
            self.rest_q.push(*q);
            self.radius.push(h.node_section(i).outer_radius());
        }
        for i in 0..h.nodes.len() - 1 {
            let (a, b) = (first_node + i, first_node + i + 1);
            let props = SectionProperties::of(h.element_section(i), &h.material);
            let el = BeamElement::with_properties(
                (a, b),
                [h.nodes[i], h.nodes[i + 1]],
                [frames[i], frames[i + 1]],
                &props,
            );
            let (m, j) = half_element_mass(&props, 0.5 * el.rest_length);
            for n in [a, b] {
                self.mass[n] += m;
                self.inertia[n] += j;
            }
            self.elements.push(el);
        }
        self.inelastic
            .add_hose(&mut self.elements, first_element, &h.material, |i| {
                *h.element_section(i)
            });
        self.hoses.push(HoseInfo {
            name: h.name.clone(),
            first_node,
            node_count: h.nodes.len(),
            first_element,
            element_count: h.nodes.len() - 1,
        });
    }

    /// Makes spans of hoses rigid (SPEC M6). Spans must lie within their hose, hold at
    /// least two nodes, and not overlap.
    pub fn with_stiffened_spans(mut self, spans: &[StiffenedSpan]) -> Result<Model, ModelError> {
        for span in spans {
            let Some(info) = self.hoses.get(span.hose) else {
                return Err(ModelError::Settings(format!(
                    "stiffened span names hose {} of {}",
                    span.hose,
                    self.hoses.len()
                )));
            };
            let err = |reason: String| {
                Err(ModelError::Hose {
                    hose: info.name.clone(),
                    reason,
                })
            };
            if span.first >= span.last || span.last >= info.node_count {
                return err(format!(
                    "stiffened span {}..={} must hold at least two of the hose's {} nodes",
                    span.first, span.last, info.node_count
                ));
            }
            let nodes = info.node(span.first)..info.node(span.last) + 1;
            if nodes.clone().any(|i| self.body_of[i].is_some()) {
                return err(format!(
                    "stiffened span {}..={} overlaps another",
                    span.first, span.last
                ));
            }
            let body = RigidBody::new(
                nodes.clone().collect(),
                &self.rest_x,
                &self.rest_q,
                &self.mass,
                &self.inertia,
            );
            for i in nodes {
                self.body_of[i] = Some(self.bodies.len());
            }
            self.bodies.push(body);
        }
        let max_pairs = self.hose_contact.max_pairs;
        self.hose_contact = HoseContactModel::new(&self, self.hose_contact.rule);
        self.hose_contact.max_pairs = max_pairs;
        Ok(self)
    }

    /// Gives hoses the stress-free shape they were delivered in (SPEC X2,
    /// pre-deformation): each element's rest length and rest frame offsets come from the
    /// delivered shape, while the hose starts where it is routed (`rest_x`, `rest_q`),
    /// holding the difference as strain. Lumped masses stay those of the routed elements
    /// (their lengths differ by the chord–arc difference, (κ l)²/24). The stable time step
    /// is found again under `settings` (the build's).
    pub fn with_delivered_shapes(
        mut self,
        shapes: &[DeliveredShape],
        settings: &SimSettings,
    ) -> Result<Model, ModelError> {
        if shapes.is_empty() {
            return Ok(self);
        }
        for shape in shapes {
            let Some(info) = self.hoses.get(shape.hose) else {
                return Err(ModelError::Settings(format!(
                    "delivered shape names hose {} of {}",
                    shape.hose,
                    self.hoses.len()
                )));
            };
            let err = |reason: String| ModelError::Hose {
                hose: info.name.clone(),
                reason,
            };
            if shape.nodes.len() != info.node_count {
                return Err(err(format!(
                    "its delivered shape has {} nodes, the hose {}",
                    shape.nodes.len(),
                    info.node_count
                )));
            }
            if let Some(k) = shape.nodes.windows(2).position(|w| {
                !(w[0].is_finite() && w[1].is_finite()) || (w[1] - w[0]).length() == 0.0
            }) {
                return Err(err(format!(
                    "its delivered shape's nodes {k} and {} coincide or are not finite",
                    k + 1
                )));
            }
            // both shapes' frames follow their curves to the ends, so that the end
            // elements bend as the others do
            let routed = info.first_node..info.first_node + info.node_count;
            let routed_frames = curve_frames(&self.rest_x[routed.clone()], shape.normal_hint);
            self.rest_q[routed].copy_from_slice(&routed_frames);
            let frames = curve_frames(&shape.nodes, shape.normal_hint);
            for i in 0..info.element_count {
                self.elements[info.first_element + i].set_rest_shape(
                    [shape.nodes[i], shape.nodes[i + 1]],
                    [frames[i], frames[i + 1]],
                );
            }
        }
        let report = stable_time_step(&self, settings)?;
        self.damping_stiffness = report.damping_stiffness;
        self.time_step = report.chosen;
        self.time_step_report = report;
        self.packed = PackedElements::new(&self.elements, &self.hoses);
        Ok(self)
    }

    pub fn node_count(&self) -> usize {
        self.rest_x.len()
    }
}

fn check_settings(s: &SimSettings) -> Result<(), ModelError> {
    let bad = |m: String| Err(ModelError::Settings(m));
    if !s.gravity.is_finite() {
        return bad(format!("gravity is not finite: {:?}", s.gravity));
    }
    if !(s.damping_mass >= 0.0 && s.damping_mass.is_finite()) {
        return bad(format!("mass damping must be ≥ 0, is {}", s.damping_mass));
    }
    if !(s.mass_scaling >= 1.0 && s.mass_scaling <= MAX_MASS_SCALING) {
        return bad(format!(
            "mass scaling must lie in 1 … {MAX_MASS_SCALING}, is {}",
            s.mass_scaling
        ));
    }
    if let Some(b) = s.damping_stiffness {
        if !(b >= 0.0 && b.is_finite()) {
            return bad(format!("stiffness damping must be ≥ 0, is {b}"));
        }
    }
    if !(s.time_step_safety > 0.0 && s.time_step_safety <= 1.0) {
        return bad(format!(
            "time step safety must lie in (0, 1], is {}",
            s.time_step_safety
        ));
    }
    if let Some(dt) = s.time_step {
        if !(dt > 0.0 && dt.is_finite()) {
            return bad(format!("time step must be positive, is {dt}"));
        }
    }
    for (name, v) in [
        ("implicit time step", s.solver.implicit_time_step),
        ("static input step", s.solver.static_input_step),
    ] {
        if !(v > 0.0 && v <= 1.0) {
            return bad(format!("{name} must lie in (0, 1] s, is {v}"));
        }
    }
    let iterations = s.solver.static_max_iterations;
    if !(1..=MAX_STATIC_ITERATIONS).contains(&iterations) {
        return bad(format!(
            "static solver iterations must lie in 1 … {MAX_STATIC_ITERATIONS}, are {iterations}"
        ));
    }
    Ok(())
}

/// The parts' motions and parents; errors name the part.
fn part_kinematics(parts: &[RigidPartSpec]) -> Result<PartKinematics, String> {
    let motions = parts.iter().map(|p| p.motion.clone()).collect();
    let parents = parts.iter().map(|p| p.parent).collect();
    let movable = parts.iter().map(|p| p.movable).collect();
    PartKinematics::with_movable(motions, parents, movable).map_err(|e| {
        // "part k: …" → the part's name
        match e.split_once(':').and_then(|(head, rest)| {
            let k: usize = head.strip_prefix("part ")?.parse().ok()?;
            Some(format!("rigid part '{}':{rest}", parts.get(k)?.name))
        }) {
            Some(named) => named,
            None => e,
        }
    })
}
