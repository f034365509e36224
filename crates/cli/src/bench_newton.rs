//! The Newton solvers' benchmark rows, part of `pliant bench`:
//! * quasi-static update of a 30-element hose (library material 1, 0.6 m, gravity,
//!   clamped at one end, the other end held by a hand that moves 2 mm per update): wall
//!   time per equilibrium solve, goal ≤ 1 ms (haptic rate);
//! * the same update with the hose held against a part: its middle
//!   pressed onto a block (12 triangles) with friction, the contact active in every
//!   update, goal ≤ 1 ms;
//! * implicit HHT-α step (Δt = 10 ms, a hanging hose swinging under gravity) for 10 …
//!   1000 elements: ns per element-step and the log-log slope of the cost (linear in N
//!   = slope 1).

use crate::bench::{fit_loglog, material_1, median, thread_cpu_seconds};
use anyhow::{Context, Result};
use glam::DVec3;
use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{HoseSpec, Model, RigidPartSpec, SimSettings, State, WorldSpec};
use serde::Serialize;
use std::time::Instant;

/// Results of the Newton rows.
#[derive(Clone, Debug, Serialize)]
pub struct NewtonBench {
    /// Median wall time of one quasi-static update of the 30-element hose \[ms\].
    pub static_update_ms_30: f64,
    /// Mean Newton iterations per update.
    pub static_iterations_30: f64,
    pub static_goal_ms: f64,
    /// The same with the hose held against a part: median \[ms\], mean iterations, and
    /// mean nodes in contact at the end of an update.
    pub static_update_contact_ms_30: f64,
    pub static_contact_iterations_30: f64,
    pub static_contact_nodes_30: f64,
    /// Updates whose Newton solve did not converge within its iterations, of the
    /// plain and the held-against-a-part rows (the next update starts from where it
    /// stopped; counted, not hidden).
    pub static_unconverged_30: usize,
    pub static_contact_unconverged_30: usize,
    /// (elements, ns per element-step) of the implicit step.
    pub implicit_rows: Vec<(usize, f64)>,
    /// Mean Newton iterations per implicit step, per row.
    pub implicit_iterations: Vec<f64>,
    /// (elements, ns of the thread's CPU time per element-step) of the same runs: the
    /// cost with a core to itself (wall time on a loaded machine also counts the time
    /// other work held the core).
    pub implicit_rows_cpu: Vec<(usize, f64)>,
    pub implicit_loglog_slope: f64,
}

/// A block 0.2 m long under the middle of the benchmark hose, its top `top` \[m\] high.
fn block(top: f64) -> RigidPartSpec {
    let (lo, hi) = (DVec3::new(0.2, -0.3, top - 0.1), DVec3::new(0.4, 0.5, top));
    RigidPartSpec::cuboid("block", lo, hi, (0.5, 0.4))
}

fn hose(elements: usize, length: f64) -> Result<(Model, State)> {
    hose_over(elements, length, vec![])
}

fn hose_over(
    elements: usize,
    length: f64,
    rigid_parts: Vec<RigidPartSpec>,
) -> Result<(Model, State)> {
    let (material, section) = material_1()?;
    let nodes = (0..=elements)
        .map(|i| DVec3::new(length * i as f64 / elements as f64, 0.0, 0.0))
        .collect();
    let mut model = Model::build(&WorldSpec {
        hoses: vec![HoseSpec {
            name: "bench".into(),
            material,
            nodes,
            sections: vec![section],
            normal_hint: Some(DVec3::Z),
        }],
        rigid_parts,
        settings: SimSettings::default(),
    })
    .context("building the Newton benchmark hose")?;
    model.hose_contact.active = false;
    let mut state = State::at_rest(&model);
    // clamped in its rest pose (an identity orientation would twist the root by the
    // section frame's quarter turn about the axis)
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: DVec3::ZERO,
        orientation: model.rest_q[0],
    }));
    Ok((model, state))
}

/// What [`static_update`] measured.
struct Updates {
    /// Median wall time of an update \[ms\].
    median_ms: f64,
    /// Mean Newton iterations per update.
    iterations: f64,
    /// Mean nodes touching a part at the end of an update.
    touching: f64,
    /// Updates that did not converge.
    unconverged: usize,
}

/// Median time of a quasi-static update with the free end walked along a path, mean
/// iterations, mean nodes touching a part and the updates that did not converge. With
/// `against_part` the hose's middle is pressed onto [`block`]: the hand holds the end
/// 2 cm low and walks it sideways.
fn static_update(updates: usize, against_part: bool) -> Result<Updates> {
    let (model, mut state) = if against_part {
        hose_over(30, 0.6, vec![block(-0.02)])?
    } else {
        hose(30, 0.6)?
    };
    let end = 30;
    let hand = state.loads.add(LoadCase::Fix(Fix {
        node: end,
        position: state.x[end],
        orientation: state.q[end],
    }));
    let mut solver = StaticSolver::new(&model)?;
    solver.solve(&model, &mut state)?; // sag into equilibrium first
    let mut times = Vec::with_capacity(updates);
    let (mut iterations, mut touching, mut unconverged) = (0usize, 0usize, 0usize);
    for k in 0..updates {
        let t = k as f64 * 0.002;
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(hand) {
            f.position = if against_part {
                DVec3::new(0.6 - 0.05 * t, 0.2 * t, -0.02)
            } else {
                DVec3::new(0.6 - 0.3 * t, 0.2 * t, 0.1 * (3.0 * t).sin())
            };
        }
        let start = Instant::now();
        let r = solver.solve(&model, &mut state)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        iterations += r.iterations;
        if !r.converged {
            unconverged += 1;
            if unconverged == 1 {
                eprintln!(
                    "pliant bench: quasi-static update {k}{} did not converge in {} iterations \
                     (residual {:.3e} N against {:.3e} N); counted, and the next update starts there",
                    if against_part { " against a part" } else { "" },
                    r.iterations,
                    r.residual_force,
                    r.force_limit
                );
            }
        }
        touching += state
            .contact_force
            .iter()
            .filter(|f| **f != DVec3::ZERO)
            .count();
    }
    let per_update = |n: usize| n as f64 / updates as f64;
    Ok(Updates {
        median_ms: median(&times),
        iterations: per_update(iterations),
        touching: per_update(touching),
        unconverged,
    })
}

/// ns per element-step of the implicit solver on a hose of `elements` hanging and
/// swinging under gravity (wall and thread CPU time), and the mean iterations per step.
fn implicit_cost(elements: usize, steps: usize) -> Result<(f64, f64, f64)> {
    let (model, mut state) = hose(elements, 1.0)?;
    let mut solver = ImplicitSolver::new(&model, ImplicitOptions::default())?;
    let (start, cpu) = (Instant::now(), thread_cpu_seconds());
    let mut iterations = 0usize;
    for k in 0..steps {
        iterations += solver
            .step(&model, &mut state)
            .with_context(|| format!("implicit step {k} of the {elements}-element hose"))?
            .iterations;
    }
    let per_element_step = 1e9 / (steps * elements) as f64;
    let ns = start.elapsed().as_secs_f64() * per_element_step;
    let ns_cpu = (thread_cpu_seconds() - cpu) * per_element_step;
    Ok((ns, ns_cpu, iterations as f64 / steps as f64))
}

pub fn run(quick: bool) -> Result<NewtonBench> {
    let updates = if quick { 50 } else { 400 };
    let plain = static_update(updates, false)?;
    let contact = static_update(updates, true)?;
    let sizes: &[usize] = if quick {
        &[10, 100]
    } else {
        &[10, 30, 100, 300, 1000]
    };
    let (mut rows, mut rows_cpu) = (Vec::new(), Vec::new());
    let mut its = Vec::new();
    for &n in sizes {
        let steps = if quick {
            20
        } else {
            (20_000 / n).clamp(20, 400)
        };
        let (ns, ns_cpu, it) = implicit_cost(n, steps)?;
        rows.push((n, ns));
        rows_cpu.push((n, ns_cpu));
        its.push(it);
    }
    let fit = fit_loglog(
        &rows
            .iter()
            .map(|&(n, ns)| (n as f64, ns * n as f64))
            .collect::<Vec<_>>(),
    );
    Ok(NewtonBench {
        static_update_ms_30: plain.median_ms,
        static_iterations_30: plain.iterations,
        static_goal_ms: 1.0,
        static_update_contact_ms_30: contact.median_ms,
        static_contact_iterations_30: contact.iterations,
        static_contact_nodes_30: contact.touching,
        static_unconverged_30: plain.unconverged,
        static_contact_unconverged_30: contact.unconverged,
        implicit_rows: rows,
        implicit_iterations: its,
        implicit_rows_cpu: rows_cpu,
        implicit_loglog_slope: fit.slope,
    })
}

/// Text lines for the human-readable report.
pub fn render(b: &NewtonBench) -> String {
    let mut s = format!(
        "\nNewton solvers:\n  quasi-static update, 30-element hose: {:.3} ms median ({:.1} Newton iterations; goal ≤ {} ms)\n",
        b.static_update_ms_30, b.static_iterations_30, b.static_goal_ms
    );
    s.push_str(&format!(
        "  the same held against a part (contact active, {:.1} nodes touching): {:.3} ms median ({:.1} Newton iterations; goal ≤ {} ms)\n",
        b.static_contact_nodes_30, b.static_update_contact_ms_30, b.static_contact_iterations_30, b.static_goal_ms
    ));
    for (row, n) in [
        ("quasi-static update", b.static_unconverged_30),
        ("held against a part", b.static_contact_unconverged_30),
    ] {
        if n > 0 {
            s.push_str(&format!("  {row}: {n} update(s) did not converge\n"));
        }
    }
    s.push_str("  implicit HHT-α step, Δt = 10 ms (ns per element-step, by wall and CPU time; iterations per step):\n");
    for (((n, ns), (_, cpu)), it) in b
        .implicit_rows
        .iter()
        .zip(&b.implicit_rows_cpu)
        .zip(&b.implicit_iterations)
    {
        s.push_str(&format!(
            "    {n:>5} elements: {ns:>8.0} ns  (CPU {cpu:>8.0} ns, {:>6.0} ns per element-iteration; {it:.1} it)\n",
            cpu / it.max(1.0)
        ));
    }
    s.push_str(&format!(
        "  cost per step ∝ N^{:.3} (log-log slope; 1 = linear)\n",
        b.implicit_loglog_slope
    ));
    s
}
