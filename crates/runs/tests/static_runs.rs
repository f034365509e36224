//! Static runs as a user makes them ("convergence is honest"): one default
//! setting of the static solver serves a 1 mm silicone tube carrying millinewtons and a
//! steel pipe carrying kilonewtons — each lands within 0.5 % of beam theory with every
//! solve converged — and a correct large-deflection solve of a soft, heavy hose is not
//! taken for a divergence (the static solver's displacement per input step is no speed).

use pliant_assembly::RunSummary;
use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;
use std::f64::consts::PI;

/// A cantilever of `length_mm` along +x, clamped at node 0, of a user material, under
/// gravity and an optional tip load, solved by the static solver.
fn cantilever(
    e_mpa: f64,
    density: f64,
    d_inner_mm: f64,
    d_outer_mm: f64,
    length_mm: f64,
    gravity: f64,
    tip_load_n: f64,
) -> (RunSummary, Vec<glam::DVec3>) {
    let scene = format!(
        r#"
format = "pliant-scene"
version = 1
name = "cantilever"
length_unit = "mm"

[simulation]
gravity = [0, 0, {gravity}]
solver = "static"

[materials.m]
e_tension_mpa = {e_mpa}
e_compression_mpa = {e_mpa}
e_bending_mpa = {e_mpa}
poisson = 0.3
density_kg_m3 = {density}

[[hoses]]
name = "c"
material = "m"
section = {{ d_inner = {d_inner_mm}, d_outer = {d_outer_mm} }}
start = [0, 0, 0]
path = [{{ line = {{ to = [{length_mm}, 0, 0] }} }}]
elements = 20

[[timeline]]
action = "fix"
hose = "c"
node = 0

[[timeline]]
action = "load"
hose = "c"
node = -1
force_n = [0, 0, {tip}]

[[timeline]]
action = "run"
duration_s = 0.05
"#,
        tip = -tip_load_n
    );
    let scene = load_scene_str_in(&scene, "cantilever.toml", std::path::Path::new(".")).unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, Some(SolverKind::Static)).unwrap();
    (run, cell.state().x.clone())
}

fn second_moment(d_inner: f64, d_outer: f64) -> f64 {
    PI / 64.0 * (d_outer.powi(4) - d_inner.powi(4))
}

#[test]
fn one_setting_serves_a_silicone_tube_and_a_steel_pipe() {
    // silicone tube 0.5/1 mm, 10 mm long, sagging under its own weight (~0.4 µN per node)
    let (e, rho, di, d, l) = (2.0e6, 1100.0, 0.5e-3, 1.0e-3, 0.01);
    let (run, x) = cantilever(e / 1e6, rho, di * 1e3, d * 1e3, l * 1e3, -9.81, 0.0);
    let w = rho * PI / 4.0 * (d * d - di * di) * 9.81;
    let exact = w * l.powi(4) / (8.0 * e * second_moment(di, d));
    assert!(exact / l < 0.02, "small deflection: {}", exact / l);
    let sag = -x[20].z;
    assert!(
        (sag / exact - 1.0).abs() < 0.005,
        "silicone sag {sag:e} m, beam theory {exact:e} m"
    );
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    // steel pipe 20/30 mm, 1 m long, 1 kN at the tip (and its weight, which is 4 % of it)
    let (e, rho, di, d, l, p) = (200.0e9, 7850.0, 0.02, 0.03, 1.0, 1000.0);
    let (run, x) = cantilever(e / 1e6, rho, di * 1e3, d * 1e3, l * 1e3, -9.81, p);
    let ei = e * second_moment(di, d);
    let w = rho * PI / 4.0 * (d * d - di * di) * 9.81;
    let exact = p * l.powi(3) / (3.0 * ei) + w * l.powi(4) / (8.0 * ei);
    let sag = -x[20].z;
    assert!(
        (sag / exact - 1.0).abs() < 0.005,
        "steel sag {sag:e} m, beam theory {exact:e} m"
    );
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
}

/// A soft, heavy hose (E = 0.02 MPa, ρ = 1000 kg/m³: wave speed √(E/ρ) ≈ 4.5 m/s) sags
/// by over 10 cm in its first 10 ms input step — faster "per step" than its wave speed,
/// which the explicit solver's divergence check would rightly call a blow-up (the static
/// solver's used to, and stopped the run). The static run completes, converged.
#[test]
fn a_large_static_sag_is_no_divergence() {
    let (e, rho) = (0.02e6, 1000.0);
    let (run, x) = cantilever(e / 1e6, rho, 10.0, 16.0, 300.0, -9.81, 0.0);
    let sag = -x[20].z;
    let (wave_speed, input_step) = ((e / rho).sqrt(), 0.01);
    assert!(
        sag / input_step > 1.5 * wave_speed,
        "the tip sagged only {sag} m"
    );
    assert!(run.steps >= 5, "{} steps", run.steps);
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    assert!(run.solver_warnings.is_empty());
}
