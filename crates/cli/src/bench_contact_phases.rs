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
//!
//! The floor at rest and the swaying one do not hold the same contacts (the hoses are
//! clamped in the world while the floor heaves under them, so it presses more of each
//! hose into contact). The **frozen** row therefore also times each window on the
//! swaying world's own state at the window's first step, its floor stopped where the
//! sway has it then: the same part at rest in the same pose, the hoses as they lie on
//! it — the moving floor over that is the cost of the motion at (initially) equal
//! contacts.

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
    /// Wall ns per step of the swaying world's state at the window's first step with its
    /// floor frozen in its pose there ([`freeze_floor`]), and the swaying floor over that.
    pub ns_per_step_frozen: f64,
    pub moving_over_frozen: f64,
    /// Active contact points per step with the floor frozen.
    pub frozen_contact_points_per_step: f64,
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

/// Per window: wall ns per step (median over the chunks) and contact points per step of
/// the world whose floor sways, taken at the window's first step and timed with the floor
/// frozen there ([`freeze_floor`]). The swaying run itself is not advanced by the timing.
fn time_frozen_windows(floor_quads: usize, quick: bool) -> Result<Vec<(f64, f64)>> {
    let sway = bench::floor_sway();
    let (mut model, mut state) = bench::setup_moving(5, 30, floor_quads, Some(sway.clone()))?;
    model.threads = 1;
    let mut step = 0u64;
    let mut out = Vec::new();
    for (name, first, steps) in windows(quick) {
        bench::run_steps(&model, &mut state, first - step);
        step = first;
        let (frozen_model, mut frozen) = freeze_floor(&model, &state, floor_quads, &sway)?;
        let (ns, points, _) = time_chunks(&frozen_model, &mut frozen, steps, |s| {
            s.contact.points.len()
        });
        if let Err(d) = health::check(&frozen_model, &frozen) {
            bail!("contact benchmark ({name} window, floor frozen) diverged: {d}");
        }
        out.push((ns, points));
    }
    Ok(out)
}

/// The bench world with its floor at rest in the pose `motion` gives it at `state`'s time
/// (its vertices mapped by that pose), and `state`'s hoses on it: positions, orientations,
/// velocities and loads. (The contacts' remembered normals start afresh: they decide the
/// side only for a hose axis exactly on the surface.)
pub(crate) fn freeze_floor(
    model: &Model,
    state: &State,
    floor_quads: usize,
    motion: &PartMotion,
) -> Result<(Model, State)> {
    let pose = motion.placement_at(state.time).pose;
    let mut world = bench::world_with_floor(5, 30, floor_quads)?;
    for part in &mut world.rigid_parts {
        for v in &mut part.vertices {
            *v = pose.apply(*v);
        }
    }
    let mut frozen_model = Model::build(&world)?;
    frozen_model.threads = model.threads;
    let mut frozen = State::at_rest(&frozen_model);
    frozen.time = state.time;
    frozen.step = state.step;
    frozen.x.clone_from(&state.x);
    frozen.q.clone_from(&state.q);
    frozen.v.clone_from(&state.v);
    frozen.w.clone_from(&state.w);
    frozen.loads = state.loads.clone();
    Ok((frozen_model, frozen))
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
    let frozen = time_frozen_windows(FLOOR_QUADS, quick)?;
    Ok(windows(quick)
        .iter()
        .zip(
            free.iter()
                .zip(floor.iter().zip(moving.iter().zip(&frozen))),
        )
        .map(
            |(
                &(name, first_step, steps),
                (&(f, _), (&(c, points), (&(m, moving_points), &(z, frozen_points)))),
            )| {
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
                    ns_per_step_frozen: z,
                    moving_over_frozen: m / z,
                    frozen_contact_points_per_step: frozen_points,
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
                 points): ×{:.2} the floor at rest (goal ≤ 1.3); ×{:.2} the floor frozen \
                 mid-sway ({:.0} ns/step, {:.1} contact points)\n",
                p.name,
                p.first_step,
                p.first_step + p.steps,
                p.ns_per_step_free,
                p.ns_per_step_contact,
                p.contact_points_per_step,
                p.ratio,
                p.ns_per_step_moving,
                p.moving_contact_points_per_step,
                p.moving_ratio,
                p.moving_over_frozen,
                p.ns_per_step_frozen,
                p.frozen_contact_points_per_step
            )
        })
        .collect()
}
