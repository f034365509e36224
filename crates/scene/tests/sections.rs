//! General sections in scene files (SPEC S3): stiffnesses given directly reach the
//! model's elements in SI, and spans give the elements whose middle they hold a section
//! of their own.

use pliant_core::Model;
use pliant_scene::load_scene_str;

const SCENE: &str = r#"
format = "pliant-scene"
version = 1
name = "sections"
length_unit = "mm"
[[hoses]]
name = "cable"
material = "hose1"
section = { d_inner = 0, d_outer = 16, ei1_n_m2 = 0.02, ei2_n_m2 = 0.2, gj_n_m2 = 0.01, ea_n = 5000, mass_kg_m = 0.3 }
elements = 8
start = [0, 0, 0]
path = [{ line = { to = [200, 0, 0] } }]
normal_hint = [0, 0, 1]
spans = [{ from = 50, to = 150, section = { d_inner = 0, d_outer = 24 } }]
"#;

#[test]
fn spans_and_given_stiffness_reach_the_elements() {
    let scene = load_scene_str(SCENE, "sections test").expect("scene loads");
    let hose = &scene.world.hoses[0];
    assert_eq!(hose.sections.len(), 8, "one section per element");
    // elements are 25 mm long; middles 62.5 … 137.5 mm lie in the span
    let thick: Vec<usize> = (0..8)
        .filter(|&e| hose.element_section(e).d_outer == 0.024)
        .collect();
    assert_eq!(thick, vec![2, 3, 4, 5]);
    // node 2 joins a thin and a thick element: clips and contact see the thick one
    assert_eq!(hose.node_section(2).d_outer, 0.024);
    assert_eq!(hose.node_section(1).d_outer, 0.016);

    let model = Model::build(&scene.world).expect("model builds");
    let ribbon = &model.elements[0];
    assert_eq!(ribbon.bending_stiffness, [0.02, 0.2]);
    assert_eq!(ribbon.torsion_stiffness, 0.01);
    assert_eq!(ribbon.axial_stiffness_tension, 5000.0);
    assert_eq!(ribbon.axial_stiffness_compression, 5000.0);
    // the span's solid rod takes the material's stiffness: E_b π d⁴/64
    let rod = &model.elements[3];
    let material = &hose.material;
    let i = std::f64::consts::PI * 0.024f64.powi(4) / 64.0;
    let expected = material.bending_modulus() * i;
    assert!((rod.bending_stiffness[0] / expected - 1.0).abs() < 1e-12);
    // 0.3 kg/m over the six thin-element halves at the first node's side: node 0 holds
    // half of element 0
    assert!((model.mass[0] - 0.3 * 0.025 / 2.0).abs() < 1e-15);
}

/// A protected stretch: its span's section and minimum bend radius reach the elements whose
/// middle it holds (and the bend-radius check's limits), its protections are kept in
/// metres as written.
#[test]
fn protections_and_span_bend_radii() {
    let text = SCENE.replace(
        "spans = [{ from = 50, to = 150, section = { d_inner = 0, d_outer = 24 } }]",
        "spans = [{ from = 50, to = 150, min_bend_radius = 60, section = { d_inner = 0, d_outer = 24 } }]\n\
         protections = [{ kind = \"tape\", from = 0, to = 200 }, { kind = \"corrugated_tube\", from = 50, to = 150 }]",
    );
    let scene = load_scene_str(&text, "protections test").expect("scene loads");
    let info = &scene.hoses[0];
    let kinds: Vec<(&str, f64, f64)> = info
        .protections
        .iter()
        .map(|p| (p.kind.key(), p.from, p.to))
        .collect();
    assert_eq!(
        kinds,
        vec![("tape", 0.0, 0.2), ("corrugated_tube", 0.05, 0.15)]
    );
    // elements 2 … 5 hold the span: its radius; the others the hose's (hose1's own)
    let hose_radius = info.min_bend_radius;
    assert!(hose_radius != 0.06);
    let expected: Vec<f64> = (0..8)
        .map(|e| {
            if (2..=5).contains(&e) {
                0.06
            } else {
                hose_radius
            }
        })
        .collect();
    assert_eq!(info.bend_radii, expected);
    let limits = &scene.checks.hoses[0];
    assert_eq!(limits.bend_radius_at(3), 0.06);
    assert_eq!(limits.bend_radius_at(0), hose_radius);
    // without span radii the hose's holds throughout, and nothing is stored per element
    let plain = load_scene_str(SCENE, "sections test").unwrap();
    assert!(plain.hoses[0].bend_radii.is_empty());
    assert!(plain.hoses[0].protections.is_empty());
    assert_eq!(
        plain.checks.hoses[0].bend_radius_at(3),
        plain.hoses[0].min_bend_radius
    );
}
