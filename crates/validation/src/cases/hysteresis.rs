//! `hysteresis_torsion` and `hysteresis_bending` (SPEC X2): a hose whose bending and
//! twist carry Dahl friction moments (`pliant_core::rod::hysteresis`) cycled through
//! loops, against Dahl's closed form.
//!
//! On a stretch where the curvature κ (or twist rate) moves one way from a turning point
//! (κ₀, z₀), the friction moment is z = s M_s − (s M_s − z₀) e^{−s (κ − κ₀)/κ_s}
//! (s the direction; Dahl 1976). A steady loop between ±κ_a turns at z_a = M_s tanh(κ_a/κ_s)
//! and dissipates per cycle, per length,
//!
//! ∮ z dκ = 2 [2 κ_a M_s − (M_s + z_a) κ_s (1 − e^{−2κ_a/κ_s})].
//!
//! * `hysteresis_torsion`, every solver: a 0.1 m hose clamped at one end, its other end
//!   turned about the axis (displacement control, the drives' smooth step over 2 s)
//!   from rest to +0.3 rad, then four times through ∓0.6 rad. The twist is uniform, so
//!   the end moment is G J τ + z(τ). Compared: the end moment at the middle and the end of
//!   every stroke, and the energy the end's drive puts in over the last full cycle
//!   (trapezoid over the solver's steps) against L ∮ z dτ. The closed form has no rate:
//!   the dynamic solvers' stiffness damping β K τ̇ adds 1.4·10⁻⁴ of the peak moment in
//!   mid-stroke (explicit; it halves when the stroke takes twice as long), 1.5·10⁻⁵
//!   (implicit).
//! * `hysteresis_bending`, static solver: the same hose as a cantilever under a dead
//!   moment about z cycled between ±0.2 N·m (load control). Pure bending is a circular
//!   arc, so the end turns by κ L with E I κ + z(κ) = M — solved for κ on each branch by
//!   bisection, independently of the solver — and the steady loop's amplitude κ_a by
//!   E I κ_a + M_s tanh(κ_a/κ_s) = M_a. Compared: the end's rotation at every input, and
//!   the dissipated energy of the last full cycle.

use crate::harness::{build, clamp, dead_load, hose1, static_settings, straight_hose};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::loads::{Drive, LoadCase};
use pliant_core::material::{DahlLaw, Hysteresis};
use pliant_core::{Material, SimSettings, Solver, SolverKind, SolverSettings, State};

const ELEMENTS: usize = 4;
const LENGTH: f64 = 0.1;
/// Duration of one stroke \[s\].
const STROKE: f64 = 2.0;
/// Torsion: saturated moment \[N·m\] and twist-rate scale \[1/m\]; amplitude \[1/m\].
const TORSION: DahlLaw = DahlLaw {
    moment: 0.02,
    curvature: 1.0,
};
const TWIST_AMPLITUDE: f64 = 3.0;
/// Bending: saturated moment \[N·m\] and curvature scale \[1/m\]; moment amplitude \[N·m\].
const BENDING: DahlLaw = DahlLaw {
    moment: 0.05,
    curvature: 1.0,
};
const MOMENT_AMPLITUDE: f64 = 0.2;
/// Static inputs per bending stroke.
const BENDING_INPUTS: usize = 50;

fn rubbing_hose() -> Material {
    let mut m = hose1().0;
    m.hysteresis = Some(Hysteresis {
        bending: BENDING,
        torsion: Some(TORSION),
    });
    m
}

/// Dahl's branch from the turning point (κ₀, z₀) in direction `s` at κ.
fn branch(law: DahlLaw, (k0, z0, s): (f64, f64, f64), kappa: f64) -> f64 {
    s * law.moment - (s * law.moment - z0) * (-s * (kappa - k0) / law.curvature).exp()
}

/// The energy one steady cycle between ±`amplitude` dissipates per length \[J/m\].
fn steady_loop_energy(law: DahlLaw, amplitude: f64) -> f64 {
    let (m, ks) = (law.moment, law.curvature);
    let za = m * (amplitude / ks).tanh();
    2.0 * (2.0 * amplitude * m - (m + za) * ks * (-(-2.0 * amplitude / ks).exp_m1()))
}

/// The angle of rotation `q` about the unit `axis` (rad), for rotations about it.
fn angle_about(q: DQuat, axis: DVec3) -> f64 {
    2.0 * DVec3::new(q.x, q.y, q.z).dot(axis).atan2(q.w)
}

fn settings(kind: SolverKind) -> SimSettings {
    SimSettings {
        solver: SolverSettings {
            kind,
            implicit_time_step: 0.005,
            static_input_step: 0.01,
            ..Default::default()
        },
        ..static_settings()
    }
}

/// The twisted hose under `kind`.
fn torsion(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "hysteresis_torsion";
    match twist_cycles(kind) {
        Ok(checks) => checks,
        Err(e) => vec![Check::failed(CASE, kind.name(), &e)],
    }
}

fn twist_cycles(kind: SolverKind) -> Result<Vec<Check>, String> {
    const CASE: &str = "hysteresis_torsion";
    let name = kind.name();
    let (material, section) = (rubbing_hose(), hose1().1);
    let gj = material.shear_modulus() * section.polar_moment();
    let model = build(
        straight_hose(ELEMENTS, LENGTH, &material, section, |_| DVec3::ZERO),
        settings(kind),
    );
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let end = ELEMENTS;
    let mut solver = Solver::new(&model, settings(kind).solver).map_err(|e| e.to_string())?;
    let peak = gj * TWIST_AMPLITUDE + TORSION.moment;
    let twist_of = |s: &State| angle_about(s.q[end], DVec3::X) / LENGTH;
    let mut checks = Vec::new();
    // the reference branch: from rest, upwards
    let mut turning = (0.0, 0.0, 1.0);
    let mut energy = 0.0;
    let strokes = [1.0, -2.0, 2.0, -2.0, 2.0];
    for (k, stroke) in strokes.into_iter().enumerate() {
        state
            .loads
            .remove_on_node(end, |c| matches!(c, LoadCase::Fix(_)));
        let start = (state.x[end], state.q[end]);
        let rotation = DVec3::X * (stroke * TWIST_AMPLITUDE * LENGTH);
        let id = state.loads.add(LoadCase::Drive(Drive::new(
            end,
            start,
            &[],
            rotation,
            state.time,
            STROKE,
        )));
        let (t0, t_end) = (state.time, state.time + STROKE);
        let mut middle_done = false;
        let mut last = (twist_of(&state), state.reaction_moment[end].x);
        while state.time < t_end - 1e-9 {
            let stats = solver.step(&model, &mut state).map_err(|e| e.to_string())?;
            if !stats.converged {
                return Err(format!("step at t = {:.3} s did not converge", state.time));
            }
            let now = (twist_of(&state), state.reaction_moment[end].x);
            if k >= 3 {
                // the drive's work on the end: ∫ M dφ = L ∫ M dτ
                energy += 0.5 * (now.1 + last.1) * (now.0 - last.0) * LENGTH;
            }
            last = now;
            let at_middle = !middle_done && state.time >= t0 + 0.5 * STROKE - 1e-9;
            let at_end = state.time >= t_end - 1e-9;
            if at_middle || at_end {
                middle_done = true;
                let tau = now.0;
                let want = gj * tau + branch(TORSION, turning, tau);
                let label = if at_end { "end" } else { "middle" };
                checks.push(Check::scaled(
                    CASE,
                    &format!("{name}: end moment, stroke {}, {label} N·m", k + 1),
                    now.1,
                    want,
                    peak,
                    1e-3,
                ));
            }
        }
        state.loads.remove(id);
        clamp(&mut state, end);
        let tau = twist_of(&state);
        turning = (tau, branch(TORSION, turning, tau), -turning.2);
    }
    let want = LENGTH * steady_loop_energy(TORSION, TWIST_AMPLITUDE);
    checks.push(Check::relative(
        CASE,
        &format!("{name}: energy dissipated in the last cycle J"),
        energy,
        want,
        3e-3,
    ));
    Ok(checks)
}

/// The root of the increasing `f` in [−100, 100] 1/m, by bisection.
fn root(f: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (-100.0, 100.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// κ on the branch from `turning` where E I κ + z(κ) = `moment` (the left side grows
/// with κ).
fn curvature_at(ei: f64, turning: (f64, f64, f64), moment: f64) -> f64 {
    root(|k| ei * k + branch(BENDING, turning, k) - moment)
}

/// The bent cantilever under the static solver.
fn bending() -> Vec<Check> {
    const CASE: &str = "hysteresis_bending";
    match bend_cycles() {
        Ok(checks) => checks,
        Err(e) => vec![Check::failed(CASE, "static", &e)],
    }
}

fn bend_cycles() -> Result<Vec<Check>, String> {
    const CASE: &str = "hysteresis_bending";
    let kind = SolverKind::Static;
    let (material, section) = (rubbing_hose(), hose1().1);
    let ei = material.bending_modulus() * section.second_moment();
    let model = build(
        straight_hose(ELEMENTS, LENGTH, &material, section, |_| DVec3::ZERO),
        settings(kind),
    );
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let end = ELEMENTS;
    let id = state.loads.add(dead_load(end, DVec3::ZERO, DVec3::ZERO));
    let mut solver = Solver::new(&model, settings(kind).solver).map_err(|e| e.to_string())?;
    let mut turning = (0.0, 0.0, 1.0);
    let mut moment = 0.0;
    let mut worst: (f64, f64, f64) = (0.0, 0.0, 0.0);
    let mut energy = 0.0;
    let mut last = (0.0, 0.0);
    let strokes = [1.0, -2.0, 2.0, -2.0, 2.0];
    for (k, stroke) in strokes.into_iter().enumerate() {
        let from = moment;
        for i in 1..=BENDING_INPUTS {
            moment = from + stroke * MOMENT_AMPLITUDE * i as f64 / BENDING_INPUTS as f64;
            if let Some(LoadCase::DeadLoad(d)) = state.loads.get_mut(id) {
                d.moment = DVec3::Z * moment;
            }
            let stats = solver.step(&model, &mut state).map_err(|e| e.to_string())?;
            if !stats.converged {
                return Err(format!("input at t = {:.3} s did not converge", state.time));
            }
            let angle = angle_about(state.q[end], DVec3::Z);
            let want = curvature_at(ei, turning, moment) * LENGTH;
            let error = (angle - want).abs();
            if error >= worst.0 {
                worst = (error, angle, want);
            }
            if k >= 3 {
                energy += 0.5 * (moment + last.1) * (angle - last.0);
            }
            last = (angle, moment);
        }
        let kappa = curvature_at(ei, turning, moment);
        turning = (kappa, branch(BENDING, turning, kappa), -turning.2);
    }
    // the steady loop's amplitude: E I κ_a + M_s tanh(κ_a/κ_s) = M_a
    let amplitude =
        root(|k| ei * k + BENDING.moment * (k / BENDING.curvature).tanh() - MOMENT_AMPLITUDE);
    let scale = amplitude * LENGTH;
    Ok(vec![
        Check::scaled(
            CASE,
            "static: end rotation, worst of 250 inputs rad",
            worst.1,
            worst.2,
            scale,
            1e-4,
        ),
        Check::relative(
            CASE,
            "static: energy dissipated in the last cycle J",
            energy,
            LENGTH * steady_loop_energy(BENDING, amplitude),
            3e-3,
        ),
    ])
}

/// The twisted hose under every solver.
pub fn run_torsion() -> Vec<Check> {
    SolverKind::ALL.into_iter().flat_map(torsion).collect()
}

/// The bent cantilever.
pub fn run_bending() -> Vec<Check> {
    bending()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed-form loop energy is the integral of the two branches between the
    /// steady turning points (Simpson on 2 000 intervals).
    #[test]
    fn the_steady_loop_energy_is_the_area_between_the_branches() {
        let (law, a) = (TORSION, TWIST_AMPLITUDE);
        let za = law.moment * (a / law.curvature).tanh();
        let up = |k: f64| branch(law, (-a, -za, 1.0), k);
        let down = |k: f64| branch(law, (a, za, -1.0), k);
        let n = 2000;
        let h = 2.0 * a / n as f64;
        let mut area = 0.0;
        for i in 0..=n {
            let k = -a + i as f64 * h;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            area += w * (up(k) - down(k));
        }
        area *= h / 3.0;
        let want = steady_loop_energy(law, a);
        assert!((area - want).abs() < 1e-10 * want, "{area} vs {want}");
        // the steady branches meet at the turning points
        assert!((up(a) - za).abs() < 1e-15 && (down(-a) + za).abs() < 1e-15);
    }
}
