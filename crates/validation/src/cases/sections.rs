//! `sections`: general cross-sections (SPEC S3), written in a scene file and loaded by
//! the scene loader as a user's would be.
//!
//! * A ribbon — EI₂ = 10 EI₁, given directly — bends under small tip loads along each
//!   section axis by PL³/3EI with that axis' stiffness (Euler–Bernoulli, exact).
//! * The same ribbon under a large oblique tip load (λ = PL²/EI₁ = 3, along both axes at
//!   once) bends and twists out of the load's plane; its tip matches the independent
//!   Cosserat shooting solver (`pliant_reference`, with EI₂ ≠ EI₃) run on the same rod.
//! * A stepped cantilever — the inner half ten times as stiff, a span of its own — bends
//!   under a small tip load by δ = P[(L³ − (L−a)³)/3EI_a + (L−a)³/3EI_b] (integrating
//!   M(s)(L−s)/EI(s)).

use crate::harness::{clamp, dead_load, settle_to};
use crate::reference_bridge::{solver_for, to_glam, to_na};
use crate::Check;
use glam::DVec3;
use pliant_core::{Model, State};
use pliant_reference::EndCondition;

const L: f64 = 1.0;
const ELEMENTS: usize = 40;
/// The ribbon's stiffnesses about section axis 1 (the hose's `normal_hint`, world y) and
/// axis 2 (world z) \[N·m²\].
const EI1: f64 = 0.02;
const EI2: f64 = 0.2;
/// Small-load ratio PL²/EI for the linear checks: the geometric non-linearity is of
/// order λ² ≈ 1e-6.
const LINEAR_LAMBDA: f64 = 1e-3;
/// Linear checks: the cubic element reproduces the linear cantilever exactly at nodes,
/// so only the non-linearity and the rest tolerance remain.
const LINEAR_TOLERANCE: f64 = 1e-4;
/// Large oblique load ratio PL²/EI₁ and its tolerance on the tip position (fraction of
/// L): 0.1 % with 40 elements (SPEC S4).
const OBLIQUE_LAMBDA: f64 = 3.0;
const OBLIQUE_TOLERANCE: f64 = 1e-3;
/// The stepped cantilever: inner span [0, a) with EI_a, the rest with EI_b.
const STEP_AT: f64 = 0.5;
const EI_INNER: f64 = 0.5;
const EI_OUTER: f64 = 0.05;

/// A straight 1 m hose along +x, clamped at x = 0, `elements` long, with the given TOML
/// for its `section` and `spans`, in a scene without gravity.
fn scene(section: &str, spans: &str) -> Result<Model, String> {
    let text = format!(
        r#"
format = "pliant-scene"
version = 1
name = "section validation"
length_unit = "m"
[simulation]
gravity = [0, 0, 0]
damping_mass_per_s = 0
[[hoses]]
name = "ribbon"
material = "hose1"
section = {section}
elements = {ELEMENTS}
start = [0, 0, 0]
path = [{{ line = {{ to = [{L}, 0, 0] }} }}]
normal_hint = [0, 1, 0]
{spans}
"#
    );
    let scene =
        pliant_scene::load_scene_str(&text, "sections validation").map_err(|e| e.to_string())?;
    Model::build(&scene.world).map_err(|e| e.to_string())
}

fn ribbon() -> Result<Model, String> {
    scene(
        &format!("{{ d_inner = 0.010, d_outer = 0.016, ei1_n_m2 = {EI1}, ei2_n_m2 = {EI2} }}"),
        "",
    )
}

/// Tip position of a clamped cantilever under a dead tip force, reached in `steps`
/// equal load increments, each to rest within `rel` of the load.
fn tip_under(model: &Model, force: DVec3, steps: usize, rel: f64) -> Result<DVec3, String> {
    let tip = model.hoses[0].node_count - 1;
    let mut state = State::at_rest(model);
    clamp(&mut state, 0);
    let mut id = None;
    for k in 1..=steps {
        if let Some(old) = id {
            state.loads.remove(old);
        }
        id = Some(state.loads.add(dead_load(
            tip,
            force * (k as f64 / steps as f64),
            DVec3::ZERO,
        )));
        settle_to(model, &mut state, force.length(), L, rel)?;
    }
    Ok(state.x[tip])
}

fn linear_ribbon(out: &mut Vec<Check>) -> Result<(), String> {
    let model = ribbon()?;
    // a load along y bends about section axis 2 (z), one along z about axis 1 (y)
    for (axis, direction, ei) in [("y", DVec3::Y, EI2), ("z", DVec3::Z, EI1)] {
        let p = LINEAR_LAMBDA * ei / (L * L);
        let tip = tip_under(&model, direction * p, 1, 1e-6)?;
        out.push(Check::relative(
            "sections",
            &format!("ribbon tip deflection along {axis} / (PL³/3EI)"),
            tip.dot(direction) / (p * L.powi(3) / (3.0 * ei)),
            1.0,
            LINEAR_TOLERANCE,
        ));
    }
    Ok(())
}

fn oblique_ribbon(out: &mut Vec<Check>) -> Result<(), String> {
    let model = ribbon()?;
    let p = OBLIQUE_LAMBDA * EI1 / (L * L);
    let force = DVec3::new(0.0, 1.0, 1.0).normalize() * p;
    let tip = tip_under(&model, force, 6, 1e-9)?;
    let solver = solver_for(&model, 0)?;
    let targets: Vec<EndCondition> = (1..=6)
        .map(|k| EndCondition::loaded(to_na(force * (k as f64 / 6.0)), to_na(DVec3::ZERO)))
        .collect();
    let solutions = solver
        .solve_path(&targets)
        .map_err(|e| format!("reference solver: {e}"))?;
    let reference = to_glam(&solutions[solutions.len() - 1].end_state().position);
    // the load's plane is y = z; the ribbon's tip leaves it (a round rod's would not)
    eprintln!("sections: oblique ribbon tip {tip:?}, reference {reference:?}");
    for (name, k) in [("x", 0), ("y", 1), ("z", 2)] {
        out.push(Check::scaled(
            "sections",
            &format!("oblique ribbon tip {name}/L vs reference"),
            tip[k] / L,
            reference[k] / L,
            1.0,
            OBLIQUE_TOLERANCE,
        ));
    }
    Ok(())
}

fn stepped(out: &mut Vec<Check>) -> Result<(), String> {
    let section = |ei: f64| {
        format!("{{ d_inner = 0.010, d_outer = 0.016, ei1_n_m2 = {ei}, ei2_n_m2 = {ei} }}")
    };
    let model = scene(
        &section(EI_OUTER),
        &format!(
            "spans = [{{ from = 0, to = {STEP_AT}, section = {} }}]",
            section(EI_INNER)
        ),
    )?;
    let p = LINEAR_LAMBDA * EI_OUTER / (L * L);
    let tip = tip_under(&model, DVec3::Y * p, 1, 1e-6)?;
    let rest = L - STEP_AT;
    let exact =
        p * ((L.powi(3) - rest.powi(3)) / (3.0 * EI_INNER) + rest.powi(3) / (3.0 * EI_OUTER));
    out.push(Check::relative(
        "sections",
        "stepped cantilever tip deflection / exact",
        tip.y / exact,
        1.0,
        LINEAR_TOLERANCE,
    ));
    Ok(())
}

pub fn run() -> Vec<Check> {
    let mut out = Vec::new();
    for (name, part) in [
        (
            "ribbon, small loads",
            linear_ribbon as fn(&mut Vec<Check>) -> Result<(), String>,
        ),
        ("ribbon, oblique load", oblique_ribbon),
        ("stepped cantilever", stepped),
    ] {
        if let Err(e) = part(&mut out) {
            out.push(Check::failed("sections", name, &e));
        }
    }
    out
}
