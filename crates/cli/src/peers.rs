//! `pliant peer …`: Pliant's side of the head-to-head benchmarks against PyElastica and
//! MuJoCo (`bench/peers/`). Each subcommand solves one problem once and
//! prints one JSON object on stdout; `bench/peers/run.py` sweeps the resolution and the
//! tolerances and compares with the peers.
//!
//! - `pliant peer params`: the shared problem data (library hose 1, geometry, loads,
//!   damping rules), so that every tool is fed the same numbers.
//! - `pliant peer cantilever --elements N --solver S --tol EPS`: cantilever of length 1 m
//!   under a dead tip load λ = PL²/EI (default 2), gravity off; tip w/L and −u/L.
//! - `pliant peer drop --elements N`: a 500 mm hose dropped onto a horizontal cylinder
//!   under gravity; simulated time to rest and wall time to get there.
//!
//! Wall times cover the solve only (loads applied → converged), not building the model.

use anyhow::{bail, Result};
use glam::{DQuat, DVec3};
use pliant_core::integrators::StaticSolver;
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::relax::{relax, RelaxOptions};
use pliant_core::{
    health, integrators::explicit, HoseSpec, Material, Model, RigidPartSpec, Section, SimSettings,
    State, WorldSpec,
};
use serde::Serialize;
use std::time::Instant;

/// How Pliant reaches the static answer of the cantilever. Add a variant per new solver
/// and one arm in [`solve_cantilever`]; `run.py` passes the name given by `--solver`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Explicit central differences with kinetic damping (dynamic relaxation,
    /// `pliant_core::relax`), stopped when the out-of-balance force on every free node is
    /// below tol·P (moment below tol·P·L).
    Relax,
    /// Explicit central differences with viscous mass damping at the critical value of
    /// the first cantilever mode (α = 2ω₁), run until every node is slower than
    /// tol·L·ω₁ — the same "damped dynamics to rest" the peers use.
    Damped,
    /// Quasi-static Newton solver (`pliant_core::integrators::StaticSolver`): one solve.
    Static,
    /// Implicit HHT-α dynamics (`pliant_core::integrators::ImplicitSolver`); not offered for
    /// the static cantilever.
    Implicit,
}

/// Length of the cantilever \[m\].
pub const CANTILEVER_LENGTH: f64 = 1.0;
/// Hose length of the drop \[m\], cylinder radius \[m\] and the gap between the hose's
/// underside and the top of the cylinder at release \[m\].
pub const DROP_LENGTH: f64 = 0.5;
pub const CYLINDER_RADIUS: f64 = 0.05;
pub const DROP_GAP: f64 = 0.01;
/// Mass-proportional damping of the drop \[1/s\] (ζ ≈ 0.1 for the first mode of a 250 mm
/// arm) and the friction coefficient hose–cylinder, used by every tool.
pub const DROP_DAMPING: f64 = 8.0;
pub const DROP_FRICTION: f64 = 0.5;
/// Rest: translational kinetic energy below this \[J\] …
pub const REST_ENERGY: f64 = 1e-6;
/// … for this long of simulated time \[s\].
pub const REST_WINDOW: f64 = 0.2;
/// Give up after this much simulated time \[s\].
pub const DROP_MAX_TIME: f64 = 10.0;
/// Sampling interval of the rest test \[s\].
pub const DROP_SAMPLE: f64 = 1e-3;

fn hose1() -> Result<(Material, Section)> {
    let library = pliant_scene::Library::builtin()?;
    let Some(entry) = library.get("hose1") else {
        bail!("library hose 'hose1' missing");
    };
    Ok((entry.material.clone(), entry.section))
}

/// Problem data shared with the peer scripts.
#[derive(Serialize)]
pub struct Params {
    pub material: &'static str,
    pub d_inner_m: f64,
    pub d_outer_m: f64,
    pub area_m2: f64,
    pub second_moment_m4: f64,
    pub polar_moment_m4: f64,
    pub density_kg_m3: f64,
    pub e_tension_pa: f64,
    pub e_compression_pa: f64,
    pub e_bending_pa: f64,
    pub shear_modulus_pa: f64,
    pub poisson: f64,
    pub ei_n_m2: f64,
    pub mass_per_length_kg_m: f64,
    pub cantilever_length_m: f64,
    /// First bending eigenfrequency of the cantilever ω₁ = 1.8751² √(EI/(ρA L⁴)) \[rad/s\].
    pub cantilever_omega1: f64,
    pub drop_length_m: f64,
    pub cylinder_radius_m: f64,
    pub drop_gap_m: f64,
    pub drop_damping_per_s: f64,
    pub drop_friction: f64,
    pub drop_gravity_m_s2: f64,
    /// First mode of a 250 mm cantilever arm (the damping rule's reference) \[rad/s\].
    pub drop_arm_omega1: f64,
    pub rest_energy_j: f64,
    pub rest_window_s: f64,
    pub drop_max_time_s: f64,
    pub drop_sample_s: f64,
}

fn omega1(ei: f64, rho_a: f64, len: f64) -> f64 {
    1.875_104_068_711_961_f64.powi(2) * (ei / (rho_a * len.powi(4))).sqrt()
}

pub fn params() -> Result<Params> {
    let (m, s) = hose1()?;
    let ei = m.bending_modulus() * s.second_moment();
    let rho_a = m.density * s.area();
    Ok(Params {
        material: "hose1",
        d_inner_m: s.d_inner,
        d_outer_m: s.d_outer,
        area_m2: s.area(),
        second_moment_m4: s.second_moment(),
        polar_moment_m4: s.polar_moment(),
        density_kg_m3: m.density,
        e_tension_pa: m.e_tension,
        e_compression_pa: m.e_compression,
        e_bending_pa: m.bending_modulus(),
        shear_modulus_pa: m.shear_modulus(),
        poisson: m.poisson,
        ei_n_m2: ei,
        mass_per_length_kg_m: rho_a,
        cantilever_length_m: CANTILEVER_LENGTH,
        cantilever_omega1: omega1(ei, rho_a, CANTILEVER_LENGTH),
        drop_length_m: DROP_LENGTH,
        cylinder_radius_m: CYLINDER_RADIUS,
        drop_gap_m: DROP_GAP,
        drop_damping_per_s: DROP_DAMPING,
        drop_friction: DROP_FRICTION,
        drop_gravity_m_s2: 9.81,
        drop_arm_omega1: omega1(ei, rho_a, 0.5 * DROP_LENGTH),
        rest_energy_j: REST_ENERGY,
        rest_window_s: REST_WINDOW,
        drop_max_time_s: DROP_MAX_TIME,
        drop_sample_s: DROP_SAMPLE,
    })
}

/// One cantilever solve.
#[derive(Serialize)]
pub struct CantileverResult {
    pub tool: &'static str,
    pub solver: Method,
    pub elements: usize,
    pub lambda: f64,
    pub tol: f64,
    pub converged: bool,
    /// Tip deflection normal to the axis and shortening, over L.
    pub w_over_l: f64,
    pub u_over_l: f64,
    pub steps: u64,
    pub time_step_s: f64,
    pub simulated_s: f64,
    /// Wall time of the solve (loads applied → converged) \[s\].
    pub wall_s: f64,
    pub note: String,
}

fn straight(n: usize, len: f64, origin: DVec3, m: &Material, s: Section) -> HoseSpec {
    HoseSpec {
        name: "hose".into(),
        material: m.clone(),
        nodes: (0..=n)
            .map(|i| origin + DVec3::new(len * i as f64 / n as f64, 0.0, 0.0))
            .collect(),
        sections: vec![s],
        normal_hint: Some(DVec3::Y),
    }
}

fn fix(state: &mut State, i: usize) {
    state.loads.add(LoadCase::Fix(Fix {
        node: i,
        position: state.x[i],
        orientation: state.q[i],
    }));
}

fn max_speed(state: &State) -> f64 {
    state
        .v
        .iter()
        .zip(&state.held)
        .filter(|(_, h)| !**h)
        .map(|(v, _)| v.length())
        .fold(0.0, f64::max)
}

/// Solves the cantilever with `solver`.
pub fn solve_cantilever(
    elements: usize,
    solver: Method,
    lambda: f64,
    tol: f64,
) -> Result<CantileverResult> {
    if elements < 1 {
        bail!("--elements must be at least 1");
    }
    let (mat, sec) = hose1()?;
    let len = CANTILEVER_LENGTH;
    let ei = mat.bending_modulus() * sec.second_moment();
    let w1 = omega1(ei, mat.density * sec.area(), len);
    let settings = match solver {
        // as the validation suite's static settings: kinetic damping only, default β
        Method::Relax | Method::Static => SimSettings {
            gravity: DVec3::ZERO,
            damping_mass: 0.0,
            damping_stiffness: None,
            ..Default::default()
        },
        Method::Damped => SimSettings {
            gravity: DVec3::ZERO,
            damping_mass: 2.0 * w1,
            damping_stiffness: None,
            ..Default::default()
        },
        Method::Implicit => {
            bail!("the cantilever is a static problem: use --solver static (Newton) or relax")
        }
    };
    let model = Model::build(&WorldSpec {
        hoses: vec![straight(elements, len, DVec3::ZERO, &mat, sec)],
        rigid_parts: Vec::new(),
        settings,
    })?;
    let mut state = State::at_rest(&model);
    fix(&mut state, 0);
    let p = lambda * ei / (len * len);
    let start = Instant::now();
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node: elements,
        force: DVec3::new(0.0, -p, 0.0),
        moment: DVec3::ZERO,
        ramp: None,
    }));
    let max_steps: u64 = 200_000_000;
    let (converged, steps, note) = match solver {
        Method::Relax => {
            let r = relax(
                &model,
                &mut state,
                &RelaxOptions {
                    force_tolerance: tol * p,
                    moment_tolerance: tol * p * len,
                    max_steps,
                    kinetic_damping: true,
                },
            )?;
            (
                r.converged,
                r.steps,
                format!(
                    "kinetic damping; residual {:.2e} N (stop at tol*P = {:.2e} N)",
                    r.residual_force,
                    tol * p
                ),
            )
        }
        Method::Damped => {
            let v_stop = tol * len * w1;
            let mut steps = 0u64;
            let mut done = false;
            while steps < max_steps {
                explicit::step(&model, &mut state);
                steps += 1;
                if steps % 64 == 0 {
                    health::check(&model, &state)?;
                    if max_speed(&state) < v_stop {
                        done = true;
                        break;
                    }
                }
            }
            (
                done,
                steps,
                format!(
                    "mass damping alpha = 2*omega1 = {:.3} 1/s; stop when max speed < tol*L*omega1 = {:.2e} m/s",
                    2.0 * w1,
                    v_stop
                ),
            )
        }
        Method::Static => {
            // one Newton solve from the straight rest shape (consistent tangent by AD,
            // O(N) block-tridiagonal solve, energy line search); buffers included in the time
            let mut solver = StaticSolver::new(&model)?;
            solver.options.tolerance =
                pliant_core::newton::Tolerance::absolute(tol * p, tol * p * len);
            solver.options.max_iterations = 200;
            let r = solver.solve(&model, &mut state)?;
            (
                r.converged,
                r.iterations as u64,
                format!(
                    "quasi-static Newton: {} iterations, residual {:.2e} N (stop at tol*P = {:.2e} N)",
                    r.iterations,
                    r.residual_force,
                    tol * p
                ),
            )
        }
        Method::Implicit => unreachable!("refused above"),
    };
    let wall_s = start.elapsed().as_secs_f64();
    let tip = state.x[elements];
    Ok(CantileverResult {
        tool: "pliant",
        solver,
        elements,
        lambda,
        tol,
        converged,
        w_over_l: -tip.y / len,
        u_over_l: (len - tip.x) / len,
        steps,
        time_step_s: model.time_step,
        simulated_s: state.time,
        wall_s,
        note,
    })
}

/// One drop run.
#[derive(Serialize)]
pub struct DropResult {
    pub tool: &'static str,
    pub elements: usize,
    pub at_rest: bool,
    /// Simulated time at which the kinetic energy fell below the threshold for good \[s\].
    pub rest_time_s: f64,
    /// Simulated time run (rest time + the rest window) \[s\].
    pub simulated_s: f64,
    /// Wall time of the run up to `simulated_s` \[s\].
    pub wall_s: f64,
    pub time_step_s: f64,
    pub steps: u64,
    /// Final shape: height of the hose ends and the middle above the cylinder axis \[m\],
    /// and the horizontal half-span between the ends \[m\].
    pub tip_z_m: f64,
    pub mid_z_m: f64,
    pub half_span_m: f64,
    /// Centre line, every node, at rest (x, z) \[m\].
    pub shape_xz: Vec<[f64; 2]>,
    pub note: String,
}

/// The horizontal cylinder (axis along y through the origin) as a fine prism whose flat
/// faces touch the true circle's radius at their middles (error ≤ R (1/cos(π/n) − 1)).
fn cylinder(radius: f64, length: f64, segments: u32) -> RigidPartSpec {
    let r = radius / (std::f64::consts::PI / segments as f64).cos();
    let mesh = pliant_scene::mesh::cylinder_mesh(r, length, segments);
    // the mesh's axis is z; turn it onto y
    let turn = DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2);
    RigidPartSpec {
        name: "cylinder".into(),
        vertices: mesh.vertices.iter().map(|v| turn * *v).collect(),
        triangles: mesh.triangles,
        friction_static: DROP_FRICTION,
        friction_sliding: DROP_FRICTION,
        motion: None,
        parent: None,
        movable: false,
    }
}

fn translational_energy(model: &Model, state: &State) -> f64 {
    state
        .v
        .iter()
        .zip(&model.mass)
        .map(|(v, m)| 0.5 * m * v.length_squared())
        .sum()
}

pub fn drop(elements: usize) -> Result<DropResult> {
    if elements < 2 {
        bail!("--elements must be at least 2");
    }
    let (mat, sec) = hose1()?;
    let r = sec.outer_radius();
    let z0 = CYLINDER_RADIUS + DROP_GAP + r;
    let hose = straight(
        elements,
        DROP_LENGTH,
        DVec3::new(-0.5 * DROP_LENGTH, 0.0, z0),
        &mat,
        sec,
    );
    let model = Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: vec![cylinder(CYLINDER_RADIUS, 0.2, 512)],
        settings: SimSettings {
            gravity: DVec3::new(0.0, 0.0, -9.81),
            damping_mass: DROP_DAMPING,
            damping_stiffness: None,
            ..Default::default()
        },
    })?;
    let mut state = State::at_rest(&model);
    let dt = model.time_step;
    let per_sample = ((DROP_SAMPLE / dt).round() as u64).max(1);
    let start = Instant::now();
    let mut quiet_since: Option<f64> = None;
    let mut at_rest = false;
    while state.time < DROP_MAX_TIME {
        for _ in 0..per_sample {
            explicit::step(&model, &mut state);
        }
        health::check(&model, &state)?;
        let ke = translational_energy(&model, &state);
        if ke < REST_ENERGY {
            let since = *quiet_since.get_or_insert(state.time);
            if state.time - since >= REST_WINDOW {
                at_rest = true;
                break;
            }
        } else {
            quiet_since = None;
        }
    }
    let wall_s = start.elapsed().as_secs_f64();
    let n = elements;
    let shape_xz: Vec<[f64; 2]> = state.x.iter().map(|p| [p.x, p.z]).collect();
    Ok(DropResult {
        tool: "pliant",
        elements,
        at_rest,
        rest_time_s: if at_rest {
            quiet_since.unwrap_or(state.time)
        } else {
            f64::NAN
        },
        simulated_s: state.time,
        wall_s,
        time_step_s: dt,
        steps: state.step,
        tip_z_m: 0.5 * (state.x[0].z + state.x[n].z),
        mid_z_m: state.x[n / 2].z,
        half_span_m: 0.5 * (state.x[n].x - state.x[0].x),
        shape_xz,
        note: format!(
            "explicit, automatic stable step; mass damping {DROP_DAMPING} 1/s + default stiffness damping; kinematic Coulomb contact mu = {DROP_FRICTION}"
        ),
    })
}

/// Prints one value as a JSON line on stdout.
pub fn print<T: Serialize>(value: &T) -> Result<()> {
    println!("{}", serde_json::to_string(value)?);
    Ok(())
}
