//! Yielding metal lines (SPEC X1) through the solvers: bent to a uniform curvature by
//! holding the end on an arc (the mandrel's curvature), released, they spring back to
//! the curvature κ − M(κ)/EI of the closed form and keep it.

use glam::{DQuat, DVec3};
use pliant_core::integrators::{explicit, StaticSolver};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::material::YieldLaw;
use pliant_core::newton::convergence::Tolerance;
use pliant_core::rod::plastic_moment;
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};

const E: f64 = 200e9;
const SY: f64 = 250e6;
const L: f64 = 0.1;
const N: usize = 20;
const DI: f64 = 0.006;
const DO: f64 = 0.008;

fn steel(hardening: f64) -> Material {
    let mut m = Material::isotropic(E, 0.3, 7850.0);
    m.plasticity = Some(YieldLaw {
        yield_stress: SY,
        hardening_modulus: hardening,
    });
    m
}

fn line(material: Material) -> (Model, State) {
    let nodes = (0..=N)
        .map(|i| DVec3::new(L * i as f64 / N as f64, 0.0, 0.0))
        .collect();
    let model = Model::build(&WorldSpec {
        hoses: vec![HoseSpec {
            name: "brake line".into(),
            material,
            nodes,
            sections: vec![Section::new(DI, DO)],
            normal_hint: Some(DVec3::Y),
        }],
        rigid_parts: vec![],
        settings: SimSettings {
            gravity: DVec3::ZERO,
            ..Default::default()
        },
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: DVec3::ZERO,
        orientation: model.rest_q[0],
    }));
    (model, state)
}

/// The pose at arc length `s` of the arc of curvature `kappa` in the x–y plane.
fn arc(model: &Model, kappa: f64, s: f64) -> (DVec3, DQuat) {
    let phi = kappa * s;
    let x = DVec3::new(phi.sin() / kappa, (1.0 - phi.cos()) / kappa, 0.0);
    (x, DQuat::from_rotation_z(phi) * model.rest_q[N])
}

/// The angle the tip turned about z.
fn tip_angle(state: &State, model: &Model) -> f64 {
    let q = state.q[N] * model.rest_q[N].conjugate();
    let (axis, angle) = q.to_axis_angle();
    angle * axis.z.signum()
}

/// Bends the line to curvature `kappa` in `steps` static solves, returns the tip's
/// reaction moment, then releases the tip and returns the curvature it springs back to.
fn bend_and_release(material: Material, kappa: f64, steps: usize) -> (f64, f64, Model, State) {
    let (model, mut state) = line(material);
    let tip = state.loads.add(LoadCase::Fix(Fix {
        node: N,
        position: model.rest_x[N],
        orientation: model.rest_q[N],
    }));
    let mut solver = StaticSolver::new(&model).unwrap();
    // pure bending carries no shear: the element forces (the relative test's force scale)
    // are round-off, so the force residual gets a floor of 1 µN (against moments of
    // ~10 N·m on 5 mm elements: 2000 N of shear scale)
    solver.options.tolerance = Tolerance {
        force: 1e-6,
        ..Tolerance::default()
    };
    for k in 1..=steps {
        let (x, q) = arc(&model, kappa * k as f64 / steps as f64, L);
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(tip) {
            f.position = x;
            f.orientation = q;
        }
        let report = solver.solve(&model, &mut state).unwrap();
        assert!(report.converged, "step {k}: {report:?}");
    }
    let moment = state.reaction_moment[N].z.abs();
    state.loads.remove(tip);
    let report = solver.solve(&model, &mut state).unwrap();
    assert!(report.converged, "release: {report:?}");
    (moment, tip_angle(&state, &model) / L, model, state)
}

/// Bent to R = 50 mm (64 times the first-yield curvature) in 40 static steps, the tube
/// (H = 1 % of E) carries M(κ) of the closed form and springs back by M/EI:
/// 1/R_after = 1/R − M/EI; released, it keeps the set.
#[test]
fn springback_after_bending_to_a_mandrel_radius() {
    let (ri, ro, h) = (0.5 * DI, 0.5 * DO, 2e9);
    let ei = E * Section::new(DI, DO).second_moment();
    let kappa = 1.0 / 0.05;
    let (moment, after, model, state) = bend_and_release(steel(h), kappa, 40);
    let want = plastic_moment::hardening_bending_moment(ri, ro, E, SY, h, kappa);
    let springback = kappa - after;
    let want_springback = want / ei;
    println!(
        "M {moment:.4} N·m (closed form {want:.4}, {:+.3} %); springback Δκ {springback:.5} 1/m \
         (closed form {want_springback:.5}, {:+.3} %)",
        100.0 * (moment / want - 1.0),
        100.0 * (springback / want_springback - 1.0)
    );
    assert!(
        (moment / want - 1.0).abs() < 0.005,
        "moment {moment} vs {want}"
    );
    assert!(
        (springback / want_springback - 1.0).abs() < 0.005,
        "springback {springback} vs {want_springback}"
    );
    // the permanent set is kept: no moment left, still bent (not straight again)
    assert!(state.reaction_moment[0].length() < 1e-6 * want);
    assert!(after > 0.9 * kappa);
    // and it stays so under further explicit steps
    let mut s = state.clone();
    for _ in 0..2000 {
        explicit::step(&model, &mut s);
    }
    let drift = (tip_angle(&s, &model) / L - after).abs();
    assert!(drift < 1e-3 * kappa, "drift {drift}");
}

/// A perfectly plastic tube (H = 0) bent to 6.4 times its first-yield curvature in small
/// steps springs back by M/EI of the closed form.
#[test]
fn perfectly_plastic_springback() {
    let (ri, ro) = (0.5 * DI, 0.5 * DO);
    let ei = E * Section::new(DI, DO).second_moment();
    let kappa = 2.0;
    let (moment, after, ..) = bend_and_release(steel(0.0), kappa, 30);
    let want = plastic_moment::bending_moment(ri, ro, E, SY, kappa);
    let springback = kappa - after;
    println!(
        "EPP: M {moment:.4} (closed form {want:.4}, {:+.3} %), springback {springback:.5} \
         (closed form {:.5}, {:+.3} %)",
        100.0 * (moment / want - 1.0),
        want / ei,
        100.0 * (springback * ei / want - 1.0)
    );
    assert!(
        (moment / want - 1.0).abs() < 0.005,
        "moment {moment} vs {want}"
    );
    assert!((springback * ei / want - 1.0).abs() < 0.005, "{springback}");
}

/// Below first yield the line springs straight back (elastic), and a material that
/// never yields is not slowed: its elements stay in the packed kernel.
#[test]
fn below_yield_the_line_springs_back_straight() {
    let ke = SY / (E * 0.5 * DO);
    let (_, after, model, _) = bend_and_release(steel(0.0), 0.8 * ke, 2);
    assert!(after.abs() < 1e-6 * ke, "{after}");
    assert!(model.inelastic.any());
    let (elastic, _) = line(Material::isotropic(E, 0.3, 7850.0));
    assert!(!elastic.inelastic.any());
    assert_eq!(elastic.packed.blocks.len(), N.div_ceil(4));
}

/// With hardening the moment at the same curvature is larger and the springback larger.
#[test]
fn hardening_raises_the_moment_and_the_springback() {
    let kappa = 2.0;
    let (m0, a0, ..) = bend_and_release(steel(0.0), kappa, 30);
    let (m1, a1, ..) = bend_and_release(steel(2e9), kappa, 30);
    assert!(m1 > m0 * 1.01, "{m1} vs {m0}");
    assert!(kappa - a1 > kappa - a0, "{a1} vs {a0}");
}

/// A yielding material refuses a section with given stiffness (the fibres need the tube).
#[test]
fn a_yielding_material_needs_the_tube() {
    let mut section = Section::new(DI, DO);
    section.given.bending = [Some(1.0), Some(1.0)];
    let spec = WorldSpec {
        hoses: vec![HoseSpec {
            name: "h".into(),
            material: steel(0.0),
            nodes: vec![DVec3::ZERO, DVec3::X],
            sections: vec![section],
            normal_hint: None,
        }],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    };
    let err = Model::build(&spec).unwrap_err().to_string();
    assert!(err.contains("yielding material"), "{err}");
    let mut bad = spec.clone();
    bad.hoses[0].sections = vec![Section::new(DI, DO)];
    bad.hoses[0].material.plasticity = Some(YieldLaw {
        yield_stress: f64::NAN,
        hardening_modulus: 0.0,
    });
    let err = Model::build(&bad).unwrap_err().to_string();
    assert!(err.contains("yield stress"), "{err}");
}
