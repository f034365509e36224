//! A junction body's shape (`[[junctions]] body = { …, part = "NAME" }`): the part rides on
//! the body, the body's own hose nodes inside it ignore it, the Newton solvers take it
//! (the contact's reaction on the body, Newton converging quadratically with the shape's
//! coupling of hose and body nodes), and every bad part is refused naming the field and
//! the reason.

use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::newton::system::{apply_increment, residual_norms};
use pliant_core::newton::NewtonSystem;
use pliant_scene::{load_scene_str, LoadedScene, SceneError};
use pliant_testkit::scenes::{HEAD_MM, TEE_MM};

/// A 20 × 10 × 10 mm box between the tee's outlets (x = 200 … 220 mm), and more parts.
const BOX: &str = r#"
[[parts]]
name = "tee_box"
box = { size = [20, 10, 10] }
position = [210, 0, 0]
"#;

fn load(body: &str, parts: &str) -> Result<LoadedScene, SceneError> {
    let text = format!("{HEAD_MM}{TEE_MM}body = {body}\n{parts}");
    load_scene_str(&text, "junction_shape.toml")
}

fn error(body: &str, parts: &str) -> String {
    match load(body, parts) {
        Ok(_) => panic!("{body} with {parts} was accepted"),
        Err(e) => e.to_string(),
    }
}

const SHAPED: &str = r#"{ mass_kg = 0.02, centre_of_mass = [210, 0, 0], inertia_kg_m2 = [3e-7, 8e-7, 8e-7], part = "tee_box" }"#;

#[test]
fn the_shape_rides_on_the_body_and_its_own_outlets_ignore_it() {
    let scene = load(SHAPED, BOX).unwrap();
    assert_eq!(scene.junctions[0].shape, Some(0));
    let model = scene.build_model().unwrap();
    assert_eq!(model.junctions[0].shape, Some(0));
    assert!(model.part_moves(0), "the shape is a moving part");
    assert!(model.junction_shapes.any());
    let outlets = model.junctions[0].nodes.clone();
    for &i in &outlets {
        assert!(model.junction_shapes.excludes_node(0, i), "outlet node {i}");
    }
    // hose a's node before its outlet lies 50 mm from the box: it touches the shape
    let before = outlets[0] - 1;
    assert!(!model.junction_shapes.excludes_node(0, before));
    assert!(!model.junction_shapes.excludes_beam(0, before - 1, before));
    // at rest the shape is where the scene put it
    let state = pliant_core::State::at_rest(&model);
    let pose = model.part_placement(&state, 0, 0.0).pose;
    assert!(pose.translation.length() < 1e-12, "{pose:?}");
    assert!(pose.rotation.abs_diff_eq(glam::DQuat::IDENTITY, 1e-12));
}

/// Hose "c" (library hose 1, r = 8 mm) along y across the top of a 20 × 100 × 20 mm box
/// between the tee's outlets, touching it; the box rubs (μ_s = 0.5).
const RESTING: &str = r#"
[[parts]]
name = "tee_box"
box = { size = [20, 100, 20] }
position = [210, 0, 0]
friction = { static = 0.5, sliding = 0.4 }

[[hoses]]
name = "c"
material = "hose1"
elements = 8
start = [210, -40, 18]
path = [{ line = { to = [210, 40, 18] } }]
"#;

/// The resting scene's model under gravity, hose a clamped at its start and b at its end.
fn resting() -> (pliant_core::Model, pliant_core::State) {
    let model = load(SHAPED, RESTING).unwrap().build_model().unwrap();
    let mut state = pliant_core::State::at_rest(&model);
    let b_end = model.hoses[1].nodes().end - 1;
    for node in [0, b_end] {
        state.loads.add(LoadCase::Fix(Fix {
            node,
            position: state.x[node],
            orientation: state.q[node],
        }));
    }
    (model, state)
}

/// The free nodes' largest out-of-balance force after full Newton steps (no line
/// search) from `state`, each solve with the shape's coupling across the matrix's band
/// or without it (`coupled`).
fn newton_residuals(
    model: &pliant_core::Model,
    state: &mut pliant_core::State,
    coupled: bool,
    iterations: usize,
) -> Vec<f64> {
    let mut sys = NewtonSystem::new(model).unwrap();
    sys.set_prescribed(model, state, state.time);
    let mut out = Vec::new();
    for _ in 0..iterations {
        sys.assemble(model, state, 0.0);
        out.push(residual_norms(&sys.force, &sys.moment, &sys.prescribed).0);
        for i in 0..sys.rhs.len() {
            let (f, m) = (sys.force[i], sys.moment[i]);
            sys.rhs[i] = nalgebra::Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z);
        }
        sys.eliminate_prescribed();
        if !coupled {
            sys.shape_couplings.clear();
        }
        sys.solve_linear(false).unwrap();
        apply_increment(state, &sys.rhs, &sys.prescribed, 1.0);
    }
    out
}

#[test]
fn the_newton_solvers_take_a_shape_and_its_reaction_reaches_the_clamp() {
    let (model, state) = resting();
    let weight = 9.81 * (0.02 + model.mass.iter().sum::<f64>());
    let c_weight = 9.81 * model.hoses[2].nodes().map(|i| model.mass[i]).sum::<f64>();
    // static; then implicit steps from that equilibrium, which must keep it
    let mut settled = state;
    let mut solver = StaticSolver::new(&model).unwrap();
    let report = solver.solve(&model, &mut settled).unwrap();
    assert!(report.converged, "{report:?}");
    let mut moving = settled.clone();
    let options = ImplicitOptions {
        time_step: 0.01,
        ..Default::default()
    };
    let mut implicit = ImplicitSolver::new(&model, options).unwrap();
    for _ in 0..20 {
        implicit.step(&model, &mut moving).unwrap();
    }
    let drift = (moving.x.iter().zip(&settled.x))
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0, f64::max);
    assert!(
        drift < 1e-6,
        "implicit moved {drift} m off the static equilibrium"
    );
    for (solver, s) in [("static", &settled), ("implicit", &moving)] {
        // the clamps carry every weight, the resting hose's through the box and the tee
        let b_end = model.hoses[1].nodes().end - 1;
        let carried = s.reaction_force[0].z + s.reaction_force[b_end].z;
        assert!(
            (carried - weight).abs() < 1e-3 * weight,
            "{solver}: clamps {carried} N, weights {weight} N"
        );
        // hose c rests on the box: the shape holds its weight up
        let held: f64 = model.hoses[2].nodes().map(|i| s.contact_force[i].z).sum();
        assert!(
            (held - c_weight).abs() < 2e-2 * c_weight,
            "{solver}: box holds {held} N of c's {c_weight} N"
        );
        // the shape's placement follows the body (reports and the viewer read it)
        let body = model.junctions[0].body;
        let pose = model.junction_shape_placement(0, &s.bodies[body]).pose;
        assert_eq!(s.contact.placements[0].pose, pose, "{solver}");
        assert!(pose.translation.length() > 1e-4, "{solver}: the tee sagged");
    }
}

#[test]
fn newton_converges_quadratically_with_the_shape_coupling() {
    let (model, mut state) = resting();
    let mut solver = StaticSolver::new(&model).unwrap();
    assert!(solver.solve(&model, &mut state).unwrap().converged);
    // from that equilibrium to the one under half as much weight again
    let mut heavier = model.clone();
    heavier.gravity *= 1.5;
    let coupled = newton_residuals(&heavier, &mut state.clone(), true, 6);
    let lagged = newton_residuals(&heavier, &mut state.clone(), false, 6);
    let r0 = coupled[0];
    // once near (within 1 % of the first residual, above round-off), each step squares
    // the relative residual, to a factor of 10
    let near = (0..coupled.len() - 1)
        .find(|&k| coupled[k] < 1e-2 * r0 && coupled[k] > 1e-6 * r0)
        .unwrap_or_else(|| panic!("never near: {coupled:?}"));
    let (now, next) = (coupled[near] / r0, coupled[near + 1] / r0);
    assert!(next <= 10.0 * now * now, "not quadratic: {coupled:?}");
    assert!(coupled[5] < 1e-8 * r0, "{coupled:?}");
    // without the coupling of hose and body nodes the full Newton steps go astray
    assert!(lagged[5] > 1e3 * coupled[5], "{lagged:?} vs {coupled:?}");
}

#[test]
fn bad_shapes_are_refused_naming_the_field() {
    let moving = format!(
        "{BOX}motion = {{ kind = \"slide\", direction = [1, 0, 0], distance = {{ times_s = [0, 1], values = [0, 10] }} }}\n"
    );
    let carried = format!("{BOX}parent = \"frame\"\n[[parts]]\nname = \"frame\"\nbox = {{ size = [10, 10, 10] }}\nposition = [0, 100, 0]\n");
    let carrier = format!("{BOX}\n[[parts]]\nname = \"lid\"\nbox = {{ size = [10, 10, 10] }}\nposition = [210, 0, 20]\nparent = \"tee_box\"\n");
    let cases: &[(&str, String, &str)] = &[
        (
            r#"{ part = "nothing" }"#,
            BOX.to_string(),
            "no part of this name",
        ),
        (r#"{ part = "tee_box" }"#, moving, "has a `motion`"),
        (r#"{ part = "tee_box" }"#, carried, "has a `parent`"),
        (
            r#"{ part = "tee_box" }"#,
            carrier,
            "part \"lid\" has it as its `parent`",
        ),
    ];
    for (body, parts, reason) in cases {
        let e = error(body, parts);
        assert!(e.contains("junctions[0].body.part"), "{e}");
        assert!(e.contains(reason), "{reason}: {e}");
    }
}
