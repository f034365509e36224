//! Metal lines keep the shape they are bent to: a 200 mm steel brake line (library
//! `steel_tube`, yielding) bent by its end into a quarter circle of radius 127 mm — an outer
//! fibre strain of 1.9 %, 23 times the yield strain — and let go keeps nearly all of the
//! bend; the same line with the same elastic data but no yield stress springs straight.

use pliant_scene::load_scene_str;
use pliant_testkit::scenes::{ELASTIC_STEEL, WEIGHTLESS_MM};

/// The line fixed at its start, its end moved onto the quarter circle and turned with it,
/// then released; `material` names the line's material, `extra` goes before the hoses.
fn scene(material: &str, extra: &str) -> String {
    format!(
        r#"{WEIGHTLESS_MM}solver = "static"
{extra}
[[hoses]]
name = "line"
material = "{material}"
section = {{ d_inner = 3.35, d_outer = 4.75 }}
elements = 20
start = [0, 0, 0]
path = [{{ line = {{ to = [200, 0, 0] }} }}]

[[timeline]]
action = "fix"
hose = "line"
node = 0

[[timeline]]
action = "move"
hose = "line"
node = -1
by = [-72.676, 0, 127.324]
rotate = {{ axis = [0, -1, 0], angle_deg = 90 }}
duration_s = 2

[[timeline]]
action = "release"
hose = "line"
node = -1

[[timeline]]
action = "run"
duration_s = 0.2
"#
    )
}

/// The end's height after the release \[m\].
fn end_height(text: &str) -> f64 {
    let scene = load_scene_str(text, "line.toml").unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, None).unwrap();
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    let x = &cell.state().x;
    x[x.len() - 1].z
}

#[test]
fn a_steel_line_bent_by_hand_keeps_its_bend_and_an_elastic_one_springs_back() {
    let kept = end_height(&scene("steel_tube", ""));
    // bent to 127 mm; springback 1/R_after = 1/R − M/EI takes off a few per cent at most
    assert!(
        kept > 0.110 && kept < 0.1274,
        "the steel line's end at z = {kept} m"
    );
    let back = end_height(&scene("elastic_steel", ELASTIC_STEEL));
    assert!(back.abs() < 1e-3, "the elastic line's end at z = {back} m");
}
