//! Deep penetration into a rigid part is resolved over a few steps by moving positions,
//! never by an explosive force (SPEC L4).

use glam::DVec3;
use pliant_core::{
    integrators::explicit, HoseSpec, Material, Model, RigidPartSpec, Section, SimSettings, State,
    WorldSpec,
};

#[test]
fn deep_penetration_is_pushed_out_gently() {
    let r = 0.008;
    let nodes = (0..=20)
        .map(|i| DVec3::new(0.025 * i as f64, 0.0, 0.5 * r))
        .collect(); // half a radius too deep
    let hose = HoseSpec {
        name: "h".into(),
        material: Material::isotropic(12e6, 0.49, 940.0),
        nodes,
        sections: vec![Section::new(0.010, 2.0 * r)],
        normal_hint: None,
    };
    let floor = RigidPartSpec {
        name: "floor".into(),
        vertices: vec![
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(2.0, -1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        friction_static: 0.5,
        friction_sliding: 0.4,
    };
    let settings = SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 0.0,
        ..Default::default()
    };
    let model = Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: vec![floor],
        settings,
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    let mut steps_to_clear = None;
    for k in 0..50 {
        explicit::step(&model, &mut state);
        let lowest = state.x.iter().map(|x| x.z).fold(f64::INFINITY, f64::min);
        if steps_to_clear.is_none() && lowest >= r * (1.0 - 1e-9) {
            steps_to_clear = Some(k + 1);
        }
    }
    let k = steps_to_clear.expect("pushed out within 50 steps");
    assert!(
        (5..=10).contains(&k),
        "out after {k} steps: 10 % of r per step"
    );
    // positions were corrected, velocities not: nothing flies off
    let fastest = state.v.iter().map(|v| v.length()).fold(0.0, f64::max);
    assert!(fastest < 1e-6, "fastest node {fastest} m/s");
}
