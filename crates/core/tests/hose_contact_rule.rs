//! Which pairs hose–hose contact considers (`SimSettings::hose_contact`).
//!
//! Two hoses drawn crossing through each other (a CAD route's bundles) are pushed apart
//! under `All`, left alone under `ApartAtRest` — while a third hose, drawn clear of them,
//! still presses on them when it is moved onto one; `Off` has no hose contact at all.

use glam::DVec3;
use pliant_core::contact::{hose_contact_forces, HoseContactRule, HoseContactScratch};
use pliant_core::{Model, SimSettings, WorldSpec};

use pliant_testkit::straight_hose1 as hose;

/// `a` along x, `b` along y crossing it 5 mm above (the 16 mm tubes overlap by 11 mm),
/// `c` parallel to `a` 40 mm above it (clear of both).
fn crossing(rule: HoseContactRule) -> Model {
    Model::build(&WorldSpec {
        hoses: vec![
            hose(
                "a",
                DVec3::new(-0.2, 0.0, 0.0),
                DVec3::new(0.2, 0.0, 0.0),
                10,
            ),
            hose(
                "b",
                DVec3::new(0.0, -0.2, 0.005),
                DVec3::new(0.0, 0.2, 0.005),
                10,
            ),
            hose(
                "c",
                DVec3::new(-0.2, 0.1, 0.04),
                DVec3::new(0.2, 0.1, 0.04),
                10,
            ),
        ],
        rigid_parts: vec![],
        settings: SimSettings {
            hose_contact: rule,
            ..Default::default()
        },
    })
    .unwrap()
}

/// Pairs in contact at `x`.
fn pairs(model: &Model, x: &[DVec3]) -> usize {
    let mut scratch = HoseContactScratch::new(model);
    let mut out = vec![DVec3::ZERO; x.len()];
    let v = vec![DVec3::ZERO; x.len()];
    hose_contact_forces(model, x, &v, &mut scratch, &mut out);
    scratch.pairs_in_contact
}

/// The rest positions with hose `c` lowered onto hose `a` (3 mm apart: the tubes overlap).
fn c_on_a(model: &Model) -> Vec<DVec3> {
    let mut x = model.rest_x.clone();
    let c = model.hoses[2].nodes();
    for p in &mut x[c] {
        *p = DVec3::new(p.x, 0.0, -0.003);
    }
    x
}

#[test]
fn all_pushes_apart_what_overlaps_at_rest() {
    let model = crossing(HoseContactRule::All);
    assert!(model.hose_contact.active);
    assert_eq!(model.hose_contact.overlapping_at_rest(), 0);
    assert!(pairs(&model, &model.rest_x) > 0);
}

#[test]
fn apart_at_rest_leaves_the_drawn_overlap_alone_and_keeps_every_other_contact() {
    let model = crossing(HoseContactRule::ApartAtRest);
    assert!(model.hose_contact.overlapping_at_rest() > 0);
    assert_eq!(
        pairs(&model, &model.rest_x),
        0,
        "the drawn crossing presses"
    );
    // c was drawn clear: lowered onto a it presses on a (and on b where it crosses it)
    assert!(pairs(&model, &c_on_a(&model)) > 0);
}

#[test]
fn off_has_no_hose_contact() {
    let model = crossing(HoseContactRule::Off);
    assert!(!model.hose_contact.active);
    assert_eq!(pairs(&model, &c_on_a(&model)), 0);
}

#[test]
fn rules_are_read_by_name_and_unknown_names_refused() {
    assert_eq!("apart_at_rest".parse(), Ok(HoseContactRule::ApartAtRest));
    assert_eq!("all".parse(), Ok(HoseContactRule::All));
    assert_eq!("off".parse(), Ok(HoseContactRule::Off));
    let err = "apart".parse::<HoseContactRule>().unwrap_err();
    assert!(err.contains("apart_at_rest"), "{err}");
}
