//! Deep penetration into a rigid part is resolved over a few steps by moving positions,
//! never by an explosive force (SPEC L4).

use glam::DVec3;
use pliant_core::{
    integrators::explicit, HoseSpec, Material, Model, RigidPartSpec, Section, SimSettings, State,
    WorldSpec,
};

/// A hose of outer radius `r` through `nodes` and one rigid `part`, without gravity or
/// mass damping.
fn hose_of_radius_over(r: f64, nodes: Vec<DVec3>, part: RigidPartSpec) -> Model {
    let hose = HoseSpec {
        name: "h".into(),
        material: Material::isotropic(12e6, 0.49, 940.0),
        nodes,
        sections: vec![Section::new(0.010, 2.0 * r)],
        normal_hint: None,
    };
    let settings = SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 0.0,
        ..Default::default()
    };
    Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: vec![part],
        settings,
    })
    .unwrap()
}

#[test]
fn deep_penetration_is_pushed_out_gently() {
    let r = 0.008;
    let nodes = (0..=20)
        .map(|i| DVec3::new(0.025 * i as f64, 0.0, 0.5 * r))
        .collect(); // half a radius too deep
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
        motion: None,
        parent: None,
        movable: false,
    };
    let model = hose_of_radius_over(r, nodes, floor);
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

/// A beam's interior contact is the nearest pair strictly inside the beam between it and
/// any mesh edge: a beam whose one end lies beside an edge of a triangle (that end is a
/// node, with its own contact) and whose interior crosses over another edge of the same
/// triangle, within reach of it, is held at that crossing — even though the triangle's
/// nearest edge is the first one, at the end.
#[test]
fn a_beam_crossing_an_edge_is_held_there_though_another_edge_is_nearer_its_end() {
    let r = 0.008;
    let (a, b) = (DVec3::new(0.06, -0.001, 0.0), DVec3::new(0.2, 0.08, 0.0094));
    let triangle = RigidPartSpec {
        name: "triangle".into(),
        vertices: vec![
            DVec3::ZERO,
            DVec3::new(0.2, 0.0, 0.0),
            DVec3::new(0.0, 0.2, 0.0),
        ],
        triangles: vec![[0, 1, 2]],
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion: None,
        parent: None,
        movable: false,
    };
    let model = hose_of_radius_over(r, vec![a, b], triangle);
    let mut state = State::at_rest(&model);
    explicit::step(&model, &mut state);
    let points = &state.contact.points;
    assert!(
        points.iter().any(|c| c.node_a == 0 && c.node_b == 0),
        "the end beside the first edge touches it: {points:?}"
    );
    // the crossing over the hypotenuse x + y = 0.2, 6 mm above it
    let crossing = (0.2 - (a.x + a.y)) / ((b.x + b.y) - (a.x + a.y));
    let interior = points
        .iter()
        .find(|c| c.node_a != c.node_b)
        .expect("an interior contact where the beam crosses the hypotenuse");
    assert!(
        (interior.t - crossing).abs() < 0.05,
        "at t = {}, the crossing at {crossing}",
        interior.t
    );
    assert!(
        interior.depth > r - 0.0061 && interior.depth < r,
        "depth {} (the beam's axis ≤ 6 mm from the edge)",
        interior.depth
    );
}
