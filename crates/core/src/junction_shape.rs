//! A junction body's shape (SPEC N1): the moulded T or Y piece as a rigid part of the
//! environment that rides on its junction's rigid body instead of following a motion.
//!
//! - **Pose.** The part's mesh is given where the hoses lie at rest (its reference
//!   placement). With the body's centre of mass c and orientation R_b now (rest: c₀, R₀),
//!   the part's pose is R = R_b R₀ᵀ, T = c − R c₀, and its twist the body's:
//!   ω, Ṫ = V + ω × (T − c) ([`crate::kinematics::Pose`], rigid velocity field).
//!   The explicit step places it so at the start of each step; contact then treats it
//!   as any moving part ([`crate::contact`], the part's velocity entering the contact and
//!   the friction).
//! - **Which hose points ignore it.** The body's own outlet nodes are dependent points of
//!   the body, and its hoses enter the piece at their outlets: from each outlet, a hose's
//!   nodes are excluded from contact with the shape as long as, at rest, they lie inside
//!   the shape's bounding box or their ball touches the shape; from the first node clear
//!   of both on, the hose touches its own junction's shape like any other. A beam is
//!   excluded when one of its nodes is.
//! - **Reaction.** Each contact impulse J_n the shape gives a hose node at x_n acts back
//!   on the body at once: −Σ J_n on its momentum and −Σ (x_n − c) × J_n on its angular
//!   momentum about its centre of mass (Newton's third law; the hoses' and the body's
//!   momentum together are unchanged by contact, linear and angular about any point).
//!   The velocity correction is shared as in a two-body impact along the normal: the
//!   hose point (effective mass m_h = Σ m_n w_n over the beam's weights) takes
//!   1 / (1 + m_h k_b) of it, with the body's inverse effective mass at the point
//!   k_b = 1/M + (r × n)·J⁻¹(r × n), so that a light piece is pushed rather than
//!   treated as immovable (which would overshoot and grow from step to step); the
//!   contacts are resolved one after the other, each seeing the body's velocity as the
//!   ones before left it. A body held by a support, or asleep, is immovable: a held
//!   body's support takes the impulses into its reaction.
//!
//! The Newton solvers (static, implicit) pose the shape from the body's master node and
//! give the contact's reaction to the body as a force and moment on it, the contact
//! coupling the hose node with the body in their tangent
//! ([`crate::newton::shape_contact`]).

use crate::kinematics::{Placement, Pose, Twist};
use crate::{Model, State};
use glam::DVec3;

/// The junction shapes of a model: which part rides on which junction, and which hose
/// nodes ignore it.
#[derive(Clone, Debug, Default)]
pub struct JunctionShapes {
    /// Per part: the junction (index into [`Model::junctions`]) it rides on, if any.
    pub junction_of_part: Vec<Option<usize>>,
    /// Per part riding on a junction: per node, whether that node ignores the part
    /// (empty for other parts).
    excluded: Vec<Vec<bool>>,
}

impl JunctionShapes {
    /// Whether any part rides on a junction.
    pub fn any(&self) -> bool {
        self.junction_of_part.iter().any(Option::is_some)
    }

    /// Whether node `i` ignores part `part` (it is a node of the piece's own hoses inside
    /// the piece near their outlets; see the module doc).
    #[inline]
    pub fn excludes_node(&self, part: usize, i: usize) -> bool {
        self.excluded
            .get(part)
            .and_then(|nodes| nodes.get(i))
            .copied()
            .unwrap_or(false)
    }

    /// Whether the beam between `a` and `b` ignores part `part` (one of its nodes does).
    #[inline]
    pub fn excludes_beam(&self, part: usize, a: usize, b: usize) -> bool {
        self.excludes_node(part, a) || self.excludes_node(part, b)
    }
}

impl Model {
    /// Lets junction `junction`'s body carry part `part` as its shape: the part becomes a
    /// moving part posed by the body, and the nodes of the junction's hoses inside it at
    /// rest ignore it (module doc). The part must stand still in the scene (no motion, no
    /// parent, not movable), carry no other part and ride on no other junction.
    pub(crate) fn attach_junction_shape(
        &mut self,
        junction: usize,
        part: usize,
    ) -> Result<(), String> {
        let parts = self.environment.parts.len();
        let Some(p) = self.environment.parts.get(part) else {
            return Err(format!("its shape names part {part} of {parts}"));
        };
        let name = p.name.clone();
        let kin = &self.kinematics;
        if p.moves || kin.motion(part).is_some() || kin.parent(part).is_some() {
            return Err(format!(
                "its shape, part '{name}', has a motion, a parent or may be moved by inputs; a junction body's shape rides on the body only"
            ));
        }
        if (0..parts).any(|k| kin.parent(k) == Some(part)) {
            return Err(format!(
                "its shape, part '{name}', carries other parts; a junction body's shape cannot"
            ));
        }
        let shapes = &mut self.junction_shapes;
        shapes.junction_of_part.resize(parts, None);
        shapes.excluded.resize(parts, Vec::new());
        if let Some(other) = shapes.junction_of_part[part] {
            return Err(format!(
                "its shape, part '{name}', is already the shape of junction '{}'",
                self.junctions[other].name
            ));
        }
        shapes.junction_of_part[part] = Some(junction);
        let excluded = self.nodes_inside_shape(junction, part);
        let shapes = &mut self.junction_shapes;
        shapes.excluded[part] = excluded;
        self.environment.parts[part].moves = true;
        self.environment.add_moving(part);
        Ok(())
    }

    /// Per node: whether it is one of junction `junction`'s hoses' nodes inside its shape
    /// `part` at rest, walking from each outlet into the hose (module doc).
    fn nodes_inside_shape(&self, junction: usize, part: usize) -> Vec<bool> {
        let shape = &self.environment.parts[part];
        let bounds = shape.mesh.local_aabb();
        let mut excluded = vec![false; self.node_count()];
        let inside = |i: usize| {
            let x = self.rest_x[i];
            let in_box = (0..3).all(|k| bounds.mins[k] <= x[k] && x[k] <= bounds.maxs[k]);
            let reach = self.radius[i] * (1.0 + crate::contact::CONTACT_SKIN);
            in_box || shape.closest_point_local(part, x, reach).is_some()
        };
        for &outlet in &self.junctions[junction].nodes {
            excluded[outlet] = true;
            let Some(hose) = self.hoses.iter().find(|h| h.nodes().contains(&outlet)) else {
                continue;
            };
            let inward: Box<dyn Iterator<Item = usize>> = if outlet == hose.first_node {
                Box::new(hose.nodes())
            } else {
                Box::new(hose.nodes().rev())
            };
            for i in inward.skip(1) {
                if !inside(i) {
                    break;
                }
                excluded[i] = true;
            }
        }
        excluded
    }

    /// Where junction `junction`'s body puts its shape, with the shape's twist, for the
    /// body's state `b` ([`crate::rod::stiffened::BodyState`]; module doc).
    pub fn junction_shape_placement(
        &self,
        junction: usize,
        b: &crate::rod::stiffened::BodyState,
    ) -> Placement {
        let body = &self.bodies[self.junctions[junction].body];
        let rotation = (b.orientation * body.rest_orientation.conjugate()).normalize();
        let translation = b.centre - rotation * body.rest_centre;
        Placement {
            pose: Pose {
                rotation,
                translation,
            },
            twist: Twist {
                linear: b.velocity + b.angular_velocity.cross(translation - b.centre),
                angular: b.angular_velocity,
            },
        }
    }

    /// Part `k`'s placement in `state` at time `t`: a junction shape's from its body's
    /// state, any other part's from the kinematics (moved by the state's inputs).
    pub fn part_placement(&self, state: &State, k: usize, t: f64) -> Placement {
        match self
            .junction_shapes
            .junction_of_part
            .get(k)
            .copied()
            .flatten()
        {
            Some(j) => self.junction_shape_placement(j, &state.bodies[self.junctions[j].body]),
            None => self.kinematics.placement_at(k, t, &state.part_moves),
        }
    }

    /// Whether part `k` moves: by its motion, its parent or inputs, or as a junction shape.
    pub fn part_moves(&self, k: usize) -> bool {
        self.kinematics.moves(k) || self.environment.parts.get(k).is_some_and(|p| p.moves)
    }

    /// Places every junction shape at its body's pose in `state.contact.placements`
    /// (after the parts' kinematics have placed the others).
    pub(crate) fn place_junction_shapes(&self, state: &mut State) {
        for (k, j) in self.junction_shapes.junction_of_part.iter().enumerate() {
            let Some(j) = *j else { continue };
            let b = state.bodies[self.junctions[j].body];
            state.contact.placements[k] = self.junction_shape_placement(j, &b);
        }
    }

    /// Whether junction `junction`'s body is immovable this step: held by a support (its
    /// reaction then takes the shape's impulses) or asleep.
    fn junction_body_immovable(&self, state: &State, junction: usize) -> bool {
        let nodes = &self.junctions[junction].nodes;
        (state.sleep.enabled && state.sleep.node_asleep[nodes[0]])
            || nodes.iter().any(|&i| state.loads.holds(i))
    }

    /// For a contact `c` on a junction body's shape (None for other parts): the shape's
    /// velocity at the contact point now, from its body's velocity (which the contacts
    /// before this one in the step have changed), and whether the body moves.
    pub(crate) fn junction_shape_contact(
        &self,
        state: &State,
        c: &crate::contact::ContactPoint,
    ) -> Option<ShapeContact> {
        let junction = (*self.junction_shapes.junction_of_part.get(c.part)?)?;
        let b = &state.bodies[self.junctions[junction].body];
        let point = (1.0 - c.t) * state.x[c.node_a] + c.t * state.x[c.node_b];
        let arm = point - b.centre;
        Some(ShapeContact {
            part: c.part,
            junction,
            arm,
            velocity: b.velocity + b.angular_velocity.cross(arm),
            movable: !self.junction_body_immovable(state, junction),
        })
    }

    /// Gives junction shape contact `s`'s body the reaction of the impulse `impulse` its
    /// shape gave hose nodes (moment `moment` about the world origin, Σ x_n × J_n): at
    /// once on a movable body's velocities, −J/M and −J_c⁻¹ (L_O − c × J) (module doc);
    /// an immovable body's is kept for its support's reaction
    /// ([`Self::react_on_junction_shapes`]).
    pub(crate) fn push_junction_shape(
        &self,
        state: &mut State,
        s: ShapeContact,
        impulse: DVec3,
        moment: DVec3,
    ) {
        if !s.movable {
            let kept = &mut state.contact.shape_impulse[s.part];
            kept.0 += impulse;
            kept.1 += moment;
            return;
        }
        let body = &self.bodies[self.junctions[s.junction].body];
        let b = &mut state.bodies[self.junctions[s.junction].body];
        b.velocity -= impulse / body.mass;
        let about_centre = moment - b.centre.cross(impulse);
        b.angular_velocity -= body.world_inertia(b.orientation).inverse() * about_centre;
    }

    /// After the step's contacts: each junction body with a shape moves its nodes with
    /// its velocities as the contacts left them; a body held by a support passes the
    /// impulses its shape took to the support's reaction (its reaction balances the
    /// body's momentum, [`crate::rod::stiffened::step_body`]).
    pub(crate) fn react_on_junction_shapes(&self, state: &mut State, dt: f64) {
        for (k, j) in self.junction_shapes.junction_of_part.iter().enumerate() {
            let Some(j) = *j else { continue };
            let (impulse, moment) = std::mem::take(&mut state.contact.shape_impulse[k]);
            let junction = &self.junctions[j];
            if let Some(&h) = junction.nodes.iter().find(|&&i| state.loads.holds(i)) {
                state.reaction_force[h] += impulse / dt;
                state.reaction_moment[h] += (moment - state.x[h].cross(impulse)) / dt;
                continue;
            }
            if self.junction_body_immovable(state, j) {
                continue; // asleep: it stays put
            }
            let body = &self.bodies[junction.body];
            let s = state.bodies[junction.body];
            for (n, &i) in body.nodes.iter().enumerate() {
                let o = s.orientation * body.offsets[n];
                state.v[i] = s.velocity + s.angular_velocity.cross(o);
                state.w[i] = s.angular_velocity;
            }
        }
    }
}

/// A contact on a junction body's shape, as the velocity correction sees it
/// ([`Model::junction_shape_contact`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShapeContact {
    part: usize,
    junction: usize,
    /// From the body's centre of mass to the contact point \[m\].
    arm: DVec3,
    /// The shape's velocity at the contact point \[m/s\].
    pub velocity: DVec3,
    /// Whether the body moves (neither held nor asleep).
    movable: bool,
}

impl ShapeContact {
    /// The shares of the velocity change along the normal `normal` and against the
    /// tangential velocity `tangential` that make the relative velocity what the contact
    /// asks, which the hose point of effective mass `hose_mass` takes: 1 / (1 + m_h k_b)
    /// with the body's inverse effective mass along each direction d,
    /// k_b = 1/M + (r × d)·J⁻¹(r × d) (two-body impact; the body takes the rest through
    /// the reaction). (1, 1) for an immovable body.
    pub fn hose_shares(
        &self,
        model: &Model,
        state: &State,
        hose_mass: f64,
        normal: DVec3,
        tangential: DVec3,
    ) -> (f64, f64) {
        if !self.movable {
            return (1.0, 1.0);
        }
        let b = model.junctions[self.junction].body;
        let body = &model.bodies[b];
        let inverse = body.world_inertia(state.bodies[b].orientation).inverse();
        let share = |d: DVec3| {
            let turn = self.arm.cross(d);
            1.0 / (1.0 + hose_mass * (1.0 / body.mass + turn.dot(inverse * turn)))
        };
        let t = tangential.normalize_or_zero();
        (share(normal), if t == DVec3::ZERO { 1.0 } else { share(t) })
    }
}
