//! Hoses resting on a still part come to rest under the explicit solver: kinetic energy
//! and out-of-balance force go to zero, and the contact carries what the supports do not
//! (SPEC L4). A contact found within the detection skin, still short of the surface, lets
//! the point close that gap in the step and holds it only there.

use glam::DVec3;
use parry3d_f64::shape::Cuboid;
use pliant_core::relax::{relax, RelaxOptions, RelaxReport};
use pliant_core::{HoseSpec, Model, RigidPartSpec, SimSettings, State, WorldSpec};
use pliant_testkit::hoses::hose3;
use pliant_testkit::models::fix_in_place;

/// Hose 3's outer radius \[m\].
const R: f64 = 0.0175;

/// Hose 3 in `elements` beams of 50 mm along x from the origin at height `z`, over an
/// 80 × 80 × 10 mm block whose top face is at z = 0, centred under x = `over`.
fn hose_over_block(elements: usize, z: f64, over: f64) -> Model {
    let (material, section) = hose3();
    let (vertices, triangles) = Cuboid::new(DVec3::new(0.04, 0.04, 0.005)).to_trimesh();
    let block = RigidPartSpec {
        name: "block".into(),
        vertices: vertices
            .iter()
            .map(|p| DVec3::new(p.x + over, p.y, p.z - 0.005))
            .collect(),
        triangles,
        friction_static: 0.6,
        friction_sliding: 0.5,
        motion: None,
        parent: None,
        movable: false,
    };
    Model::build(&WorldSpec {
        hoses: vec![HoseSpec {
            name: "h".into(),
            material,
            nodes: (0..=elements)
                .map(|i| DVec3::new(0.05 * i as f64, 0.0, z))
                .collect(),
            sections: vec![section],
            normal_hint: Some(DVec3::Y),
        }],
        rigid_parts: vec![block],
        settings: SimSettings::default(),
    })
    .unwrap()
}

/// Relaxes with kinetic damping to 1 mN and 0.1 mN·m within `max_steps`.
fn settle(model: &Model, state: &mut State, max_steps: u64) -> RelaxReport {
    let opts = RelaxOptions {
        force_tolerance: 1e-3,
        moment_tolerance: 1e-4,
        max_steps,
        kinetic_damping: true,
    };
    relax(model, state, &opts).unwrap()
}

/// A 200 mm span of hose 3 held at both ends (position and orientation) 2 or 5 mm lower
/// than it would rest on a block under its middle: it bends over the block's two top
/// edges, where its beams' interiors touch. It comes to rest — converged, kinetic energy
/// below the `settle` action's default 1 µJ — and, at rest, the block's push and the
/// fixes' reactions carry its weight (0.84 N) to the residual's tolerance summed over the
/// three free nodes, 3 mN (the elastic forces are internal).
#[test]
fn a_span_between_two_fixes_pressed_onto_a_block_comes_to_rest() {
    for lower in [0.002, 0.005] {
        let elements = 4;
        let model = hose_over_block(elements, R - lower, 0.1);
        let mut state = State::at_rest(&model);
        fix_in_place(&mut state, [0, elements]);
        let report = settle(&model, &mut state, 20_000);
        assert!(report.converged, "{lower} m lower: {report:?}");
        let energy = state.kinetic_energy(&model);
        assert!(energy < 1e-6, "{lower} m lower: kinetic energy {energy} J");
        assert!(
            !state.contact.points.is_empty(),
            "{lower} m lower: rests on the block"
        );
        let weight: DVec3 = model.mass.iter().map(|m| *m * model.gravity).sum();
        let carried: DVec3 = (0..=elements)
            .map(|i| state.reaction_force[i] + state.contact_force[i])
            .sum();
        let balance = (weight + carried).length();
        assert!(
            balance < 3e-3,
            "{lower} m lower: weight {weight} against supports and contact {carried}"
        );
    }
}

/// A straight hose released 1.5 mm above the middle of a block's top face with its ends
/// free: within the detection skin (1 % of the radius, 0.175 mm) of the face, it lands on
/// it. It comes to rest touching the face (its lowest point at the radius to 1 µm), not
/// hovering where its contact was first found.
#[test]
fn a_hose_found_within_the_skin_lands_on_the_face() {
    let gap = 0.5 * 0.01 * R;
    let model = hose_over_block(1, R + gap, 0.025);
    let mut state = State::at_rest(&model);
    let report = settle(&model, &mut state, 20_000);
    assert!(report.converged, "{report:?}");
    for (i, x) in state.x.iter().enumerate() {
        assert!((x.z - R).abs() < 1e-6, "node {i} at z = {} m", x.z);
    }
}
