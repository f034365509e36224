//! `hose_contact` (SPEC L5): two hoses crossing at right angles, each clamped at both
//! ends, the upper one pressed down at its middle by a dead load of 2 N. At rest the
//! contact forces on the two hoses are equal and opposite, the lower hose's supports carry
//! exactly the force the contact passes on (static balance, 1 %), and the capsules
//! interpenetrate by less than 2 % of the radius.

use crate::harness::{dead_load, hose1, settle_to};
use crate::Check;
use glam::DVec3;
use pliant_core::contact::hose_hose::closest_segment_segment;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{HoseSpec, Model, SimSettings, State, WorldSpec};

/// Elements per hose.
pub const N: usize = 20;
/// The dead load pressing the upper hose down at its middle \[N\].
pub const LOAD: f64 = 2.0;

/// The two crossing hoses, clamped at both ends, the upper one touching the lower one at
/// the crossing and loaded by [`LOAD`] at its middle (node N + 1 + N/2), not yet at rest.
pub fn crossing_hoses() -> Result<(Model, State), String> {
    let (mat, sec) = hose1();
    let r = sec.outer_radius();
    let line = |name: &str, from: DVec3, to: DVec3| HoseSpec {
        name: name.into(),
        material: mat.clone(),
        nodes: (0..=N)
            .map(|i| from.lerp(to, i as f64 / N as f64))
            .collect(),
        sections: vec![sec],
        normal_hint: None,
    };
    // the upper hose lies on the lower one, touching at the crossing
    let lower = line(
        "lower",
        DVec3::new(-0.25, 0.0, 0.0),
        DVec3::new(0.25, 0.0, 0.0),
    );
    let upper = line(
        "upper",
        DVec3::new(0.0, -0.25, 2.0 * r),
        DVec3::new(0.0, 0.25, 2.0 * r),
    );
    let settings = SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 0.0,
        damping_stiffness: None,
        ..Default::default()
    };
    let model = Model::build(&WorldSpec {
        hoses: vec![lower, upper],
        rigid_parts: vec![],
        settings,
    })
    .map_err(|e| e.to_string())?;
    let mut state = State::at_rest(&model);
    for i in [0, N, N + 1, 2 * N + 1] {
        state.loads.add(LoadCase::Fix(Fix {
            node: i,
            position: state.x[i],
            orientation: state.q[i],
        }));
    }
    let mid_upper = N + 1 + N / 2;
    state.loads.add(dead_load(
        mid_upper,
        DVec3::new(0.0, 0.0, -LOAD),
        DVec3::ZERO,
    ));
    Ok((model, state))
}

/// The total hose–hose contact force on hose `h` \[N\].
pub fn contact_force_on(model: &Model, state: &State, h: usize) -> DVec3 {
    model.hoses[h]
        .nodes()
        .map(|i| state.hose_contact_force[i])
        .sum()
}

pub fn run() -> Vec<Check> {
    let (model, mut state) = match crossing_hoses() {
        Ok(m) => m,
        Err(e) => return vec![Check::failed("hose_contact", "model", &e)],
    };
    let (f, r) = (LOAD, model.radius[0]);
    if let Err(e) = settle_to(&model, &mut state, f, 0.5, 1e-7) {
        return vec![Check::failed("hose_contact", "relaxation", &e)];
    }
    let (on_lower, on_upper) = (
        contact_force_on(&model, &state, 0),
        contact_force_on(&model, &state, 1),
    );
    let lower_supports: DVec3 = [0, N].iter().map(|&i| state.reaction_force[i]).sum();
    let mut gap = f64::INFINITY;
    for a in model.hoses[0].first_element..model.hoses[0].first_element + N {
        for b in model.hoses[1].first_element..model.hoses[1].first_element + N {
            let (ea, eb) = (&model.elements[a], &model.elements[b]);
            let (p1, q1, p2, q2) = (
                state.x[ea.node_a],
                state.x[ea.node_b],
                state.x[eb.node_a],
                state.x[eb.node_b],
            );
            let (s, t) = closest_segment_segment(p1, q1, p2, q2);
            gap = gap.min((p1.lerp(q1, s) - p2.lerp(q2, t)).length() - 2.0 * r);
        }
    }
    let penetration = (-gap).max(0.0);
    vec![
        Check::with_error(
            "hose_contact",
            "|F_lower + F_upper| / |F_lower| (action = reaction)",
            (on_lower + on_upper).length() / on_lower.length(),
            0.0,
            (on_lower + on_upper).length() / on_lower.length(),
            1e-9,
        ),
        Check::relative(
            "hose_contact",
            "lower hose supports = contact force on it N",
            -lower_supports.z,
            on_lower.z,
            0.01,
        ),
        Check::with_error(
            "hose_contact",
            "penetration / r",
            penetration / r,
            0.0,
            penetration / r,
            0.02,
        ),
    ]
}
