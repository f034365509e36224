//! The nonlinear system the Newton solvers (`super::statics`, `super::implicit`)
//! linearise: the total force and moment on every node for a configuration, and its
//! tangent K = −∂(f, m)/∂u with respect to the node increments u = (δx, δθ).
//!
//! What enters, and how:
//! * elements: loads and their consistent tangent by automatic differentiation
//!   ([`crate::rod::tangent`]), with stiffness-proportional damping through the velocities;
//! * gravity m g (constant) and mass-proportional damping −α m v, −α I ω;
//! * dead loads (constant forces and moments in global axes — no tangent);
//! * fixings' supports ([`crate::loads::Support`]): springs in the fixed directions of
//!   their frame with their diagonal tangent, friction along the free ones;
//! * stiffened sections (SPEC M6): their elements with axial, bending and torsion
//!   stiffness × [`RIGID_FACTOR`] (10⁴) — rigid to 1e-4 relative, where the explicit solver
//!   uses an exact rigid body (its time step forbids stiff springs; Newton does not care);
//! * rigid parts: a penalty spring per penetrating node ball, f = k (r − d) n with
//!   k = E_c A / l₀ of the node's elements and tangent k n nᵀ, and Coulomb friction by an
//!   elastoplastic tangential spring of the same stiffness ([`crate::contact::friction`]);
//!   a junction body's shape is such a part posed from the body, its reaction on the
//!   body's master node coupling the two ([`super::shape_contact`]);
//! * hose–hose contact: the explicit solver's penalty forces at the current positions,
//!   with each pair's tangent: within the block band (each node with itself, the two nodes
//!   of a beam with each other) in the matrix, across the two beams by GMRES on the
//!   factorised band ([`NewtonSystem::solve_linear`]);
//! * cable ties between hoses ([`crate::loads::Tie`]): their spring along n, the coupling
//!   of the two nodes solved exactly by a rank-one update per tie ([`super::ties`]).
//!
//! Prescribed nodes (fix, drive, hand) are eliminated: their increment is zero.

use super::block_tree::{BlockTree, Inertia, NotATree, SingularBlock};
use super::condensation::{Condensation, Factored};
use super::convergence::LoadScale;
use super::factor_reuse::FactorReuse;
use super::gmres::Gmres;
use super::shape_contact::{self, ShapeCoupling};
use super::ties::TieCouplings;
use crate::contact::friction::{outer, FrictionResponse};
use crate::contact::{hose_contact_forces_with, ContactPair};
use crate::loads::{LoadCase, Support, SupportLoad};
use crate::rod::element::{BeamElement, ElementEnds, ElementLoads};
use crate::rod::tangent::{block_tangent, inelastic_tangent, ElementTangent};
use crate::{Model, State};
use glam::{DQuat, DVec3};
use nalgebra::{Matrix3, Vector6};

/// How much stiffer than the hose a stiffened section's elements are in the Newton solvers.
pub const RIGID_FACTOR: f64 = 1e4;

/// Buffers of the Newton solvers, allocated once per model.
#[derive(Clone, Debug)]
pub struct NewtonSystem {
    /// The model's elements, stiffened-section ones made rigid.
    pub elements: Vec<BeamElement>,
    pub matrix: BlockTree,
    /// Right-hand side, then the solution of the linear solve.
    pub rhs: Vec<Vector6<f64>>,
    pub force: Vec<DVec3>,
    pub moment: Vec<DVec3>,
    /// Force of rigid parts on each node (penalty), last assembly.
    pub contact_force: Vec<DVec3>,
    /// Penalty stiffness per node \[N/m\] (normal and tangential).
    pub contact_stiffness: Vec<f64>,
    /// Friction of each node touching a part, last assembly (None: not in contact).
    pub friction: Vec<Option<FrictionResponse>>,
    /// Give a slipping node's friction its secant stiffness μ f_n/|g_t| along the slip as
    /// well (the static solver: `add_contact`).
    pub regularise_slip: bool,
    /// Normal force of each node's rigid-part contact in the last assembly \[N\].
    normal_force: Vec<f64>,
    /// The normal forces the friction potential is evaluated with while
    /// [`Self::lag_friction_normal`] is on \[N\].
    lagged_normal: Vec<f64>,
    lag_normal: bool,
    /// The part each node touched at the last assembly (`usize::MAX`: none).
    contact_part: Vec<usize>,
    /// The time the solve is for (set with the prescribed poses): the time the inelastic
    /// elements' history is aged to and committed at.
    pub solve_time: f64,
    /// Every part's pose at the time of the solve (empty when no part moves): a moving
    /// part is a sequence of poses to the Newton solvers, its contact and friction are
    /// taken in its own frame, so friction acts on the motion relative to it.
    pub placements: Vec<crate::kinematics::Placement>,
    /// Whether a node's increment is prescribed (zero).
    pub prescribed: Vec<bool>,
    /// Target poses of the prescribed nodes, and whether they still have to be moved.
    target_x: Vec<DVec3>,
    target_q: Vec<DQuat>,
    pending: bool,
    /// Hose–hose contact pairs of the last assembly (their cross-beam coupling is applied
    /// iteratively in [`Self::solve_linear`]).
    pub pairs: Vec<ContactPair>,
    /// Hose nodes touching a junction body's shape at the last assembly, coupled with the
    /// body's master node (applied in [`Self::solve_linear`] with the pairs).
    pub shape_couplings: Vec<ShapeCoupling>,
    /// Ties of the last assembly (their tangent, applied in [`Self::solve_linear`]).
    pub ties: TieCouplings,
    /// Size of the loads of the last assembly (for the convergence test).
    pub scale: LoadScale,
    /// Mean rest length of the elements \[m\].
    pub mean_length: f64,
    /// Scratch of the linear solve.
    base_rhs: Vec<Vector6<f64>>,
    /// The contact coupling's GMRES (buffers only when hose contact is on).
    coupling: Gmres,
    /// The junctions' condensation onto their master nodes (SPEC N1; `None` without
    /// junctions, when `matrix` is factorised as it is).
    pub junctions: Option<Condensation>,
    /// The input of the last modified factorisation, to skip factorising it again.
    pub reuse: FactorReuse,
    /// Assemblies so far: with the elements' tangents ([`Self::assemble`]) and of the
    /// loads alone ([`Self::assemble_loads`]).
    pub assemblies: Assemblies,
}

/// How many assemblies a [`NewtonSystem`] has done, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Assemblies {
    pub with_tangent: usize,
    pub loads_only: usize,
}

/// A support's load on its node at the state's configuration ([`Support::load`]).
fn support_load(model: &Model, state: &State, s: &Support, rate_factor: f64) -> SupportLoad {
    let i = s.node;
    s.load(
        state.x[i],
        state.q[i],
        state.v[i],
        state.w[i],
        (model.mass[i], model.inertia[i], model.time_step),
        rate_factor,
    )
}

/// The poses and rates of element `e`'s end nodes in `state`.
fn element_ends(state: &State, e: &BeamElement) -> ElementEnds {
    let (a, b) = (e.node_a, e.node_b);
    ElementEnds {
        x: [state.x[a], state.x[b]],
        q: [state.q[a], state.q[b]],
        v: [state.v[a], state.v[b]],
        w: [state.w[a], state.w[b]],
    }
}

/// Adds element `e`'s `loads` to its end nodes' forces and moments, and their sizes to
/// the load `scale`.
fn add_element_loads(
    e: &BeamElement,
    loads: &ElementLoads,
    (force, moment): (&mut [DVec3], &mut [DVec3]),
    scale: &mut LoadScale,
) {
    let (a, b) = (e.node_a, e.node_b);
    scale.include(
        loads.force[0].length(),
        loads.moment[0].length().max(loads.moment[1].length()),
    );
    force[a] += loads.force[0];
    force[b] += loads.force[1];
    moment[a] += loads.moment[0];
    moment[b] += loads.moment[1];
}

/// A glam 3×3 matrix as nalgebra's.
fn mat3(m: glam::DMat3) -> Matrix3<f64> {
    Matrix3::from_column_slice(&m.to_cols_array())
}

/// Relative residual to which [`NewtonSystem::solve_linear`] solves the contact-coupled
/// system.
const COUPLING_TOLERANCE: f64 = 1e-12;

/// Why a Newton solver could not be set up for a model.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TopologyError {
    #[error(
        "the Newton solvers need each element to join consecutive nodes; element {0} does not"
    )]
    NotAChain(usize),
    #[error(transparent)]
    Loop(#[from] NotATree),
}

impl NewtonSystem {
    pub fn new(model: &Model) -> Result<Self, TopologyError> {
        let n = model.node_count();
        let mut elements = model.elements.clone();
        let mut contact_stiffness = vec![0.0_f64; n];
        for (k, e) in elements.iter_mut().enumerate() {
            if e.node_b != e.node_a + 1 {
                return Err(TopologyError::NotAChain(k));
            }
            let axial = e.axial_stiffness_compression / e.rest_length;
            contact_stiffness[e.node_a] = contact_stiffness[e.node_a].max(axial);
            contact_stiffness[e.node_b] = contact_stiffness[e.node_b].max(axial);
            let rigid = matches!(
                (model.body_of[e.node_a], model.body_of[e.node_b]),
                (Some(a), Some(b)) if a == b
            );
            if rigid {
                // a rigid span does not yield
                e.inelastic = None;
                e.axial_stiffness_tension *= RIGID_FACTOR;
                e.axial_stiffness_compression *= RIGID_FACTOR;
                e.bending_stiffness[0] *= RIGID_FACTOR;
                e.bending_stiffness[1] *= RIGID_FACTOR;
                e.torsion_stiffness *= RIGID_FACTOR;
            }
        }
        let mean_length =
            elements.iter().map(|e| e.rest_length).sum::<f64>() / elements.len().max(1) as f64;
        let junctions = Condensation::new(model)?;
        Ok(Self {
            reuse: FactorReuse::new(n, junctions.as_ref()),
            scale: LoadScale::default(),
            mean_length,
            elements,
            matrix: BlockTree::new(n),
            rhs: vec![Vector6::zeros(); n],
            force: vec![DVec3::ZERO; n],
            moment: vec![DVec3::ZERO; n],
            contact_force: vec![DVec3::ZERO; n],
            contact_stiffness,
            friction: vec![None; n],
            regularise_slip: false,
            normal_force: vec![0.0; n],
            lagged_normal: vec![0.0; n],
            lag_normal: false,
            contact_part: vec![usize::MAX; n],
            solve_time: 0.0,
            placements: if model.environment.any_moves() {
                vec![Default::default(); model.environment.parts.len()]
            } else {
                Vec::new()
            },
            prescribed: vec![false; n],
            target_x: vec![DVec3::ZERO; n],
            target_q: vec![DQuat::IDENTITY; n],
            pending: false,
            pairs: Vec::with_capacity(4 * n),
            shape_couplings: if model.junction_shapes.any() {
                Vec::with_capacity(n)
            } else {
                Vec::new()
            },
            ties: TieCouplings::default(),
            base_rhs: vec![Vector6::zeros(); n],
            coupling: if model.hose_contact.active {
                Gmres::new(n)
            } else {
                Gmres::default()
            },
            junctions,
            assemblies: Assemblies::default(),
        })
    }

    /// Total loads on every node at (x, q, v, w) and their tangent; `rate_factor` c is
    /// ∂v/∂δx (0 for statics, γ/(βΔt) for Newmark). Writes `force`, `moment`,
    /// `contact_force` and `matrix` (prescribed nodes not yet eliminated).
    pub fn assemble(&mut self, model: &Model, state: &mut State, rate_factor: f64) {
        self.assemble_with(model, state, rate_factor, true);
    }

    /// The loads of [`Self::assemble`] without the elements' tangents, for a line search
    /// that only compares residuals or slopes along a step: each element's loads from
    /// [`BeamElement::loads`] (the same loads as the tangent kernel's, to round-off)
    /// instead of the tangent kernel, which costs several times as much. `matrix` is not
    /// a tangent afterwards (its element blocks are missing) until the next
    /// [`Self::assemble`]; `pairs` holds no hose–hose pair.
    pub fn assemble_loads(&mut self, model: &Model, state: &mut State, rate_factor: f64) {
        self.assemble_with(model, state, rate_factor, false);
    }

    /// [`Self::assemble`], with the elements' tangents only if `tangent`.
    fn assemble_with(&mut self, model: &Model, state: &mut State, rate_factor: f64, tangent: bool) {
        if tangent {
            self.assemblies.with_tangent += 1;
        } else {
            self.assemblies.loads_only += 1;
        }
        model.place_junction_nodes(&mut state.x, &mut state.q);
        self.place_shapes(model, state);
        self.matrix.clear();
        self.shape_couplings.clear();
        self.force.fill(DVec3::ZERO);
        self.moment.fill(DVec3::ZERO);
        self.contact_force.fill(DVec3::ZERO);
        self.pairs.clear();
        self.ties.clear();
        let mut scale = LoadScale::default();
        let beta = model.damping_stiffness;
        if !tangent {
            for e in &self.elements {
                let ends = element_ends(state, e);
                let loads = match &e.inelastic {
                    Some(hinge) => {
                        let history = state.inelastic_view_at(self.solve_time);
                        model.inelastic.loads(e, hinge, history, &ends, beta)
                    }
                    None => e.loads(&ends, beta),
                };
                add_element_loads(e, &loads, (&mut self.force, &mut self.moment), &mut scale);
            }
        }
        // four elements at a time (the tangent kernel's lanes), added in element order
        let mut tangents = [(ElementLoads::default(), ElementTangent::zeros()); 4];
        for chunk in self.elements.chunks(4).filter(|_| tangent) {
            let last = chunk.len() - 1;
            let element = |k: usize| &chunk[k.min(last)];
            let mut ends = [ElementEnds {
                x: [DVec3::ZERO; 2],
                q: [DQuat::IDENTITY; 2],
                v: [DVec3::ZERO; 2],
                w: [DVec3::ZERO; 2],
            }; 4];
            for (k, ends) in ends.iter_mut().enumerate() {
                *ends = element_ends(state, element(k));
            }
            block_tangent(
                [element(0), element(1), element(2), element(3)],
                [&ends[0], &ends[1], &ends[2], &ends[3]],
                chunk.len(),
                beta,
                rate_factor,
                &mut tangents,
            );
            for (e, out) in chunk.iter().zip(&mut tangents) {
                if let Some(hinge) = &e.inelastic {
                    let ends = element_ends(state, e);
                    let history = state.inelastic_view_at(self.solve_time);
                    let hinges = &model.inelastic;
                    *out = inelastic_tangent(hinges, (e, hinge), history, &ends, beta, rate_factor);
                }
            }
            for (e, (loads, k)) in chunk.iter().zip(&tangents) {
                let (a, b) = (e.node_a, e.node_b);
                add_element_loads(e, loads, (&mut self.force, &mut self.moment), &mut scale);
                self.matrix.diag[a] += k.fixed_view::<6, 6>(0, 0);
                self.matrix.diag[b] += k.fixed_view::<6, 6>(6, 6);
                self.matrix.upper[a] += k.fixed_view::<6, 6>(0, 6);
                self.matrix.lower[a] += k.fixed_view::<6, 6>(6, 0);
            }
        }
        let alpha = model.damping_mass;
        for i in 0..self.force.len() {
            scale.include(model.mass[i] * model.gravity.length(), 0.0);
            self.force[i] += model.mass[i] * (model.gravity - alpha * state.v[i]);
            self.moment[i] -= alpha * model.inertia[i] * state.w[i];
            let (dm, di) = (
                alpha * model.mass[i] * rate_factor,
                alpha * model.inertia[i] * rate_factor,
            );
            for k in 0..3 {
                self.matrix.diag[i][(k, k)] += dm;
                self.matrix.diag[i][(k + 3, k + 3)] += di;
            }
        }
        if model.has_own_masses() {
            let weight = super::body_terms::add_body_loads(
                model,
                state,
                &mut self.force,
                &mut self.moment,
                &mut self.matrix.diag,
                rate_factor,
            );
            scale.include(weight, 0.0);
        }
        for (_, case) in state.loads.iter() {
            match case {
                LoadCase::DeadLoad(d) => {
                    let (force, moment) = d.at(state.time);
                    self.force[d.node] += force;
                    self.moment[d.node] += moment;
                    scale.include(force.length(), moment.length());
                }
                LoadCase::Support(s) => {
                    let i = s.node;
                    let l = support_load(model, state, s, rate_factor);
                    self.force[i] += l.force;
                    self.moment[i] += l.moment;
                    let mut t = self.matrix.diag[i].fixed_view_mut::<3, 3>(0, 0);
                    t += mat3(l.tangent_translation);
                    let mut r = self.matrix.diag[i].fixed_view_mut::<3, 3>(3, 3);
                    r += mat3(l.tangent_rotation);
                    scale.include(l.force.length(), l.moment.length());
                }
                _ => {}
            }
        }
        if !model.environment.is_empty() {
            self.add_contact(model, state);
            for f in &self.contact_force {
                scale.include(f.length(), 0.0);
            }
        }
        if model.hose_contact.active {
            let (matrix, pairs) = (&mut self.matrix, &mut self.pairs);
            pairs.clear();
            hose_contact_forces_with(
                model,
                &state.x,
                &state.v,
                &mut state.hose_contact,
                &mut state.hose_contact_force,
                |mut pair| {
                    if tangent {
                        // the damper acts through v = v₀ + c δx: stiffness k + c·damping
                        pair.stiffness += pair.damping * rate_factor;
                        add_pair_tangent(matrix, &pair);
                        pairs.push(pair);
                    }
                },
            );
            for (f, c) in self.force.iter_mut().zip(&state.hose_contact_force) {
                *f += *c;
                scale.include(c.length(), 0.0);
            }
        }
        // ties: a spring along n between two nodes; the tangent k n nᵀ couples them
        // outside the band and is applied in the linear solve
        for (_, case) in state.loads.iter() {
            let LoadCase::Tie(t) = case else { continue };
            let [a, b] = t.nodes;
            let l = t.load_in(model, state, rate_factor);
            self.force[a] += l.force;
            self.force[b] -= l.force;
            scale.include(l.force.length(), 0.0);
            self.ties.push(a, b, l.normal, l.stiffness);
        }
        scale.include(0.0, scale.force * self.mean_length);
        self.scale = scale;
        if let Some(junctions) = &mut self.junctions {
            junctions.fold_loads(
                &state.x,
                &mut self.force,
                &mut self.moment,
                &self.prescribed,
            );
        }
    }

    /// Poses the junction bodies' shapes in `placements` from their master nodes
    /// ([`shape_contact::place_shapes`]).
    fn place_shapes(&mut self, model: &Model, state: &State) {
        if model.junction_shapes.any() {
            let (pose, twist) = ((&state.x[..], &state.q[..]), (&state.v[..], &state.w[..]));
            shape_contact::place_shapes(model, pose, twist, &mut self.placements);
        }
    }

    /// Penalty contact of node balls with the rigid parts, with friction (see the module
    /// doc).
    fn add_contact(&mut self, model: &Model, state: &State) {
        let with_friction = state.friction.fits(self.force.len());
        for i in 0..self.force.len() {
            self.friction[i] = None;
            self.contact_part[i] = usize::MAX;
            self.normal_force[i] = 0.0;
            let Some((part, n, depth)) = self.touching(model, state.x[i], i) else {
                continue;
            };
            if model.environment.parts[part].moves {
                self.contact_part[i] = part;
            }
            let k = self.contact_stiffness[i];
            self.normal_force[i] = k * depth;
            let mut f = n * (k * depth);
            let nn = normal_projector(n);
            let friction = (with_friction && !self.prescribed[i])
                .then(|| self.friction_response(model, state, i, part, n, k * depth, k));
            let mut block = self.matrix.diag[i].fixed_view_mut::<3, 3>(0, 0);
            block += nn * k;
            if let Some(r) = friction {
                block += r.tangent;
                if self.regularise_slip && r.slipping && r.secant > 0.0 {
                    // the slip's own direction gets the secant stiffness: the consistent
                    // tangent has none there, and a hose slipping at every node would
                    // leave Newton no stiffness along the slip at all
                    let t = -r.force / r.force.length();
                    block += outer(t, t) * r.secant;
                }
                f += r.force;
                self.friction[i] = Some(r);
            }
            self.force[i] += f;
            self.contact_force[i] += f;
            if let Some(j) = shape_contact::shape_junction(model, part) {
                let tangent = match friction {
                    Some(r) => nn * k + r.tangent,
                    None => nn * k,
                };
                let s = glam::DMat3::from_cols_slice(tangent.as_slice());
                let coupling = shape_contact::add_reaction(
                    model,
                    j,
                    (i, &state.x),
                    (f, s),
                    (&mut self.force, &mut self.moment),
                    &mut self.matrix.diag,
                );
                self.shape_couplings.push(coupling);
            }
        }
    }

    /// Friction of node `i` touching `part` with normal `n`: in the part's own frame
    /// when it moves (its anchor stays on the part), turned back to world axes.
    #[allow(clippy::too_many_arguments)]
    fn friction_response(
        &self,
        model: &Model,
        state: &State,
        i: usize,
        part: usize,
        n: DVec3,
        normal_force: f64,
        k: f64,
    ) -> FrictionResponse {
        let p = &model.environment.parts[part];
        let mu = (p.friction_static, p.friction_sliding);
        match self.moving_pose(model, part) {
            None => state
                .friction
                .response(i, state.x[i], n, normal_force, k, mu),
            Some(pose) => {
                let back = pose.rotation;
                let local_x = pose.inverse_apply(state.x[i]);
                let local_n = back.conjugate() * n;
                let mut r = state
                    .friction
                    .response(i, local_x, local_n, normal_force, k, mu);
                let turn = mat3(glam::DMat3::from_quat(back));
                r.force = back * r.force;
                r.tangent = turn * r.tangent * turn.transpose();
                r
            }
        }
    }

    /// The pose of `part` at the solve's time if it moves.
    fn moving_pose(&self, model: &Model, part: usize) -> Option<crate::kinematics::Pose> {
        if !model.environment.parts.get(part)?.moves {
            return None;
        }
        self.placements.get(part).map(|p| p.pose)
    }

    /// The part node `i` at `x` penetrates, the unit normal towards the node and the
    /// depth r − d > 0; None when the node's ball is clear of every part. A node inside
    /// its own junction body's shape ignores it ([`crate::junction_shape`]).
    fn touching(&self, model: &Model, x: DVec3, i: usize) -> Option<(usize, DVec3, f64)> {
        let r = model.radius[i];
        let env = &model.environment;
        let (part, p, d) = if model.junction_shapes.any() {
            let still = env.closest_point(x, r);
            let shapes = &model.junction_shapes;
            let allowed = |k: usize| !shapes.excludes_node(k, i);
            let reach = still.map_or(r, |h| h.2);
            match env.closest_moving_where(x, reach, &self.placements, allowed) {
                Some(m) if still.is_none_or(|h| m.2 < h.2) => m,
                _ => still?,
            }
        } else if env.any_moves() {
            env.closest_point_placed(x, r, &self.placements)?
        } else {
            env.closest_point(x, r)?
        };
        (d < r && d > 1e-12 * r).then(|| (part, (x - p) / d, r - d))
    }

    /// Accepts the state's configuration as the end of a step or an equilibrium for the
    /// inelastic elements at the solve's time ([`State::commit_inelastic`]; rigid spans
    /// are elastic).
    pub fn commit_inelastic(&self, model: &Model, state: &mut State) {
        state.commit_inelastic(model, &self.elements, self.solve_time);
    }

    /// Accepts the configuration of the last assembly as the end of a step for friction
    /// ([`crate::contact::friction::FrictionMemory::commit`]).
    pub fn commit_friction(&self, state: &mut State) {
        if !state.friction.fits(self.force.len()) {
            state.friction = crate::contact::friction::FrictionMemory::new(&state.x);
            return;
        }
        for i in 0..self.force.len() {
            let k = self.contact_stiffness[i];
            let moving = self.placements.get(self.contact_part[i]);
            match (moving, self.friction[i].as_ref()) {
                // a moving part's anchor is kept in its frame (Self::friction_response)
                (Some(place), Some(r)) => {
                    let back = place.pose.rotation.conjugate();
                    let local = FrictionResponse {
                        force: back * r.force,
                        ..*r
                    };
                    let x = place.pose.inverse_apply(state.x[i]);
                    state.friction.commit(i, x, Some(&local), k);
                }
                _ => state
                    .friction
                    .commit(i, state.x[i], self.friction[i].as_ref(), k),
            }
        }
    }

    /// Potential energy of the conservative loads at the state's configuration: strain
    /// energy (rigid-factor elements), gravity, dead forces, contact springs (parts and
    /// hoses). Used by the
    /// static line search. Dead moments have no potential (they are not conservative
    /// under finite rotations) and are left out.
    pub fn potential_energy(&mut self, model: &Model, state: &mut State) -> f64 {
        model.place_junction_nodes(&mut state.x, &mut state.q);
        self.place_shapes(model, state);
        let mut e = 0.0;
        for el in &self.elements {
            let (a, b) = (el.node_a, el.node_b);
            let (x, q) = ([state.x[a], state.x[b]], [state.q[a], state.q[b]]);
            e += match &el.inelastic {
                // the incremental potential: its gradient is the loads
                Some(inelastic) => {
                    let history = state.inelastic_view_at(self.solve_time);
                    model
                        .inelastic
                        .strain_energy(el, inelastic, history, (x, q), true)
                }
                None => el.strain_energy(x, q),
            };
        }
        for i in 0..state.x.len() {
            e -= model.mass[i] * model.gravity.dot(state.x[i]);
        }
        if model.has_own_masses() {
            e += model.own_mass_gravity_energy(&state.x, &state.q);
        }
        for (_, case) in state.loads.iter() {
            match case {
                LoadCase::DeadLoad(d) => e -= d.at(state.time).0.dot(state.x[d.node]),
                LoadCase::Support(s) => e += support_load(model, state, s, 0.0).energy,
                LoadCase::Tie(t) => e += t.load_in(model, state, 0.0).energy,
                _ => {}
            }
        }
        if model.hose_contact.active {
            // the penalty springs' energy ½ k pen², computed with the forces
            hose_contact_forces_with(
                model,
                &state.x,
                &state.v,
                &mut state.hose_contact,
                &mut state.hose_contact_force,
                |_| {},
            );
            e += state.hose_contact.energy;
        }
        if !model.environment.is_empty() {
            let with_friction = state.friction.fits(state.x.len());
            for i in 0..state.x.len() {
                let Some((part, n, depth)) = self.touching(model, state.x[i], i) else {
                    continue;
                };
                let k = self.contact_stiffness[i];
                e += 0.5 * k * depth * depth;
                if with_friction && !self.prescribed[i] {
                    let lagged = self.lagged_normal[i];
                    let normal = if self.lag_normal && lagged > 0.0 {
                        lagged
                    } else {
                        k * depth
                    };
                    let r = self.friction_response(model, state, i, part, n, normal, k);
                    e += r.energy;
                }
            }
        }
        e
    }

    /// Evaluates the friction potential of [`Self::potential_energy`] with the normal
    /// forces of the last assembly (`on`) or with the normal forces where it is evaluated.
    /// The friction potential is a potential only at a fixed normal force (Coulomb friction
    /// is not conservative): its change with the penetration, μ k |g_t| per metre, is no
    /// force of the model, and along a line search it would outweigh the forces' work
    /// where a node has slipped far from its anchor. Lagging the normal force makes the
    /// line search's energy the incremental potential whose gradient is the loads (the
    /// lagged normal force of Li et al., "Incremental Potential Contact", ACM Trans.
    /// Graph. 39(4), 2020, §5).
    pub fn lag_friction_normal(&mut self, on: bool) {
        if on {
            self.lagged_normal.copy_from_slice(&self.normal_force);
        }
        self.lag_normal = on;
    }

    /// Marks the nodes prescribed by kinematic load cases at time `t` and records their
    /// target poses, without moving them: the first Newton iteration then carries the
    /// prescribed motion into the free nodes through the tangent
    /// ([`Self::add_prescribed_coupling`]) — the linear response as predictor — and
    /// [`Self::move_prescribed`] puts them on target. (Jumping them first would start
    /// Newton from a state strained by the whole jump in one element.)
    ///
    /// A junction with a held member is held whole: its other members' targets follow
    /// rigidly from the held one's ([`Model::junction_poses_from`]).
    pub fn set_prescribed(&mut self, model: &Model, state: &State, t: f64) {
        self.solve_time = t;
        self.prescribed.fill(false);
        self.pending = false;
        if model.environment.any_moves() {
            let moves = &state.part_moves;
            model
                .kinematics
                .place_all(t, t, moves, &mut self.placements);
        }
        for (_, case) in state.loads.iter() {
            let Some((x_new, q_new)) =
                case.prescribed_pose(t, &model.kinematics, &state.part_moves)
            else {
                continue;
            };
            let i = case.node();
            self.target_x[i] = x_new;
            self.target_q[i] = q_new;
            self.prescribed[i] = true;
            if let Some(j) = model.junction_of(i) {
                for (k, xk, qk) in model.junction_poses_from(j, i, x_new, q_new) {
                    if k != i {
                        self.target_x[k] = xk;
                        self.target_q[k] = qk;
                        self.prescribed[k] = true;
                    }
                }
            }
        }
        for i in 0..self.prescribed.len() {
            if self.moves(state, i) {
                self.pending = true;
            }
        }
    }

    /// Whether node `i` is prescribed and not yet on its target.
    pub fn moves(&self, state: &State, i: usize) -> bool {
        self.prescribed[i] && (self.target_x[i] != state.x[i] || self.target_q[i] != state.q[i])
    }

    /// Whether prescribed nodes still have to be moved to their targets.
    pub fn pending(&self) -> bool {
        self.pending
    }

    /// The increment (δx, δθ) that takes prescribed node `i` to its target.
    pub fn prescribed_increment(&self, state: &State, i: usize) -> (DVec3, DVec3) {
        (
            self.target_x[i] - state.x[i],
            crate::math::log_map(self.target_q[i] * state.q[i].conjugate()),
        )
    }

    /// rhs_i −= J_ip δu_p for the free neighbours i of each prescribed node p (call after
    /// the matrix is complete, before [`Self::eliminate_prescribed`]).
    pub fn add_prescribed_coupling(&mut self, state: &State) {
        let n = self.prescribed.len();
        for p in 0..n {
            if !self.prescribed[p] {
                continue;
            }
            let (dx, dth) = self.prescribed_increment(state, p);
            let d = Vector6::new(dx.x, dx.y, dx.z, dth.x, dth.y, dth.z);
            if p > 0 && !self.prescribed[p - 1] {
                // block (p−1, p)
                self.rhs[p - 1] -= self.matrix.upper[p - 1] * d;
            }
            if p + 1 < n && !self.prescribed[p + 1] {
                // block (p+1, p)
                self.rhs[p + 1] -= self.matrix.lower[p] * d;
            }
        }
    }

    /// Moves the prescribed nodes the fraction `s` < 1 of the way to their targets
    /// (x += s δx, q ← exp(s δθ) q with [`Self::prescribed_increment`]); they stay pending.
    pub fn move_prescribed_part(&self, state: &mut State, s: f64) {
        for i in 0..self.prescribed.len() {
            if self.prescribed[i] {
                let (dx, dth) = self.prescribed_increment(state, i);
                state.x[i] += s * dx;
                state.q[i] = (crate::math::exp_map(s * dth) * state.q[i]).normalize();
            }
        }
    }

    /// Puts the prescribed nodes on their targets.
    pub fn move_prescribed(&mut self, state: &mut State) {
        for i in 0..self.prescribed.len() {
            if self.prescribed[i] {
                state.x[i] = self.target_x[i];
                state.q[i] = self.target_q[i];
            }
        }
        self.pending = false;
    }

    /// Solves J δu = rhs (rhs becomes δu) for J = T + C: T the block-tridiagonal part in
    /// `matrix`, C the hose–hose contact coupling between the two beams of each pair,
    /// −k wᵢ wⱼ n nᵀ, and that of each hose node touching a junction body's shape with
    /// the body's master node ([`super::shape_contact`]) (T includes the cable ties,
    /// solved exactly by their rank-one updates, [`super::ties`]). Without such
    /// couplings this is one O(N) solve; with them, GMRES on
    /// (I + T⁻¹C) δu = T⁻¹ rhs with the factorised T ([`super::gmres`]), to a relative
    /// residual of `COUPLING_TOLERANCE`. (The fixed-point iteration δu ← T⁻¹(rhs − C δu)
    /// on the same splitting, used before, converges at the rate k/(k + k_hose) of the
    /// contact stiffness against the hoses' own stiffness at the contact — 1 − 4·10⁻⁴ for
    /// two soft hoses pressed together — and left Newton with wrong steps.)
    ///
    /// `modified`: factorise a positive-definite neighbour of T where T is not
    /// ([`BlockTree::factor_modified`], the static solver) and return T's inertia;
    /// otherwise T as it is (the implicit solver, whose mass term keeps T definite).
    pub fn solve_linear(&mut self, modified: bool) -> Result<Inertia, SingularBlock> {
        let inertia = if modified {
            self.factor_modified_keeping(false)?
        } else {
            self.reuse.forget();
            match &mut self.junctions {
                Some(j) => j.factor(&self.matrix)?,
                None => self.matrix.factor()?,
            }
            Inertia::default()
        };
        let factored = match &self.junctions {
            Some(j) => Factored::Condensed(j),
            None => Factored::Chain(&self.matrix),
        };
        let tied = !self.ties.is_empty();
        if tied {
            self.ties.prepare(factored, &self.prescribed)?;
        }
        factored.solve_factored(&mut self.rhs)?;
        if tied {
            self.ties.correct(&mut self.rhs, &self.prescribed);
        }
        if self.pairs.is_empty() && self.shape_couplings.is_empty() {
            return Ok(inertia);
        }
        // b' = T⁻¹ rhs, also the start (the solution without the coupling)
        self.base_rhs.copy_from_slice(&self.rhs);
        if self.coupling.len() != self.rhs.len() {
            // hose contact switched on after the solver was built: buffers once
            self.coupling = Gmres::new(self.rhs.len());
        }
        let (pairs, prescribed) = (&self.pairs, &self.prescribed);
        let shapes = &self.shape_couplings;
        let ties = &mut self.ties;
        let mut failed = None;
        self.coupling.solve(
            &self.base_rhs,
            &mut self.rhs,
            COUPLING_TOLERANCE,
            |v, out| {
                // (I + K⁻¹C) v = v − K⁻¹(−C v), K = T with the ties' rank-one updates
                out.fill(Vector6::zeros());
                add_minus_coupling(pairs, prescribed, v, out);
                shape_contact::add_minus_shape_coupling(shapes, prescribed, v, out);
                if let Err(e) = factored.solve_factored(out) {
                    failed = Some(e);
                }
                if tied {
                    ties.correct(out, prescribed);
                }
                for (o, vi) in out.iter_mut().zip(v) {
                    *o = vi - *o;
                }
            },
        );
        if let Some(e) = failed {
            return Err(e);
        }
        Ok(inertia)
    }

    /// Multiplies the tangent's off-diagonal blocks and the hose–hose contact pairs'
    /// stiffness (their coupling across the two beams, applied in
    /// [`Self::solve_linear`]) by `factor` — the HHT-α weight 1 + α of the implicit
    /// solver's Jacobian, whose diagonal blocks it scales itself. (Leaving the pairs out,
    /// as before, made the cross-beam coupling 1/(1 + α) times too stiff: the Newton steps
    /// of two hoses pressed together overshot, and the contact chattered on and off.)
    pub fn scale_off_diagonal_tangent(&mut self, factor: f64) {
        for m in self
            .matrix
            .upper
            .iter_mut()
            .chain(self.matrix.lower.iter_mut())
        {
            *m *= factor;
        }
        for p in &mut self.pairs {
            p.stiffness *= factor;
        }
        for c in &mut self.shape_couplings {
            c.scale(factor);
        }
    }

    /// Factorises a positive-definite neighbour of the tangent (condensed at junctions)
    /// and returns the tangent's inertia ([`BlockTree::factor_modified`]) — or keeps the
    /// factors in hand when they were computed from this very matrix ([`FactorReuse`]).
    /// The factors are kept for reuse: call it for the stability check at an
    /// equilibrium, the factorisation the next input step's first iteration can reuse.
    pub fn factor_modified(&mut self) -> Result<Inertia, SingularBlock> {
        self.factor_modified_keeping(true)
    }

    /// [`Self::factor_modified`]; `keep`: record the matrix so that its factors can be
    /// reused (a Newton iteration's matrix never recurs: the next one is assembled
    /// elsewhere).
    fn factor_modified_keeping(&mut self, keep: bool) -> Result<Inertia, SingularBlock> {
        if let Some(inertia) = self.reuse.reusable(&self.matrix, self.junctions.as_ref()) {
            return Ok(inertia);
        }
        if keep {
            self.reuse.record(&self.matrix, self.junctions.as_ref());
        } else {
            self.reuse.forget();
        }
        let factored = match &mut self.junctions {
            Some(j) => j.factor_modified(&self.matrix),
            None => self.matrix.factor_modified(),
        };
        match factored {
            Ok(inertia) if keep => self.reuse.factorised(inertia),
            Ok(_) => {}
            Err(_) => self.reuse.forget(),
        }
        factored
    }

    /// A direction of negative curvature from the last [`Self::factor_modified`]
    /// ([`BlockTree::negative_curvature_direction`]), junction slaves moving with their
    /// masters.
    pub fn negative_curvature_direction(
        &self,
        block: usize,
        eigenvector: &Vector6<f64>,
        d: &mut [Vector6<f64>],
    ) {
        match &self.junctions {
            Some(j) => {
                j.tree.negative_curvature_direction(block, eigenvector, d);
                j.expand(d);
            }
            None => self
                .matrix
                .negative_curvature_direction(block, eigenvector, d),
        }
    }

    /// Folds the right-hand side of junction slaves onto their masters (the implicit
    /// solver's inertial residual is per node; [`super::condensation`]).
    pub fn fold_rhs(&mut self) {
        if let Some(j) = &self.junctions {
            j.fold_rhs(&mut self.rhs);
        }
    }

    /// Eliminates the prescribed nodes from the matrix and zeroes their right-hand side.
    pub fn eliminate_prescribed(&mut self) {
        for i in 0..self.prescribed.len() {
            if self.prescribed[i] {
                self.matrix.eliminate(i);
                self.rhs[i] = Vector6::zeros();
            }
        }
    }
}

/// out += −C v for the hose–hose contact pairs' coupling across their two beams,
/// C_ij = −k wᵢ wⱼ n nᵀ (i on one beam, j on the other; translations only), on the free
/// rows.
fn add_minus_coupling(
    pairs: &[ContactPair],
    prescribed: &[bool],
    v: &[Vector6<f64>],
    out: &mut [Vector6<f64>],
) {
    for p in pairs {
        let [a, b, c, d] = p.nodes;
        let nv = nalgebra::Vector3::new(p.normal.x, p.normal.y, p.normal.z);
        for (i, wi) in [(a, p.weights[0]), (b, p.weights[1])] {
            for (j, wj) in [(c, p.weights[2]), (d, p.weights[3])] {
                let kw = p.stiffness * wi * wj;
                if !prescribed[i] {
                    let mut row = out[i].fixed_rows_mut::<3>(0);
                    row += nv * (kw * nv.dot(&v[j].fixed_rows::<3>(0)));
                }
                if !prescribed[j] {
                    let mut row = out[j].fixed_rows_mut::<3>(0);
                    row += nv * (kw * nv.dot(&v[i].fixed_rows::<3>(0)));
                }
            }
        }
    }
}

/// n nᵀ: the stiffness direction of a contact spring along the unit normal n.
fn normal_projector(n: DVec3) -> Matrix3<f64> {
    outer(n, n)
}

/// The tangent of one hose–hose contact pair, k wₐ w_b n nᵀ (signs by side), for the node
/// pairs inside the block band: each node with itself and the two nodes of one beam with
/// each other. The coupling across the two beams (far apart in the chain) is applied by
/// [`NewtonSystem::solve_linear`].
fn add_pair_tangent(matrix: &mut BlockTree, pair: &ContactPair) {
    let nn = normal_projector(pair.normal) * pair.stiffness;
    let [a, b, c, d] = pair.nodes;
    let w = pair.weights;
    for (node, wk) in [(a, w[0]), (b, w[1]), (c, w[2]), (d, w[3])] {
        let mut block = matrix.diag[node].fixed_view_mut::<3, 3>(0, 0);
        block += nn * (wk * wk);
    }
    for (first, second, wf, ws) in [(a, b, w[0], w[1]), (c, d, w[2], w[3])] {
        let (lo, hi, wl, wh) = if first < second {
            (first, second, wf, ws)
        } else {
            (second, first, ws, wf)
        };
        if hi == lo + 1 {
            let coupling = nn * (wl * wh);
            let mut up = matrix.upper[lo].fixed_view_mut::<3, 3>(0, 0);
            up += coupling;
            let mut down = matrix.lower[lo].fixed_view_mut::<3, 3>(0, 0);
            down += coupling;
        }
    }
}

/// Applies the increment `s · rhs` to the free nodes: x += s δx, q ← exp(s δθ) q.
pub fn apply_increment(state: &mut State, rhs: &[Vector6<f64>], prescribed: &[bool], s: f64) {
    for i in 0..state.x.len() {
        if prescribed[i] {
            continue;
        }
        let d = rhs[i];
        state.x[i] += s * DVec3::new(d[0], d[1], d[2]);
        let phi = s * DVec3::new(d[3], d[4], d[5]);
        state.q[i] = (crate::math::exp_map(phi) * state.q[i]).normalize();
    }
}

/// Largest rotation one Newton iteration may give a node \[rad\]. Newton's step on the
/// rotation group is only a linearisation; a larger turn (a free end spun by a suddenly
/// released twist) can land in an equilibrium whole turns away. Steps are shortened to it.
pub const MAX_ROTATION_PER_ITERATION: f64 = 0.25;

/// The fraction of the Newton increment that keeps every node's rotation within
/// [`MAX_ROTATION_PER_ITERATION`] (1 when it already does).
pub fn rotation_limited_step(rhs: &[Vector6<f64>], prescribed: &[bool]) -> f64 {
    limited_step(rhs, prescribed, 3, MAX_ROTATION_PER_ITERATION)
}

/// The fraction of the Newton increment that keeps every free node's translation within
/// `limit` \[m\] (1 when it already does).
pub fn translation_limited_step(rhs: &[Vector6<f64>], prescribed: &[bool], limit: f64) -> f64 {
    limited_step(rhs, prescribed, 0, limit)
}

/// The largest length of a free node's three components of an increment from `first`
/// (0: translation \[m\], 3: rotation \[rad\]).
pub fn largest_free(rhs: &[Vector6<f64>], prescribed: &[bool], first: usize) -> f64 {
    rhs.iter()
        .zip(prescribed)
        .filter(|(_, p)| !**p)
        .map(|(d, _)| d.fixed_rows::<3>(first).norm())
        .fold(0.0, f64::max)
}

/// The fraction of the increment that keeps the length of every free node's three
/// components from `first` (0: translation, 3: rotation) within `limit`.
fn limited_step(rhs: &[Vector6<f64>], prescribed: &[bool], first: usize, limit: f64) -> f64 {
    let largest = largest_free(rhs, prescribed, first);
    if largest > limit {
        limit / largest
    } else {
        1.0
    }
}

/// Largest translation of a node in one Newton iteration near contact \[m\]: `fraction`
/// of the smallest node radius when the model has rigid parts, or when two hose
/// capsules are near each other (the hose–hose pair list of the last assembly is not
/// empty: some pair is within about a radius of touching); `None` otherwise. A longer
/// step can carry a node ball or capsule through what it should touch within one
/// iteration — where no contact force was yet seen — and Newton then balances it on the
/// far side, pushed by a contact normal that points the wrong way.
pub fn contact_translation_limit(model: &Model, state: &State, fraction: f64) -> Option<f64> {
    let hoses_near = model.hose_contact.active && !state.hose_contact.candidates.is_empty();
    (!model.environment.is_empty() || hoses_near)
        .then(|| fraction * model.radius.iter().cloned().fold(f64::INFINITY, f64::min))
}

/// The fraction of the Newton increment at which the first hose–hose candidate pair that
/// is apart now would touch, the increment linearised at the pair's closest points (the
/// time of impact of conservative advancement, Mirtich 1996, "Impulse-based dynamic
/// simulation of rigid body systems", ch. 3; the pair's surfaces close at the rate the
/// increment moves its closest points towards each other); ∞ when no pair closes. The
/// energy a line search compares sees only where a trial lands: a trial far beyond this
/// can carry one hose through the other, where no contact force acts on the far side.
pub fn first_touch_step(
    model: &Model,
    state: &State,
    rhs: &[Vector6<f64>],
    prescribed: &[bool],
) -> f64 {
    if !model.hose_contact.active {
        return f64::INFINITY;
    }
    let moved = |i: usize| {
        if prescribed[i] {
            DVec3::ZERO
        } else {
            DVec3::new(rhs[i][0], rhs[i][1], rhs[i][2])
        }
    };
    let (x, r) = (&state.x, &model.radius);
    let mut first = f64::INFINITY;
    for &(i, j) in &state.hose_contact.candidates {
        let (ei, ej) = (&model.elements[i as usize], &model.elements[j as usize]);
        let (a, b, c, d) = (ei.node_a, ei.node_b, ej.node_a, ej.node_b);
        let (s, t) = crate::contact::hose_hose::closest_segment_segment(x[a], x[b], x[c], x[d]);
        let gap = x[a].lerp(x[b], s) - x[c].lerp(x[d], t);
        let distance = gap.length();
        let clearance = distance - (r[a] + s * (r[b] - r[a]) + r[c] + t * (r[d] - r[c]));
        if clearance <= 0.0 || distance == 0.0 {
            continue;
        }
        let closing =
            -(gap / distance).dot(moved(a).lerp(moved(b), s) - moved(c).lerp(moved(d), t));
        if closing > 0.0 {
            first = first.min(clearance / closing);
        }
    }
    first
}

/// Unit round-off of f64, u = 2⁻⁵³.
const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;
/// Margin on the round-off estimate of [`NewtonSystem::noise_floor`]: the three
/// components of a difference, and the sum over a node's elements.
const NOISE_MARGIN: f64 = 4.0;

impl NewtonSystem {
    /// The round-off floor of node `i`'s out-of-balance force \[N\] and moment \[N·m\] in the
    /// last assembly (call before the prescribed nodes are eliminated). Element loads are
    /// computed from differences of positions of size |x|, each rounded to about u|x|;
    /// the node's stiffness turns that into a force error of u ‖K_tt‖ |x| and a moment
    /// error of u (‖K_rt‖ |x| + ‖K_rr‖) — the backward-error bound of a residual
    /// evaluated in floating point (Higham, *Accuracy and Stability of Numerical
    /// Algorithms*, 2nd ed., §12.1). No Newton step can balance a node below it: the
    /// metal-tube nodes of the demo (stiffness × 10⁴, 0.5 m from the origin) stalled at
    /// 7e-8 N against a limit of 4.7e-8 N while their floor is ≈ 5e-7 N.
    pub fn noise_floor(&self, state: &State, i: usize) -> (f64, f64) {
        let d = &self.matrix.diag[i];
        // the node's and its neighbours' coordinates (one element further out)
        let reach = 2.0 * (state.x[i].abs().max_element() + self.mean_length);
        let (tt, rt, rr) = (
            d.fixed_view::<3, 3>(0, 0).norm(),
            d.fixed_view::<3, 3>(3, 0).norm(),
            d.fixed_view::<3, 3>(3, 3).norm(),
        );
        let u = NOISE_MARGIN * UNIT_ROUNDOFF;
        (u * tt * reach, u * (rt * reach + rr))
    }

    /// Largest force and moment residual over the free nodes, a residual within its
    /// node's round-off floor ([`Self::noise_floor`]) counting as zero: what a
    /// convergence test may ask of the last assembly.
    pub fn residuals_above_noise(&self, state: &State) -> (f64, f64) {
        let mut f: f64 = 0.0;
        let mut m: f64 = 0.0;
        for i in 0..self.force.len() {
            if self.prescribed[i] {
                continue;
            }
            let (floor_f, floor_m) = self.noise_floor(state, i);
            let (rf, rm) = (self.force[i].length(), self.moment[i].length());
            if rf > floor_f {
                f = f.max(rf);
            }
            if rm > floor_m {
                m = m.max(rm);
            }
        }
        (f, m)
    }
}

/// Largest force and moment residual over the free nodes.
pub fn residual_norms(force: &[DVec3], moment: &[DVec3], prescribed: &[bool]) -> (f64, f64) {
    let mut f: f64 = 0.0;
    let mut m: f64 = 0.0;
    for i in 0..force.len() {
        if !prescribed[i] {
            f = f.max(force[i].length());
            m = m.max(moment[i].length());
        }
    }
    (f, m)
}

/// Puts each stiffened section's body state where its nodes now are, and each junction
/// body's shape where its body now is (the Newton solvers move the nodes; the explicit
/// solver and the reports read the bodies and the parts' placements).
pub fn sync_bodies(model: &Model, state: &mut State) {
    for (b, body) in model.bodies.iter().enumerate() {
        let first = body.nodes[0];
        if body.attached.is_some() {
            // the centre of mass is not the nodes' alone: place it from the first node
            let (centre, orientation) = body.pose_from_node(0, state.x[first], state.q[first]);
            let s = &mut state.bodies[b];
            s.centre = centre;
            s.orientation = orientation;
            s.velocity = state.v[first] + state.w[first].cross(centre - state.x[first]);
            s.angular_velocity = state.w[first];
            continue;
        }
        let centre = body
            .nodes
            .iter()
            .map(|&i| model.mass[i] * state.x[i])
            .sum::<DVec3>()
            / body.mass;
        let velocity = body
            .nodes
            .iter()
            .map(|&i| model.mass[i] * state.v[i])
            .sum::<DVec3>()
            / body.mass;
        let orientation: DQuat = (state.q[first] * body.frames[0].conjugate()).normalize();
        let s = &mut state.bodies[b];
        s.centre = centre;
        s.orientation = orientation;
        s.velocity = velocity;
        s.angular_velocity = state.w[first];
    }
    if model.junction_shapes.any() && !state.contact.placements.is_empty() {
        // the shapes ride on the bodies (reports and the viewer read their placements)
        model.place_junction_shapes(state);
    }
}
