//! Assembly of the nodal loads of all elements, gravity (P6) and damping (P4).

use crate::element::ElementEnds;
use crate::Model;
use glam::{DQuat, DVec3};

/// Borrowed node arrays of a configuration.
pub struct Config<'a> {
    pub x: &'a [DVec3],
    pub q: &'a [DQuat],
    pub v: &'a [DVec3],
    pub w: &'a [DVec3],
}

/// Writes the internal element loads (with stiffness-proportional damping β) into
/// `force` and `moment`, overwriting them. No allocation.
pub fn internal_loads(
    model: &Model,
    c: &Config,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
) {
    internal_loads_except(model, c, beta, force, moment, |_| false);
}

/// [`internal_loads`] leaving out the elements whose first node `skip` selects (the
/// elements of sleeping hoses, [`crate::sleep`]).
pub fn internal_loads_except(
    model: &Model,
    c: &Config,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
    skip: impl Fn(usize) -> bool,
) {
    force.fill(DVec3::ZERO);
    moment.fill(DVec3::ZERO);
    for e in &model.elements {
        let (a, b) = (e.node_a, e.node_b);
        if skip(a) {
            continue;
        }
        let ends = ElementEnds {
            x: [c.x[a], c.x[b]],
            q: [c.q[a], c.q[b]],
            v: [c.v[a], c.v[b]],
            w: [c.w[a], c.w[b]],
        };
        let l = e.loads(&ends, beta);
        force[a] += l.force[0];
        force[b] += l.force[1];
        moment[a] += l.moment[0];
        moment[b] += l.moment[1];
    }
}

/// Adds gravity m g and mass-proportional damping −α m v, −α I ω.
pub fn add_body_loads(model: &Model, c: &Config, force: &mut [DVec3], moment: &mut [DVec3]) {
    let alpha = model.damping_mass;
    for i in 0..force.len() {
        force[i] += model.mass[i] * (model.gravity - alpha * c.v[i]);
        moment[i] -= alpha * model.inertia[i] * c.w[i];
    }
}
