//! Junctions (SPEC N1): hose ends joined into a network. A *welded branch point* joins
//! ends that meet at one point — position and rotation shared, each segment keeping the
//! tangent its data gives it; a *junction body* (a moulded T or Y piece) joins ends that
//! lie apart, at its outlets. Either way the joined end nodes move as one rigid body
//! ([`crate::rod::stiffened::RigidBody`]): the explicit solver steps it by Newton–Euler as it
//! does a stiffened section, the Newton solvers condense its nodes onto one master node
//! ([`crate::newton::condensation`]). A junction body's own mass is either lumped onto
//! its outlet nodes in equal shares — its centre of mass then the mean of its outlets and
//! its rotational inertia that of point masses there, exact for a symmetric piece, an
//! estimate otherwise — or, when its centre of mass or inertia is given, carried by the
//! rigid body as a mass of its own ([`crate::rod::attached`]): its weight acts at its
//! centre of mass and its inertia tensor joins the outlets' by the parallel-axis theorem
//! (equal nodal shares could not place a centre of mass outside the outlets' hull).

use crate::model::{Model, ModelError};
use crate::rod::attached::check_inertia;
use crate::rod::stiffened::RigidBody;
use glam::{DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Which end of a hose.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HoseEnd {
    Start,
    End,
}

/// What a caller hands [`Model::with_junctions`]: the ends to join.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct JunctionSpec {
    /// Name shown in outputs.
    pub name: String,
    /// The joined ends: hose index and which end.
    pub ends: Vec<(usize, HoseEnd)>,
    /// Mass of a junction body beyond the hoses' own \[kg\] (0 for a welded branch point).
    #[serde(default)]
    pub body_mass: f64,
    /// The body's own centre of mass at rest \[m\]. Given (or with `body_inertia`), the
    /// body's mass is its own rigid mass instead of equal shares on its outlets; absent
    /// then, the outlets' mean.
    #[serde(default)]
    pub body_centre: Option<DVec3>,
    /// The body's own inertia tensor about its centre of mass, world axes at rest
    /// \[kg·m²\]. Absent with `body_centre` given: zero (a point mass there).
    #[serde(default)]
    pub body_inertia: Option<DMat3>,
    /// The rigid part (index into the world's parts) that is the body's shape, given
    /// where the hoses lie at rest: it rides on the body and hoses touch it
    /// ([`crate::junction_shape`]). None: the body has no shape.
    #[serde(default)]
    pub shape: Option<usize>,
}

impl JunctionSpec {
    /// Whether the body's mass is a rigid mass of its own (centre or inertia given).
    pub fn has_own_mass(&self) -> bool {
        self.body_centre.is_some() || self.body_inertia.is_some()
    }
}

/// A built junction: its end nodes (global indices; the first is the Newton solvers'
/// master) and the rigid body they form.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Junction {
    pub name: String,
    pub nodes: Vec<usize>,
    /// Index into [`Model::bodies`].
    pub body: usize,
    /// The junction body's own mass properties at rest (zero mass for a welded branch
    /// point).
    pub own: OwnMass,
    /// The part that is the body's shape, if it has one ([`crate::junction_shape`]).
    pub shape: Option<usize>,
}

/// A junction body's own mass, centre of mass and inertia about it (world axes, at
/// rest), as the solvers treat it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OwnMass {
    /// \[kg\]
    pub mass: f64,
    /// \[m\]
    pub centre: DVec3,
    /// \[kg·m²\]
    pub inertia: DMat3,
    /// Whether the mass is lumped onto the outlets in equal shares (its centre their
    /// mean, its inertia theirs as point masses) rather than carried as given.
    pub lumped: bool,
}

impl Junction {
    /// Degree: how many hose ends meet here.
    pub fn degree(&self) -> usize {
        self.nodes.len()
    }
}

impl Model {
    /// Joins hose ends into junctions. Each end may belong to one junction, and not to a
    /// stiffened section; a junction joins at least two ends. (Whether the hoses and
    /// junctions form a tree is checked by the Newton solvers, which need one; the
    /// explicit solver steps any network.)
    pub fn with_junctions(mut self, junctions: &[JunctionSpec]) -> Result<Model, ModelError> {
        for spec in junctions {
            let err = |reason: String| {
                Err(ModelError::Junction {
                    junction: spec.name.clone(),
                    reason,
                })
            };
            if spec.ends.len() < 2 {
                return err(format!(
                    "joins {} hose end(s); needs at least 2",
                    spec.ends.len()
                ));
            }
            if !(spec.body_mass >= 0.0 && spec.body_mass.is_finite()) {
                return err(format!("body mass must be ≥ 0 kg, is {}", spec.body_mass));
            }
            let mut nodes = Vec::with_capacity(spec.ends.len());
            for &(hose, end) in &spec.ends {
                let Some(info) = self.hoses.get(hose) else {
                    return err(format!("names hose {hose} of {}", self.hoses.len()));
                };
                let node = match end {
                    HoseEnd::Start => info.first_node,
                    HoseEnd::End => info.first_node + info.node_count - 1,
                };
                if nodes.contains(&node) {
                    return err(format!("joins the {end:?} of hose '{}' twice", info.name));
                }
                if let Some(b) = self.body_of[node] {
                    let other = self
                        .junctions
                        .iter()
                        .find(|j| j.body == b)
                        .map(|j| format!("junction '{}'", j.name))
                        .unwrap_or_else(|| "a stiffened section".into());
                    return err(format!(
                        "the {end:?} of hose '{}' already belongs to {other}",
                        info.name
                    ));
                }
                nodes.push(node);
            }
            let outlets: Vec<DVec3> = nodes.iter().map(|&i| self.rest_x[i]).collect();
            let mean = outlets.iter().sum::<DVec3>() / nodes.len() as f64;
            let mut own = OwnMass {
                mass: spec.body_mass,
                centre: spec.body_centre.unwrap_or(mean),
                inertia: spec.body_inertia.unwrap_or(DMat3::ZERO),
                lumped: !spec.has_own_mass(),
            };
            if own.lumped {
                let share = spec.body_mass / nodes.len() as f64;
                for p in &outlets {
                    let o = *p - mean;
                    own.inertia += share
                        * (DMat3::IDENTITY * o.length_squared()
                            - DMat3::from_cols(o * o.x, o * o.y, o * o.z));
                }
            }
            let body = if spec.has_own_mass() {
                if !(spec.body_mass > 0.0) {
                    return err(
                        "a body with its own centre of mass or inertia needs a mass > 0 kg".into(),
                    );
                }
                let centre = own.centre;
                if !centre.is_finite() {
                    return err(format!("body centre of mass {centre} is not finite"));
                }
                let inertia = own.inertia;
                if let Some(j) = spec.body_inertia {
                    check_inertia(j).map_err(|reason| ModelError::Junction {
                        junction: spec.name.clone(),
                        reason: format!("body inertia tensor {reason}"),
                    })?;
                }
                RigidBody::with_attached(
                    nodes.clone(),
                    (&self.rest_x, &self.rest_q),
                    (&self.mass, &self.inertia),
                    spec.body_mass * self.mass_scaling,
                    centre,
                    inertia * self.mass_scaling,
                )
            } else {
                let share = spec.body_mass * self.mass_scaling / nodes.len() as f64;
                for &i in &nodes {
                    self.mass[i] += share;
                }
                RigidBody::new(
                    nodes.clone(),
                    &self.rest_x,
                    &self.rest_q,
                    &self.mass,
                    &self.inertia,
                )
            };
            for &i in &nodes {
                self.body_of[i] = Some(self.bodies.len());
            }
            self.junctions.push(Junction {
                name: spec.name.clone(),
                nodes,
                body: self.bodies.len(),
                own,
                shape: spec.shape,
            });
            self.bodies.push(body);
            if let Some(part) = spec.shape {
                let junction = self.junctions.len() - 1;
                self.attach_junction_shape(junction, part)
                    .map_err(|reason| ModelError::Junction {
                        junction: spec.name.clone(),
                        reason,
                    })?;
            }
        }
        self.hose_network = networks(self.hoses.len(), junctions);
        self.hose_contact = crate::contact::HoseContactModel::new(&self, self.hose_contact.rule);
        Ok(self)
    }

    /// Puts every junction's other end nodes where the rigid body of its first (master)
    /// node places them: x_k = c + R o_k, q_k = R f_k with R = q_master f_masterᵀ and
    /// c = x_master − R o_master (the body's rest offsets o and frames f).
    pub fn place_junction_nodes(&self, x: &mut [DVec3], q: &mut [DQuat]) {
        for junction in &self.junctions {
            let body = &self.bodies[junction.body];
            let m = junction.nodes[0];
            let r = (q[m] * body.frames[0].conjugate()).normalize();
            let centre = x[m] - r * body.offsets[0];
            for (k, &i) in junction.nodes.iter().enumerate().skip(1) {
                x[i] = centre + r * body.offsets[k];
                q[i] = (r * body.frames[k]).normalize();
            }
        }
    }

    /// The poses of all of a junction's nodes when its member `held` (a node index) is
    /// at (x_held, q_held): the rigid body's placement from that node.
    pub fn junction_poses_from(
        &self,
        junction: usize,
        held: usize,
        x_held: DVec3,
        q_held: DQuat,
    ) -> impl Iterator<Item = (usize, DVec3, DQuat)> + '_ {
        let j = &self.junctions[junction];
        let body = &self.bodies[j.body];
        let k = j.nodes.iter().position(|&i| i == held).unwrap_or(0);
        let r = (q_held * body.frames[k].conjugate()).normalize();
        let centre = x_held - r * body.offsets[k];
        j.nodes.iter().enumerate().map(move |(k, &i)| {
            (
                i,
                centre + r * body.offsets[k],
                (r * body.frames[k]).normalize(),
            )
        })
    }

    /// Each junction body's own mass with its pose: where its master node puts it.
    fn own_masses<'a>(
        &'a self,
        x: &'a [DVec3],
        q: &'a [DQuat],
    ) -> impl Iterator<Item = (usize, &'a RigidBody, DVec3, DQuat)> + 'a {
        self.junctions.iter().filter_map(move |j| {
            let body = &self.bodies[j.body];
            let m = j.nodes[0];
            body.attached.as_ref()?;
            let (centre, orientation) = body.pose_from_node(0, x[m], q[m]);
            Some((m, body, centre, orientation))
        })
    }

    /// Kinetic energy of the junction bodies' own masses,
    /// Σ ½ m_b |v_c|² + ½ Ωᵀ J_c Ω \[J\] (their nodes' is the nodes').
    pub fn own_mass_kinetic_energy(
        &self,
        (x, q): (&[DVec3], &[DQuat]),
        (v, w): (&[DVec3], &[DVec3]),
    ) -> f64 {
        self.own_masses(x, q)
            .filter_map(|(m, body, centre, orientation)| {
                let own = body.attached.as_ref()?;
                let c = centre + orientation * own.offset;
                let v_c = v[m] + w[m].cross(c - x[m]);
                let j = own.world_inertia(orientation);
                Some(0.5 * (own.mass * v_c.length_squared() + w[m].dot(j * w[m])))
            })
            .sum()
    }

    /// Potential energy of gravity of the junction bodies' own masses, −Σ m_b g·c \[J\].
    pub fn own_mass_gravity_energy(&self, x: &[DVec3], q: &[DQuat]) -> f64 {
        -self
            .own_masses(x, q)
            .filter_map(|(_, body, centre, orientation)| {
                let own = body.attached.as_ref()?;
                Some(own.mass * self.gravity.dot(centre + orientation * own.offset))
            })
            .sum::<f64>()
    }

    /// Whether any junction body carries a mass of its own.
    pub fn has_own_masses(&self) -> bool {
        self.bodies.iter().any(|b| b.attached.is_some())
    }

    /// The junction node `i` belongs to, if any.
    pub fn junction_of(&self, i: usize) -> Option<usize> {
        let b = self.body_of.get(i).copied().flatten()?;
        self.junctions.iter().position(|j| j.body == b)
    }
}

/// Per hose, the smallest index of the hoses joined to it through `junctions`
/// (connected components, by union–find with path halving).
fn networks(hoses: usize, junctions: &[JunctionSpec]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..hoses).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for j in junctions {
        for w in j.ends.windows(2) {
            let (a, b) = (root(&mut parent, w[0].0), root(&mut parent, w[1].0));
            parent[a.max(b)] = a.min(b);
        }
    }
    (0..hoses).map(|h| root(&mut parent, h)).collect()
}
