//! Each validation case as a test: every check of the case must pass.

fn assert_case(name: &str) {
    let checks = pliant_validation::run(Some(name)).expect("case exists");
    assert!(!checks.is_empty());
    for c in &checks {
        println!(
            "{}: {} computed {:.6e} reference {:.6e} error {:.3e} tol {:.1e}",
            c.case, c.quantity, c.computed, c.reference, c.error, c.tolerance
        );
    }
    let failed: Vec<_> = checks.iter().filter(|c| !c.pass).collect();
    assert!(failed.is_empty(), "failed checks: {failed:#?}");
}

#[test]
fn rollup() {
    assert_case("rollup");
}
#[test]
fn tip_load() {
    assert_case("tip_load");
}
#[test]
fn buckling() {
    assert_case("buckling");
}
#[test]
fn postbuckling() {
    assert_case("postbuckling");
}
#[test]
fn axial() {
    assert_case("axial");
}
#[test]
fn torsion() {
    assert_case("torsion");
}
#[test]
fn invariance() {
    assert_case("invariance");
}
#[test]
fn energy() {
    assert_case("energy");
}
#[test]
fn convergence() {
    assert_case("convergence");
}
#[test]
fn thesis_1() {
    assert_case("thesis_1");
}
#[test]
fn thesis_2() {
    assert_case("thesis_2");
}
#[test]
fn thesis_3() {
    assert_case("thesis_3");
}
#[test]
fn thesis_4() {
    assert_case("thesis_4");
}
#[test]
fn contact_rest() {
    assert_case("contact_rest");
}
#[test]
fn contact_incline() {
    assert_case("contact_incline");
}
#[test]
fn friction_newton() {
    assert_case("friction_newton");
}
#[test]
fn tunnelling() {
    assert_case("tunnelling");
}
#[test]
fn stub() {
    assert_case("stub");
}
#[test]
fn clip() {
    assert_case("clip");
}
#[test]
fn stiffened() {
    assert_case("stiffened");
}

#[test]
fn scale() {
    assert_case("scale");
}

#[test]
fn helix() {
    assert_case("helix");
}

#[test]
fn large_frames() {
    assert_case("large_frames");
}
#[test]
fn junction_body() {
    assert_case("junction_body");
}
#[test]
fn junction_body_torsion() {
    assert_case("junction_body_torsion");
}
#[test]
fn junction_shape_rest() {
    assert_case("junction_shape_rest");
}
#[test]
fn junction_shape_impact() {
    assert_case("junction_shape_impact");
}
#[test]
fn mass_scaling() {
    assert_case("mass_scaling");
}
#[test]
fn curved_reactions() {
    assert_case("curved_reactions");
}
#[test]
fn sections() {
    assert_case("sections");
}
#[test]
fn hose_contact() {
    assert_case("hose_contact");
}
#[test]
fn solvers() {
    assert_case("solvers");
}

#[test]
fn plastic_section() {
    assert_case("plastic_section");
}
#[test]
fn springback() {
    assert_case("springback");
}
#[test]
fn relaxing_bar() {
    assert_case("relaxing_bar");
}
#[test]
fn relaxing_beam() {
    assert_case("relaxing_beam");
}
#[test]
fn moving_carry() {
    assert_case("moving_carry");
}
#[test]
fn moving_lift() {
    assert_case("moving_lift");
}
#[test]
fn moving_drag() {
    assert_case("moving_drag");
}
#[test]
fn moving_hinge() {
    assert_case("moving_hinge");
}
#[test]
fn moving_fast() {
    assert_case("moving_fast");
}
