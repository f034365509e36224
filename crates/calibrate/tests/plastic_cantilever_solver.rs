//! `plastic_cantilever` against the simulator itself: a cantilever of the library's
//! steel brake line (4.75 × 0.7 mm, σ_y 170 MPa, H 480 MPa) loaded at its tip past yield
//! and unloaded by the static solver; the fit of its force–deflection curve gives back
//! the library's E, σ_y and H.
//!
//! Two errors separate: the beam mesh's (the solver's curve against the beam theory over
//! the simulator's own 16 × 32 fibre section, integrated finely) and the fibre grid's
//! (that curve fitted by the closed-form law). The tolerances follow from the convergence
//! study `cantilever_convergence_study` (ignored: run it with `--ignored --nocapture`):
//! E and σ_y come back to 1e-4 and 1e-3, H only to about 10 %, and that is the fibre
//! grid's quadrature, not the mesh (the fit to the grid's own beam theory is as far off).
//! The cantilever is loaded to 1.5 times first yield (the tube's plastic moment is 1.46
//! times it) so that the hardening shows at all; its tip deflects 1.7 % of L.

use glam::DVec3;
use pliant_calibrate::beam_deflection::{smoothed_simpson_with, Beam, Support};
use pliant_calibrate::synthetic_laws::{simulator_section, two_column_csv};
use pliant_calibrate::{csv_input, fit_law, Geometry, LawFit, TestKind};
use pliant_core::autodiff::V3;
use pliant_core::integrators::StaticSolver;
use pliant_core::loads::LoadCase;
use pliant_core::rod::fibre_section::FibreSection;
use pliant_core::State;
use pliant_validation::harness::{
    build, clamp, dead_load, library_hose, static_settings, straight_hose,
};

const LENGTH: f64 = 0.06;
/// Load steps up to the largest force and down to zero.
const UP: usize = 24;
const DOWN: usize = 16;
/// The largest force as a multiple of first yield's (F ℓ = M_e).
const PEAK: f64 = 1.5;

struct Steel {
    e: f64,
    sy: f64,
    h: f64,
    d_inner: f64,
    d_outer: f64,
    poisson: f64,
}

fn steel() -> Steel {
    let (m, s) = library_hose("steel_tube");
    let law = m.plasticity.expect("the steel tube yields");
    Steel {
        e: m.bending_modulus(),
        sy: law.yield_stress,
        h: law.hardening_modulus,
        d_inner: s.d_inner,
        d_outer: s.d_outer,
        poisson: m.bending_modulus() / (2.0 * m.shear_modulus()) - 1.0,
    }
}

fn forces(st: &Steel) -> Vec<f64> {
    let i = std::f64::consts::FRAC_PI_4 * ((0.5 * st.d_outer).powi(4) - (0.5 * st.d_inner).powi(4));
    let f_max = PEAK * st.sy * i / (0.5 * st.d_outer * LENGTH);
    (0..=UP)
        .map(|k| f_max * k as f64 / UP as f64)
        .chain((1..=DOWN).map(|k| f_max * (1.0 - k as f64 / DOWN as f64)))
        .collect()
}

/// The tip deflections of the static solver's cantilever of `elements` elements under
/// the tip forces `force` in order (each step's history committed).
fn solver_curve(elements: usize, force: &[f64]) -> Vec<f64> {
    let (material, section) = library_hose("steel_tube");
    let hose = straight_hose(elements, LENGTH, &material, section, |_| DVec3::ZERO);
    let model = build(hose, static_settings());
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let tip = state
        .loads
        .add(dead_load(elements, DVec3::ZERO, DVec3::ZERO));
    let mut solver = StaticSolver::new(&model).expect("a chain");
    force
        .iter()
        .enumerate()
        .map(|(k, f)| {
            if let Some(LoadCase::DeadLoad(d)) = state.loads.get_mut(tip) {
                d.force = DVec3::new(0.0, *f, 0.0);
            }
            match solver.solve(&model, &mut state) {
                Ok(r) if r.converged => {}
                other => panic!("{elements} elements, step {k}: {other:?}"),
            }
            state.x[elements].y - model.rest_x[elements].y
        })
        .collect()
}

/// The beam theory over the fibre section's own M(κ) (monotone: one return from the
/// virgin state is exact for uniaxial linear hardening), the deflection integral by
/// Simpson over `intervals` per segment and Masing on unloading.
fn fibre_theory_curve(section: &FibreSection, force: &[f64]) -> Vec<f64> {
    let zero = vec![0.0; section.history_len()];
    let moment = |k: f64| section.moments(V3::new(0.0, k, 0.0), &zero).y;
    let mono = |f: f64| -> f64 {
        if f <= 0.0 {
            return 0.0;
        }
        let m_r = f * LENGTH;
        let (mut lo, mut hi) = (0.0, 1.0);
        while moment(hi) < m_r {
            hi *= 2.0;
        }
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if moment(mid) < m_r {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let integrand = |k: f64| m_r * m_r - moment(k).powi(2);
        0.5 * smoothed_simpson_with(&integrand, 0.0, 0.5 * (lo + hi), 2000) / (f * f)
    };
    let peak = force
        .iter()
        .enumerate()
        .fold(0, |b, (i, f)| if *f > force[b] { i } else { b });
    let f_max = force[peak];
    force
        .iter()
        .enumerate()
        .map(|(i, f)| {
            if i <= peak {
                mono(*f)
            } else {
                mono(f_max) - 2.0 * mono(0.5 * (f_max - f))
            }
        })
        .collect()
}

fn fit_curve(st: &Steel, force: &[f64], deflection: &[f64]) -> LawFit {
    let csv = two_column_csv("force_N,deflection_m", force, deflection, 0.0, 1);
    let table = csv_input::parse(&csv, "cantilever.csv").unwrap();
    let g = Geometry {
        d_inner: st.d_inner,
        d_outer: st.d_outer,
        length: Some(LENGTH),
    };
    fit_law(TestKind::PlasticCantilever, "cantilever.csv", &table, g).unwrap()
}

fn errors(st: &Steel, f: &LawFit) -> [f64; 3] {
    let v = |n: &str| f.estimate(n).unwrap().value;
    [
        (v("E") - st.e).abs() / st.e,
        (v("sigma_y") - st.sy).abs() / st.sy,
        (v("H") - st.h).abs() / st.h,
    ]
}

/// Largest relative difference of two deflection curves, over the largest deflection.
fn curve_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// The steel, the tip forces and the fibre theory's deflections under them.
fn setup() -> (Steel, Vec<f64>, Vec<f64>) {
    let st = steel();
    let force = forces(&st);
    let law = pliant_core::material::YieldLaw {
        yield_stress: st.sy,
        hardening_modulus: st.h,
    };
    let section = simulator_section(st.d_inner, st.d_outer, st.e, st.poisson, &law);
    let theory = fibre_theory_curve(&section, &force);
    (st, force, theory)
}

/// Elements of the tested mesh.
const ELEMENTS: usize = 80;

#[test]
fn the_static_solvers_cantilever_gives_the_library_law_back() {
    let (st, force, theory) = setup();
    let grid = errors(&st, &fit_curve(&st, &force, &theory));
    let solver = solver_curve(ELEMENTS, &force);
    let mesh = curve_difference(&solver, &theory);
    let fitted = fit_curve(&st, &force, &solver);
    let all = errors(&st, &fitted);
    println!("fibre grid alone: relative errors E, σ_y, H = {grid:?}");
    println!("{ELEMENTS} elements: curve against the fibre theory {mesh:.3e}; relative errors E, σ_y, H = {all:?}");
    for c in &fitted.checks {
        println!("  {c}");
    }
    assert!(
        grid.iter().zip(GRID_TOLERANCE).all(|(e, t)| *e < t),
        "{grid:?}"
    );
    assert!(mesh < MESH_TOLERANCE, "{mesh}");
    assert!(all.iter().zip(TOLERANCE).all(|(e, t)| *e < t), "{all:?}");
}

/// The fibre grid's errors (E, σ_y, H) of the fit to the fibre theory's curve, about
/// twice to three times the measured 3.4e-5, 3.3e-4, 0.100: H, a slope of 0.2 % of E
/// felt only near the plastic moment, takes the grid's quadrature error (its curve
/// differs from the closed form's by 1.6e-2 of the largest deflection) tenfold.
const GRID_TOLERANCE: [f64; 3] = [1e-4, 1e-3, 0.2];
/// The solver's curve against the fibre theory at [`ELEMENTS`] (first order in the
/// element length: 0.213, 0.079, 0.020, 0.0096, 0.0045 at 10, 20, 40, 80, 160 elements).
const MESH_TOLERANCE: f64 = 2e-2;
/// The whole: the solver's curve fitted. The study: E 1.1e-4, 6.4e-5, 7.5e-5, 1.2e-4,
/// 1.3e-4; σ_y 7.9e-3, 3.6e-3, 7.9e-4, 4.0e-5, 2.0e-4; H 2.7, 0.23, 0.108, 0.123, 0.110
/// at 10 … 160 elements — H levels off at the grid's own 0.10.
const TOLERANCE: [f64; 3] = [3e-4, 1e-3, 0.2];

/// The study behind the tolerances: the solver's curve at 10 … 160 elements against the
/// fibre theory, and the fitted law's errors.
#[test]
#[ignore]
fn cantilever_convergence_study() {
    let (st, force, theory) = setup();
    let beam = Beam {
        support: Support::Cantilever,
        ri: 0.5 * st.d_inner,
        ro: 0.5 * st.d_outer,
        length: LENGTH,
    };
    let p = [st.e, st.sy, st.h];
    let peak = force
        .iter()
        .enumerate()
        .fold(0, |b, (i, f)| if *f > force[b] { i } else { b });
    let closed: Vec<f64> = force
        .iter()
        .enumerate()
        .map(|(i, f)| {
            if i <= peak {
                beam.deflection(p, *f)
            } else {
                beam.deflection(p, force[peak]) - 2.0 * beam.deflection(p, 0.5 * (force[peak] - f))
            }
        })
        .collect();
    println!(
        "largest deflection {:.3} mm ({:.2} % of L); fibre theory against the closed form {:.3e}",
        theory[peak] * 1e3,
        100.0 * theory[peak] / LENGTH,
        curve_difference(&theory, &closed)
    );
    println!(
        "fibre grid alone: {:?}",
        errors(&st, &fit_curve(&st, &force, &theory))
    );
    for n in [10, 20, 40, 80, 160] {
        let solver = solver_curve(n, &force);
        println!(
            "{n} elements: curve {:.3e}, errors {:?}",
            curve_difference(&solver, &theory),
            errors(&st, &fit_curve(&st, &force, &solver))
        );
    }
}
