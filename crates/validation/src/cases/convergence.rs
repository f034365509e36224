//! `convergence`: the discretisation error of the tip-load cantilever (λ = PL²/EI = 2)
//! falls at second order or faster in the element count. (The linear co-rotational
//! element converged at second order; with the shallow-arch coupling of the local element
//! the measured slope is about −3.8 over N = 4 … 32.) The error is taken against the independent shooting solution
//! of the same extensible rod (same EA, EI), so the extensibility of the hose does not
//! pollute the measured rate; the slope of log(error) over log(N) for N = 4, 8, 16, 32 must
//! be −1.8 or steeper (second order, less 10 %).

use crate::cases::tip_load::tip_deflection;
use crate::harness::hose1;
use crate::reference_bridge::hose1_stiffness;
use crate::Check;
use nalgebra::Vector3;
use pliant_reference::{EndCondition, Rod, ShootingSolver};

const LAMBDA: f64 = 2.0;
const COUNTS: [usize; 4] = [4, 8, 16, 32];

fn reference_tip() -> Result<f64, String> {
    let (mat, sec) = hose1();
    let stiffness = hose1_stiffness()?;
    let rod =
        Rod::new(vec![Vector3::zeros(), Vector3::x()], stiffness).map_err(|e| e.to_string())?;
    let base = rod.rest_base_pose();
    let solver = ShootingSolver::new(rod, base).map_err(|e| e.to_string())?;
    let p = LAMBDA * mat.bending_modulus() * sec.second_moment();
    let steps: Vec<EndCondition> = (1..=8)
        .map(|k| {
            EndCondition::loaded(
                Vector3::new(0.0, -p * k as f64 / 8.0, 0.0),
                Vector3::zeros(),
            )
        })
        .collect();
    let sols = solver.solve_path(&steps).map_err(|e| e.to_string())?;
    let tip = sols.last().ok_or("no solution")?.end_state().position;
    Ok(-tip.y)
}

pub fn run() -> Vec<Check> {
    let reference = match reference_tip() {
        Ok(r) => r,
        Err(e) => return vec![Check::failed("convergence", "reference", &e)],
    };
    let mut points = Vec::new();
    for n in COUNTS {
        match tip_deflection(n, LAMBDA) {
            Ok((w, _)) => {
                let error = (w - reference).abs() / reference;
                eprintln!("convergence: N = {n}: relative tip error {error:.3e}");
                points.push(((n as f64).ln(), error.ln()))
            }
            Err(e) => return vec![Check::failed("convergence", &format!("N={n}"), &e)],
        }
    }
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let slope = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / points.iter().map(|(x, _)| (x - mx).powi(2)).sum::<f64>();
    let finest = points.last().map(|p| p.1.exp()).unwrap_or(f64::NAN);
    vec![
        // the error is how far the slope falls short of −2, relative to 2
        Check::with_error(
            "convergence",
            "log-log slope of tip error vs N (lambda=2), at most -2",
            slope,
            -2.0,
            (slope + 2.0).max(0.0) / 2.0,
            0.1,
        ),
        Check::with_error(
            "convergence",
            "tip w error at N=32 vs reference (relative)",
            finest,
            0.0,
            finest,
            1e-3,
        ),
    ]
}
