//! A metal line bent round a mandrel by contact (SPEC X1): a steel brake line (library
//! `steel_tube`) clamped tangent to a cylinder part, its end carried round the cylinder so
//! that the line wraps a quarter turn onto it, then let go. In the middle of the wrapped
//! arc it keeps the bend less a springback that is the elastic unloading of the moment
//! each element carries under load: κ_after = κ_loaded − M/EI element by element
//! (Lubliner 1990, "Plasticity Theory", §4.1; the line let go carries no moment).
//!
//! That moment is bounded by the closed-form M(κ_loaded) of a section bent monotonically
//! to the loaded curvature (`plastic_moment`) but not equal to it: the steel hardens
//! little (H/E = 0.0023), so a section bent a little past the mandrel's curvature where
//! the line leaves it, and pressed back onto it as the end goes on round, unloads
//! elastically by EI·Δκ — 1 % of overshoot (0.3 1/m) takes 1.2 N·m of the 2.2 N·m.
//! Measured, the sections carry 0.71–0.81 of M(κ) (0.42–0.74 before the static solver's
//! predictor obeyed the contact step limit): the fraction follows the solver's path. The mandrel is a 256-sided prism (facets 0.74 mm,
//! shorter than the line's 1.35 mm elements, its circle's sagitta 2.3 µm) wrapped in 1°
//! steps: on a 64-sided one (facets 2.9 mm) wrapped in 10° steps the line lies in a
//! zigzag of plastic hinges at the prism's vertices (element curvatures 21–41 1/m), snaps
//! between steps, and the moments it carries change sign with small changes of the
//! solver's path.

use pliant_assembly::Workcell;
use pliant_core::rod::plastic_moment::hardening_bending_moment;
use pliant_core::rod::section_loads::{section_loads, SectionLoads};
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{action, run_for, SceneText};
use pliant_testkit::scenes::{ELASTIC_STEEL, WEIGHTLESS_MM};
use std::f64::consts::PI;

const R_OUTER: f64 = 2.375e-3;
const R_INNER: f64 = 1.675e-3;
const MANDREL_RADIUS_MM: f64 = 30.0;
const E: f64 = 210e9;
const SY: f64 = 170e6;
const H: f64 = 480e6;
const LEAD_MM: f64 = 10.0;
const TAIL_MM: f64 = 30.0;
const ELEMENTS: usize = 60;
const WRAP_STEPS: usize = 90;
/// Sides of the mandrel's prism.
const SIDES: usize = 256;

fn centre_radius_mm() -> f64 {
    MANDREL_RADIUS_MM + R_OUTER * 1e3
}

fn free_length_mm() -> f64 {
    0.5 * PI * centre_radius_mm() + TAIL_MM
}

/// The scene: the line along +x touching the top of the mandrel (axis along y, below the
/// line) at x = 0, clamped `LEAD_MM` before it; its end carried round in `WRAP_STEPS` moves,
/// each to where a line wrapped a further 90°/`WRAP_STEPS` onto the mandrel with a straight
/// tail has its end (the involute of the circle), turned with it. `release` adds the end's
/// release and a short run.
fn scene(material: &str, extra: &str, segments: usize, release: bool) -> String {
    let r = centre_radius_mm();
    let l = free_length_mm();
    let mut text = format!(
        r#"{WEIGHTLESS_MM}solver = "static"
{extra}
[[parts]]
name = "mandrel"
cylinder = {{ radius = {MANDREL_RADIUS_MM}, height = 30, segments = {segments} }}
position = [0, 0, {z}]
rotation = {{ axis = [1, 0, 0], angle_deg = 90 }}

[[hoses]]
name = "line"
material = "{material}"
section = {{ d_inner = 3.35, d_outer = 4.75 }}
elements = {ELEMENTS}
start = [{x0}, 0, 0]
path = [{{ line = {{ to = [{l}, 0, 0] }} }}]

[[timeline]]
action = "fix"
hose = "line"
node = 0
"#,
        z = -r,
        x0 = -LEAD_MM,
    );
    let step = 0.5 * PI / WRAP_STEPS as f64;
    for k in 1..=WRAP_STEPS {
        let theta = step * k as f64;
        let tail = l - r * theta;
        let x = r * theta.sin() + tail * theta.cos();
        let z = -r + r * theta.cos() - tail * theta.sin();
        text.push_str(&format!(
            r#"
[[timeline]]
action = "move"
hose = "line"
node = -1
to = [{x}, 0, {z}]
rotate = {{ axis = [0, 1, 0], angle_deg = {a} }}
duration_s = {d}
"#,
            a = step.to_degrees(),
            d = 0.9 / WRAP_STEPS as f64
        ));
    }
    if release {
        let end = SceneText::piece()
            .with(action("release").text("hose", "line").number("node", -1.0))
            .with(run_for(0.05));
        text.push_str(&String::from(end));
    }
    text
}

fn run(text: &str) -> Workcell {
    let scene = load_scene_str(text, "mandrel.toml").unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, None).unwrap();
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    cell
}

/// What every element's section carries in `cell`'s state.
fn sections(cell: &Workcell) -> Vec<SectionLoads> {
    let model = cell.model();
    (0..model.elements.len())
        .map(|e| section_loads(model, cell.state(), e))
        .collect()
}

/// Mean curvature \[1/m\] of the centre line between nodes `a` and `b`: the turn of the
/// element chord from the element starting at `a` to the one ending at `b`, over the
/// distance between those chords' midpoints.
fn mean_curvature(x: &[glam::DVec3], a: usize, b: usize) -> f64 {
    let t0 = (x[a + 1] - x[a]).normalize();
    let t1 = (x[b] - x[b - 1]).normalize();
    let angle = t0.angle_between(t1);
    let s: f64 = (a..b).map(|i| (x[i + 1] - x[i]).length()).sum::<f64>()
        - 0.5 * (x[a + 1] - x[a]).length()
        - 0.5 * (x[b] - x[b - 1]).length();
    angle / s
}

/// Nodes bounding the middle half of the wrapped arc.
fn middle_of_arc() -> (usize, usize) {
    let h = (free_length_mm() + LEAD_MM) / ELEMENTS as f64;
    let arc = 0.5 * PI * centre_radius_mm();
    let node = |s: f64| ((LEAD_MM + s) / h).round() as usize;
    (node(0.25 * arc), node(0.75 * arc))
}

#[test]
fn a_steel_line_wrapped_round_a_mandrel_springs_back_by_the_moment_it_carries() {
    let loaded = std::thread::spawn(|| run(&scene("steel_tube", "", SIDES, false)));
    let after = run(&scene("steel_tube", "", SIDES, true));
    let loaded = loaded.join().unwrap();
    let (a, b) = middle_of_arc();
    let k_loaded = mean_curvature(&loaded.state().x, a, b);
    let k_after = mean_curvature(&after.state().x, a, b);
    let k_mandrel = 1e3 / centre_radius_mm();
    let ei = E * PI / 4.0 * (R_OUTER.powi(4) - R_INNER.powi(4));
    let monotonic = hardening_bending_moment(R_INNER, R_OUTER, E, SY, H, k_loaded) / ei;
    println!(
        "mandrel 1/R {k_mandrel:.4}, loaded {k_loaded:.4}, kept {k_after:.4} 1/m: \
         springback {:.4} against M(k)/EI {monotonic:.4}",
        k_loaded - k_after
    );
    // wrapped onto the mandrel by contact: the prism's facets and the contact's
    // penetration leave the loaded curvature within 0.5 % of the centre line's circle
    // (0.10–0.15 % measured)
    assert!(
        (k_loaded - k_mandrel).abs() < 0.005 * k_mandrel,
        "loaded {k_loaded} 1/m against 1/R = {k_mandrel} 1/m"
    );
    // element by element over the arc's middle half (the curvature the law reads, bent
    // about the mandrel's axis y): let go, each element springs back by the moment it
    // carried, M/EI — an elastic unloading, exact but for the solves' round-off (10⁻¹³
    // 1/m measured; 10⁻⁹ of a springback of ~0.3 1/m allowed) — and that moment is
    // between zero and M(κ) of the curvature it was loaded to
    let (before, kept) = (sections(&loaded), sections(&after));
    let (mut worst, mut carried, mut sprung, mut length) = (0.0_f64, 0.0, 0.0, 0.0);
    let l0 = loaded.model().elements[a].axis_length;
    for e in a..b {
        let (k, m) = (before[e].curvature.y, before[e].bending_moment.y);
        let springback = k - kept[e].curvature.y;
        let m_k = hardening_bending_moment(R_INNER, R_OUTER, E, SY, H, k);
        println!(
            "element {e}: loaded κ {k:.4} 1/m carrying M {m:.4} N·m (M(κ) {m_k:.4}); \
             springback {springback:.5} against M/EI {:.5} 1/m; moment let go {:.2e} N·m",
            m / ei,
            kept[e].bending_moment.length()
        );
        worst = worst.max((springback - m / ei).abs());
        // bent the mandrel's way, at most as far as the monotonic curve allows: no
        // section unloaded past zero
        assert!(
            m > 0.0 && m < m_k,
            "element {e}: M {m} N·m against M(κ) {m_k} N·m"
        );
        carried += m / ei * l0;
        sprung += springback * l0;
        length += l0;
    }
    println!(
        "arc middle: springback {:.4} 1/m against the mean M/EI carried {:.4} 1/m; \
         worst element |springback − M/EI| {worst:.2e} 1/m",
        sprung / length,
        carried / length
    );
    assert!(
        worst < 2e-3,
        "an element sprang back {worst} 1/m off its M/EI"
    );
    // so the arc springs back, by less than the monotonic curve's M(κ)/EI
    assert!(carried / length < monotonic);
    assert!(k_loaded - k_after > 0.0 && k_loaded - k_after < monotonic);
}

#[test]
fn an_elastic_line_wrapped_round_the_mandrel_springs_straight() {
    let after = run(&scene("elastic_steel", ELASTIC_STEEL, SIDES, true));
    let (a, b) = middle_of_arc();
    let k_after = mean_curvature(&after.state().x, a, b);
    assert!(k_after.abs() < 0.5, "the elastic line keeps {k_after} 1/m");
}
