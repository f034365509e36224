//! The full engine-bay benchmark (SPEC §6 and I6), part of `pliant
//! bench`: 20 hoses of 30 elements (600 elements) routed among procedural engine-bay
//! parts of more than a million triangles — a finely tessellated, wavy heat shield, an
//! engine block (a box with subdivided faces) and six cylinders (pipes, pulleys) — one
//! hand routing one hose along a scripted path, run through the [`Workcell`] as a live
//! session runs it. Reported per solver (explicit, implicit, static), with and without
//! sleeping hoses ([`pliant_core::sleep`]): the real-time factor (simulated seconds per
//! wall second) and how many hoses slept.
//!
//! Sequence per case: every hose is clamped at both ends (routed and mounted) except
//! the one the hand takes by its free end; the world is brought to its static
//! equilibrium (one [`Input::SolveStatic`], untimed), the hand grabs, the cell runs until
//! calm hoses have had time to fall asleep (untimed; [`SLEEP_AFTER_STEPS`] steps and
//! at least 0.2 s for the explicit solver, 50 ms for the others, which do not sleep),
//! then the hand routes its hose for the timed span (0.3 s of its 1 s path). The parts are built
//! in code, so no big file is committed; `--quick` builds ≈ 12 000 triangles, skips the
//! settle and times a few steps (a smoke run, its numbers are not the engine bay's).

use crate::bench::{material_1, thread_cpu_seconds};
use anyhow::{Context, Result};
use glam::DVec3;
use pliant_assembly::workcell::WorkcellSetup;
use pliant_assembly::{Grip, InitialLoad, Input, NoObserver, NodeRef, Workcell, WorkcellOptions};
use pliant_core::sleep::SLEEP_AFTER_STEPS;
use pliant_core::spec::RigidPartSpec;
use pliant_core::{HoseSpec, Model, SimSettings, SolverKind, WorldSpec};
use serde::Serialize;
use std::sync::{mpsc, Arc, Mutex, PoisonError};
use std::time::Duration;
use std::time::Instant;

/// Hoses and elements per hose.
pub const HOSES: usize = 20;
pub const ELEMENTS_PER_HOSE: usize = 30;
/// Hose length \[m\] (25 mm elements, ≈ 1.6 outer diameters of library hose 1).
const HOSE_LENGTH: f64 = 0.75;
/// The routed hose (its last node is free, held by the hand).
const ROUTED: usize = 4;
/// Most wall time one case's timed span may take \[s\] (`--quick`: 2 s); a case stopped
/// there reports the steps it took (a static step that meets a limit point follows the
/// snap dynamically, which can take many explicit steps).
const WALL_CAP: f64 = 40.0;
/// Duration of the hand's path \[s\] (≈ 0.2 m at a worker's ≈ 0.2 m/s); the timed span
/// covers all of it or its start.
const PATH_DURATION: f64 = 1.0;

/// Tessellation of the parts.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Tessellation {
    /// Heat shield: quads per side (2 triangles each).
    pub shield_quads: usize,
    /// Engine block: quads per face side.
    pub block_quads: usize,
    /// Cylinders: segments around, rings along.
    pub cylinder_segments: usize,
    pub cylinder_rings: usize,
}

impl Tessellation {
    pub fn new(quick: bool) -> Self {
        if quick {
            Tessellation {
                shield_quads: 60,
                block_quads: 10,
                cylinder_segments: 24,
                cylinder_rings: 12,
            }
        } else {
            Tessellation {
                shield_quads: 560,
                block_quads: 100,
                cylinder_segments: 160,
                cylinder_rings: 200,
            }
        }
    }
}

/// One measured case.
#[derive(Clone, Debug, Serialize)]
pub struct EngineBayRow {
    pub solver: &'static str,
    pub sleeping: bool,
    /// Simulated time measured \[s\] and the steps it took.
    pub simulated_s: f64,
    pub steps: u64,
    pub time_step_s: f64,
    pub wall_s: f64,
    /// Simulated seconds per wall second.
    pub realtime_factor: f64,
    /// CPU time of the case's thread over the timed span \[s\], and simulated seconds
    /// per CPU second: what the real-time factor would be with a core to itself (on a
    /// loaded machine the wall time also counts the time other work held the core).
    pub cpu_s: f64,
    pub realtime_factor_cpu: f64,
    /// Mean number of hoses asleep over the timed steps.
    pub hoses_asleep_mean: f64,
    /// Peak hand force during the timed span \[N\].
    pub hand_force_peak_n: f64,
    /// Why the timed span ended early, if it did — a divergence, or the wall-time cap
    /// (the row then measures the steps before it).
    pub stopped: Option<String>,
}

/// How far a case has got (read when it overruns its wall-time budget).
#[derive(Clone, Copy, Debug, Default)]
struct Partial {
    taken: u64,
    wall: f64,
    asleep_sum: usize,
    peak: f64,
    time_step: f64,
}

/// The engine-bay section of `pliant bench`.
#[derive(Clone, Debug, Serialize)]
pub struct EngineBayBench {
    pub hoses: usize,
    pub elements: usize,
    pub triangles: usize,
    pub tessellation: Tessellation,
    /// Wall time to build the model (contact trees of every part) \[s\].
    pub build_s: f64,
    /// Wall time of the untimed static equilibrium at the start \[s\] (first case).
    pub presettle_s: f64,
    pub rows: Vec<EngineBayRow>,
    pub quick: bool,
}

/// A grid of `nu × nv` quads over `point(u, v)`, u, v ∈ [0, 1], into `part`.
fn grid(
    part: &mut RigidPartSpec,
    nu: usize,
    nv: usize,
    closed_u: bool,
    point: impl Fn(f64, f64) -> DVec3,
) {
    let base = part.vertices.len() as u32;
    let cols = if closed_u { nu } else { nu + 1 };
    for j in 0..=nv {
        for i in 0..cols {
            part.vertices
                .push(point(i as f64 / nu as f64, j as f64 / nv as f64));
        }
    }
    for j in 0..nv {
        for i in 0..nu {
            let i1 = if closed_u { (i + 1) % nu } else { i + 1 };
            let at = |i: usize, j: usize| base + (j * cols + i) as u32;
            let (a, b, c, d) = (at(i, j), at(i1, j), at(i1, j + 1), at(i, j + 1));
            part.triangles.push([a, b, c]);
            part.triangles.push([a, c, d]);
        }
    }
}

fn part(name: &str) -> RigidPartSpec {
    RigidPartSpec {
        name: name.into(),
        vertices: Vec::new(),
        triangles: Vec::new(),
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion: None,
        parent: None,
        movable: false,
    }
}

/// The parts: a wavy heat shield over the bay's floor (x 0…0.8 m, y −0.4…0.4 m, z ≈ 5 cm),
/// an engine block (x 0.25…0.55, y −0.15…0.15, z 0.06…0.30) and six upright cylinders
/// (r 3 cm, z 0.05…0.30) at x 0.22 and 0.58, y −0.3, 0, 0.3.
pub fn parts(t: &Tessellation) -> Vec<RigidPartSpec> {
    let mut shield = part("heat shield");
    grid(
        &mut shield,
        t.shield_quads,
        t.shield_quads,
        false,
        |u, v| {
            let (x, y) = (0.8 * u, -0.4 + 0.8 * v);
            DVec3::new(x, y, 0.05 + 0.008 * (23.0 * x).sin() * (19.0 * y).cos())
        },
    );
    let mut block = part("engine block");
    let (lo, hi) = (DVec3::new(0.25, -0.15, 0.06), DVec3::new(0.55, 0.15, 0.30));
    let n = t.block_quads;
    for axis in 0..3 {
        for side in [lo, hi] {
            let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
            grid(&mut block, n, n, false, |u, v| {
                let mut p = side;
                p[a1] = lo[a1] + (hi[a1] - lo[a1]) * u;
                p[a2] = lo[a2] + (hi[a2] - lo[a2]) * v;
                p
            });
        }
    }
    let mut out = vec![shield, block];
    for (k, (x, y)) in [0.22, 0.58]
        .iter()
        .flat_map(|&x| [-0.3, 0.0, 0.3].map(move |y| (x, y)))
        .enumerate()
    {
        let mut c = part(&format!("cylinder {}", k + 1));
        grid(
            &mut c,
            t.cylinder_segments,
            t.cylinder_rings,
            true,
            |u, v| {
                let a = std::f64::consts::TAU * u;
                DVec3::new(x + 0.03 * a.cos(), y + 0.03 * a.sin(), 0.05 + 0.25 * v)
            },
        );
        out.push(c);
    }
    out
}

/// Start and end of hose `k`: ten hoses along x at z = 0.33 m over the block and the
/// cylinders (they sag onto the block), ten along y at z = 0.09 m beside the block, over
/// the heat shield (they sag onto it).
fn route(k: usize) -> (DVec3, DVec3) {
    if k < 10 {
        let y = -0.36 + 0.08 * k as f64;
        (DVec3::new(0.025, y, 0.33), DVec3::new(0.775, y, 0.33))
    } else {
        let j = k - 10;
        let x = if j < 5 {
            0.03 + 0.035 * j as f64
        } else {
            0.63 + 0.035 * (j - 5) as f64
        };
        (DVec3::new(x, -0.375, 0.09), DVec3::new(x, 0.375, 0.09))
    }
}

/// The engine bay's model.
pub fn model(t: &Tessellation) -> Result<Model> {
    let (material, section) = material_1()?;
    let hoses = (0..HOSES)
        .map(|k| {
            let (a, b) = route(k);
            HoseSpec {
                name: format!("hose {}", k + 1),
                material: material.clone(),
                nodes: (0..=ELEMENTS_PER_HOSE)
                    .map(|i| a.lerp(b, i as f64 / ELEMENTS_PER_HOSE as f64))
                    .collect(),
                sections: vec![section],
                normal_hint: Some(DVec3::Z),
            }
        })
        .collect();
    debug_assert!((route(0).1 - route(0).0).length() - HOSE_LENGTH < 1e-9);
    Model::build(&WorldSpec {
        hoses,
        rigid_parts: parts(t),
        settings: SimSettings::default(),
    })
    .context("building the engine-bay benchmark model")
}

fn setup(model: &Arc<Model>) -> WorkcellSetup {
    let mut initial = Vec::new();
    for hose in 0..HOSES {
        initial.push(InitialLoad::fix(NodeRef { hose, node: 0 }));
        if hose != ROUTED {
            initial.push(InitialLoad::fix(NodeRef {
                hose,
                node: ELEMENTS_PER_HOSE,
            }));
        }
    }
    WorkcellSetup {
        initial,
        ..WorkcellSetup::bare(model.clone())
    }
}

fn asleep(cell: &Workcell) -> usize {
    cell.state()
        .sleep
        .hose_asleep
        .iter()
        .filter(|a| **a)
        .count()
}

/// One case: returns the row and the wall time of the static pre-settle.
fn case(
    model: &Arc<Model>,
    solver: SolverKind,
    sleeping: bool,
    quick: bool,
    partial: &Mutex<Partial>,
) -> Result<(EngineBayRow, f64)> {
    let options = WorkcellOptions {
        solver: Some(solver),
        sleeping,
        ..WorkcellOptions::default()
    };
    let mut cell = Workcell::new(setup(model), options).map_err(anyhow::Error::msg)?;
    let start = Instant::now();
    if !quick {
        cell.apply(Input::SolveStatic {
            force_tolerance: 1e-3,
            moment_tolerance: 1e-4,
            max_iterations: 200,
            stable_only: false,
        })
        .map_err(|e| anyhow::anyhow!("the engine bay's static pre-settle: {e}"))?;
        cell.apply(Input::Arrest)
            .map_err(|e| anyhow::anyhow!("{e}"))?;
    }
    let presettle = start.elapsed().as_secs_f64();
    let end = cell.state().x[model.hoses[ROUTED].node(ELEMENTS_PER_HOSE)];
    cell.apply(Input::Grab {
        hand: 0,
        at: end,
        grip: Grip::Firm,
    })
    .map_err(|e| anyhow::anyhow!("the hand's grab: {e}"))?;
    if !quick {
        // calm hoses fall asleep (with sleeping on); the hand holds still
        // (sleeping affects the explicit solver only: the others settle for 50 ms)
        let settle = match solver {
            SolverKind::Explicit => cell.steps_in(0.2).max(
                u64::from(SLEEP_AFTER_STEPS) + 2 * pliant_assembly::workcell::HEALTH_CHECK_EVERY,
            ),
            _ => cell.steps_in(0.05),
        };
        cell.steps(settle, &mut NoObserver)
            .map_err(|d| anyhow::anyhow!("the engine bay diverged while settling: {d}"))?;
    }
    // the routed hose's end is carried up, over its neighbour and down beside it
    let simulated = match (quick, solver) {
        (true, SolverKind::Explicit) => 0.01,
        (true, _) => 0.03,
        (false, _) => 0.3,
    };
    let waypoints = vec![
        end + DVec3::new(-0.05, 0.02, 0.06),
        end + DVec3::new(-0.10, 0.06, 0.06),
        end + DVec3::new(-0.12, 0.08, 0.0),
    ];
    cell.apply(Input::MoveHand {
        hand: 0,
        waypoints,
        rotation: DVec3::new(0.0, 0.0, 0.3),
        duration: PATH_DURATION,
    })
    .map_err(|e| anyhow::anyhow!("the hand's path: {e}"))?;
    let steps = cell.steps_until_done(simulated);
    let (mut asleep_sum, mut peak) = (0usize, 0.0_f64);
    let (start, cpu_start) = (Instant::now(), thread_cpu_seconds());
    let (mut taken, mut diverged) = (0u64, None);
    let cap = if quick { 2.0 } else { WALL_CAP };
    for k in 0..steps {
        if start.elapsed().as_secs_f64() > cap {
            diverged = Some(format!(
                "stopped at the {cap} s wall-time cap after {k} of {steps} steps"
            ));
            break;
        }
        if let Err(d) = cell.step(&mut NoObserver) {
            diverged = Some(format!("diverged at timed step {k}: {d}"));
            break;
        }
        taken += 1;
        asleep_sum += asleep(&cell);
        if let Some(r) = cell.hand_records().first() {
            peak = peak.max(r.load.force.length());
        }
        *partial.lock().unwrap_or_else(PoisonError::into_inner) = Partial {
            taken,
            wall: start.elapsed().as_secs_f64(),
            asleep_sum,
            peak,
            time_step: cell.time_step(),
        };
    }
    let wall = start.elapsed().as_secs_f64();
    let cpu = thread_cpu_seconds() - cpu_start;
    if diverged.is_none() {
        if let Err(d) = cell.check() {
            diverged = Some(format!("diverged at the end: {d}"));
        }
    }
    // the steps taken before a divergence still measure the cost per step
    let sim = taken as f64 * cell.time_step();
    Ok((
        EngineBayRow {
            solver: solver.name(),
            sleeping,
            simulated_s: sim,
            steps: taken,
            time_step_s: cell.time_step(),
            wall_s: wall,
            realtime_factor: sim / wall.max(1e-12),
            cpu_s: cpu,
            realtime_factor_cpu: sim / cpu.max(1e-12),
            hoses_asleep_mean: asleep_sum as f64 / taken.max(1) as f64,
            hand_force_peak_n: peak,
            stopped: diverged,
        },
        presettle,
    ))
}

pub fn run(quick: bool, progress: bool) -> Result<EngineBayBench> {
    let tessellation = Tessellation::new(quick);
    let start = Instant::now();
    let model = Arc::new(model(&tessellation)?);
    let build_s = start.elapsed().as_secs_f64();
    let triangles = model
        .environment
        .parts
        .iter()
        .map(|p| p.mesh.indices().len())
        .sum();
    let mut rows = Vec::new();
    let mut presettle_s = 0.0;
    let mut abandoned = false;
    for solver in SolverKind::ALL {
        for sleeping in [false, true] {
            if progress {
                eprintln!(
                    "measuring the engine bay: {} solver, sleeping {} …",
                    solver.name(),
                    if sleeping { "on" } else { "off" }
                );
            }
            if abandoned {
                rows.push(not_measured(solver, sleeping));
                continue;
            }
            // each case in a thread of its own: a static step that follows a snap by
            // dynamic relaxation cannot be interrupted, so an overrunning case is left
            // behind (it ends with the process) and reported from its progress so far
            let partial = Arc::new(Mutex::new(Partial::default()));
            let (tx, rx) = mpsc::channel();
            let (m, p) = (model.clone(), partial.clone());
            std::thread::spawn(move || {
                let _ = tx.send(case(&m, solver, sleeping, quick, &p));
            });
            let budget = Duration::from_secs_f64(3.0 * if quick { 2.0 } else { WALL_CAP });
            match rx.recv_timeout(budget) {
                Ok(result) => {
                    let (row, presettle) = result?;
                    if rows.is_empty() {
                        presettle_s = presettle;
                    }
                    rows.push(row);
                }
                Err(_) => {
                    let why = format!(
                        "no result within {:.0} s of wall time: a step of this solver overran \
                         (the static solver follows a snap past a limit point by dynamic \
                         relaxation); the cases after it are not measured, so that it \
                         does not slow them",
                        budget.as_secs_f64()
                    );
                    let p = *partial.lock().unwrap_or_else(PoisonError::into_inner);
                    let sim = p.taken as f64 * p.time_step;
                    rows.push(EngineBayRow {
                        solver: solver.name(),
                        sleeping,
                        simulated_s: sim,
                        steps: p.taken,
                        time_step_s: p.time_step,
                        wall_s: p.wall,
                        realtime_factor: if p.wall > 0.0 { sim / p.wall } else { 0.0 },
                        cpu_s: 0.0,
                        realtime_factor_cpu: 0.0,
                        hoses_asleep_mean: p.asleep_sum as f64 / p.taken.max(1) as f64,
                        hand_force_peak_n: p.peak,
                        stopped: Some(why),
                    });
                    abandoned = true;
                }
            }
        }
    }
    Ok(EngineBayBench {
        hoses: HOSES,
        elements: model.elements.len(),
        triangles,
        tessellation,
        build_s,
        presettle_s,
        rows,
        quick,
    })
}

/// A row for a case left out after an overrun.
fn not_measured(solver: SolverKind, sleeping: bool) -> EngineBayRow {
    EngineBayRow {
        solver: solver.name(),
        sleeping,
        simulated_s: 0.0,
        steps: 0,
        time_step_s: 0.0,
        wall_s: 0.0,
        realtime_factor: 0.0,
        cpu_s: 0.0,
        realtime_factor_cpu: 0.0,
        hoses_asleep_mean: 0.0,
        hand_force_peak_n: 0.0,
        stopped: Some("not measured: an earlier case overran its wall-time budget".into()),
    }
}

/// Text lines for the human-readable report.
pub fn render(b: &EngineBayBench) -> String {
    let mut s = format!(
        "\nEngine bay: {} hoses, {} elements, {} part triangles (built in {:.2} s; static pre-settle {:.2} s), one hand routing one hose{}:\n",
        b.hoses,
        b.elements,
        b.triangles,
        b.build_s,
        b.presettle_s,
        if b.quick { "; --quick: coarse parts, no settle" } else { "" }
    );
    s.push_str("  solver    sleeping  Δt [ms]  steps  simulated [s]  wall [s]  real-time factor  (by CPU)  hoses asleep  peak hand force [N]\n");
    for r in &b.rows {
        s.push_str(&format!(
            "  {:<9} {:<9} {:>7.4} {:>6} {:>14.3} {:>9.3} {:>17.3} {:>9.3} {:>13.1} {:>20.2}\n",
            r.solver,
            if r.sleeping { "on" } else { "off" },
            r.time_step_s * 1e3,
            r.steps,
            r.simulated_s,
            r.wall_s,
            r.realtime_factor,
            r.realtime_factor_cpu,
            r.hoses_asleep_mean,
            r.hand_force_peak_n
        ));
        if let Some(d) = &r.stopped {
            s.push_str(&format!("      stopped early: {d}\n"));
        }
    }
    s
}
