//! The contact benchmark at fixed steps of its world.
//!
//! The time-boxed rows of `pliant bench --only contact` warm up for a wall time and then
//! measure for one. A slower or busier machine therefore measures earlier steps, and
//! those are dearer: the hoses still slide over the floor there. The ratio moves with the
//! machine's load as much as with the code.
//!
//! These windows are fixed step numbers of the same world ([`bench::setup_moving`]), so every
//! machine measures the same simulated states:
//! - **sliding**: steps 10 000–15 000, the hoses still moving over the floor;
//! - **lying**: steps 55 000–60 000, the hoses at rest on it.
//!
//! Each window is timed in five chunks; the per-step time is their median, and the ratio
//! compares the floor's world with the contact-free one at the same steps. The same
//! windows of the world whose floor sways ([`bench::floor_sway`]) give the moving floor's
//! cost over the floor at rest, at the same steps every run.

use crate::bench::{self, median, FLOOR_QUADS};
use anyhow::{bail, Result};
use pliant_core::kinematics::PartMotion;
use pliant_core::{health, integrators::explicit, Model, State};
use serde::Serialize;
use std::time::Instant;

/// One window of steps, without and with the floor.
#[derive(Clone, Debug, Serialize)]
pub struct ContactPhase {
    pub name: &'static str,
    /// The window's first step and its length.
    pub first_step: u64,
    pub steps: u64,
    /// Wall ns per step (median of five chunks) without and with the floor.
    pub ns_per_step_free: f64,
    pub ns_per_step_contact: f64,
    /// ns_per_step_contact / ns_per_step_free.
    pub ratio: f64,
    /// Active contact points per step with the floor, over the window.
    pub contact_points_per_step: f64,
    /// Wall ns per step with the floor swaying ([`bench::floor_sway`]), and that over the
    /// floor at rest at the same steps.
    pub ns_per_step_moving: f64,
    pub moving_ratio: f64,
    /// Active contact points per step with the floor swaying.
    pub moving_contact_points_per_step: f64,
}

/// The windows: name, first step, steps (`quick`: a smoke-test size).
fn windows(quick: bool) -> [(&'static str, u64, u64); 2] {
    if quick {
        [("sliding", 200, 100), ("lying", 500, 100)]
    } else {
        [("sliding", 10_000, 5_000), ("lying", 55_000, 5_000)]
    }
}

/// Chunks each window is timed in.
const CHUNKS: u64 = 5;

/// Per window: wall ns per step (median over the chunks) and contact points per step, the
/// floor moving by `floor_motion` (None: at rest).
fn time_windows(
    floor_quads: usize,
    floor_motion: Option<PartMotion>,
    quick: bool,
) -> Result<Vec<(f64, f64)>> {
    let (mut model, mut state) = bench::setup_moving(5, 30, floor_quads, floor_motion)?;
    model.threads = 1;
    let mut step = 0u64;
    let mut out = Vec::new();
    for (name, first, steps) in windows(quick) {
        bench::run_steps(&model, &mut state, first - step);
        let (ns, points, done) = time_chunks(&model, &mut state, steps, |s| s.contact.points.len());
        step = first + done;
        if let Err(d) = health::check(&model, &state) {
            bail!("contact benchmark ({name} window) diverged: {d}");
        }
        out.push((ns, points));
    }
    Ok(out)
}

/// Times about `steps` steps of `state` in [`CHUNKS`] chunks: wall ns per step (median
/// over the chunks), `count` of the state after each step averaged over the steps, and
/// the steps taken.
pub(crate) fn time_chunks(
    model: &Model,
    state: &mut State,
    steps: u64,
    count: impl Fn(&State) -> usize,
) -> (f64, f64, u64) {
    let chunk = (steps / CHUNKS).max(1);
    let (mut per_step, mut total) = (Vec::new(), 0usize);
    for _ in 0..CHUNKS {
        let t = Instant::now();
        for _ in 0..chunk {
            explicit::step(model, state);
            total += count(state);
        }
        per_step.push(t.elapsed().as_nanos() as f64 / chunk as f64);
    }
    let done = CHUNKS * chunk;
    (median(&per_step), total as f64 / done as f64, done)
}

/// Measures both windows without, with the 100 352-triangle floor and with it swaying.
pub fn measure(quick: bool) -> Result<Vec<ContactPhase>> {
    let free = time_windows(0, None, quick)?;
    let floor = time_windows(FLOOR_QUADS, None, quick)?;
    let moving = time_windows(FLOOR_QUADS, Some(bench::floor_sway()), quick)?;
    Ok(windows(quick)
        .iter()
        .zip(free.iter().zip(floor.iter().zip(&moving)))
        .map(
            |(&(name, first_step, steps), (&(f, _), (&(c, points), &(m, moving_points))))| {
                ContactPhase {
                    name,
                    first_step,
                    steps,
                    ns_per_step_free: f,
                    ns_per_step_contact: c,
                    ratio: c / f,
                    contact_points_per_step: points,
                    ns_per_step_moving: m,
                    moving_ratio: m / c,
                    moving_contact_points_per_step: moving_points,
                }
            },
        )
        .collect())
}

/// One line per window, for the terminal.
pub fn render(phases: &[ContactPhase]) -> String {
    phases
        .iter()
        .map(|p| {
            format!(
                "  {} (steps {}–{}): {:.0} ns/step free, {:.0} ns/step on the floor \
                 ({:.1} contact points): ×{:.2}; swaying {:.0} ns/step ({:.1} contact \
                 points): ×{:.2} the floor at rest (goal ≤ 1.3)\n",
                p.name,
                p.first_step,
                p.first_step + p.steps,
                p.ns_per_step_free,
                p.ns_per_step_contact,
                p.contact_points_per_step,
                p.ratio,
                p.ns_per_step_moving,
                p.moving_contact_points_per_step,
                p.moving_ratio
            )
        })
        .collect()
}
