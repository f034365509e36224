//! A fixed number of steps of the contact benchmark's world (5 hoses × 30 on the
//! 100 352-triangle floor, `pliant bench --only contact`), or of any other bench world
//! (e.g. `1000 0 1500 1 1000`: the "1 hose × 1000" row), for profilers and instruction
//! counts (`valgrind --tool=callgrind`), where the bench's timed repeats would vary:
//!
//! ```sh
//! cargo run --release -p pliant --example contact_steps -- [steps] [floor quads, 0: none] [warm-up steps] [hoses] [elements per hose] [floor motion: 1 = it sways as in the bench's moving rows, 2 = it glides at 0.05 m/s, 3 = it sways through the warm-up and is then frozen in its pose there, the bench's frozen row] [sleeping: 1 = on, the hoses free; 2 = on, the hoses free and lying straight on a flat floor; 3 = the same, sleeping off]
//! ```
//!
//! Prints the CPU time of the steps (and per element-step), the candidate-list counters,
//! the hose-contact pair-list rebuilds and a hash of the final positions and velocities'
//! bits (a change that must keep the results bit for bit keeps the hash).

#![allow(dead_code)]

use pliant_core::integrators::explicit;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let steps: u64 = args.get(1).map_or(Ok(16_500), |s| s.parse())?;
    let quads: usize = args.get(2).map_or(Ok(bench::FLOOR_QUADS), |s| s.parse())?;
    let warm: u64 = args.get(3).map_or(Ok(1_500), |s| s.parse())?;
    let hoses: usize = args.get(4).map_or(Ok(5), |s| s.parse())?;
    let elements: usize = args.get(5).map_or(Ok(30), |s| s.parse())?;
    let motion = match args.get(6).map(String::as_str) {
        Some("1") | Some("3") => Some(bench::floor_sway()),
        Some("2") => Some(floor_glide()),
        _ => None,
    };
    let sleeping = args.get(7).map_or("0", String::as_str);
    let (mut model, mut state) = if sleeping == "2" || sleeping == "3" {
        lying_on_flat_floor(hoses, elements, quads, motion)?
    } else {
        bench::setup_moving(hoses, elements, quads, motion)?
    };
    model.threads = 1;
    if sleeping == "1" || sleeping == "2" {
        // sleeping on, the hoses' first nodes let go: they come to rest on the floor,
        // and sleep (carried by it when it moves)
        state.loads = Default::default();
        state.sleep.enabled = true;
    }
    if sleeping == "3" {
        state.loads = Default::default();
    }
    run(&model, &mut state, warm);
    if args.get(6).map(String::as_str) == Some("3") {
        (model, state) =
            bench_contact_phases::freeze_floor(&model, &state, quads, &bench::floor_sway())?;
    }
    let before = state.contact.candidates.clone();
    let rebuilds = state.hose_contact.rebuilds;
    let t0 = cpu_seconds();
    let points = measured(&model, &mut state, steps);
    let cpu = cpu_seconds() - t0;
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    for v in state.x.iter().chain(state.v.iter()) {
        for c in v.to_array() {
            hash = (hash ^ c.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
    }
    let c = &state.contact.candidates;
    let (refreshes, truncations, fallbacks) = (
        c.refreshes - before.refreshes,
        c.truncations - before.truncations,
        c.fresh_fallbacks - before.fresh_fallbacks,
    );
    println!(
        "{steps} steps of {hoses} × {elements} on {} triangles: {:.2} µs CPU per step \
         ({:.1} ns per element-step), {:.2} contact points per step, {} refreshes, \
         {} truncations, {} fresh fallbacks, {} pair-list rebuilds, {} hoses asleep \
         ({} carried), hash {hash:016x}",
        2 * quads * quads,
        cpu * 1e6 / steps as f64,
        cpu * 1e9 / (steps as f64 * model.elements.len() as f64),
        points as f64 / steps as f64,
        refreshes,
        truncations,
        fallbacks,
        state.hose_contact.rebuilds - rebuilds,
        state.sleep.sleeping(),
        (0..model.hoses.len())
            .filter(|&h| state.sleep.carried.part_of_hose(h).is_some())
            .count(),
    );
    Ok(())
}

/// The measured steps, alone in this function for
/// `valgrind --tool=callgrind --collect-atstart=no --toggle-collect=contact_steps::measured`.
#[inline(never)]
fn measured(model: &pliant_core::Model, state: &mut pliant_core::State, steps: u64) -> usize {
    std::hint::black_box(run(model, state, std::hint::black_box(steps)))
}

/// `steps` steps; returns the contact points summed over the steps.
#[inline(never)]
fn run(model: &pliant_core::Model, state: &mut pliant_core::State, steps: u64) -> usize {
    let mut points = 0;
    for _ in 0..steps {
        explicit::step(model, state);
        points += state.contact.points.len();
    }
    points
}

/// The bench's hoses lying straight at rest on a flat floor of `2·quads²` triangles (the
/// bench floor's area, 3 cm down) moving by `motion`: at rest on it from the start, they
/// fall asleep after [`pliant_core::sleep::SLEEP_AFTER_STEPS`] steps (carried by it when it
/// moves, [`pliant_core::sleep::carried`]).
fn lying_on_flat_floor(
    hoses: usize,
    elements: usize,
    quads: usize,
    motion: Option<pliant_core::kinematics::PartMotion>,
) -> anyhow::Result<(pliant_core::Model, pliant_core::State)> {
    let mut world = bench::world_with_floor(hoses, elements, 0)?;
    let mut floor = bench::grid_floor(quads, |_, _| -0.03);
    floor.motion = motion;
    world.rigid_parts = vec![floor];
    let model = pliant_core::Model::build(&world)?;
    let mut state = pliant_core::State::at_rest(&model);
    for (x, r) in state.x.iter_mut().zip(&model.radius) {
        x.z = -0.03 + r;
    }
    Ok((model, state))
}

/// User + system CPU time of this process \[s\].
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|s| s.parse::<f64>().ok()).unwrap_or(0.0);
    // fields 14 and 15 of /proc/pid/stat (utime, stime), counted after the ')' from 3
    (ticks(11) + ticks(12)) / 100.0
}

// the bench's own world, as `pliant bench` builds it
#[path = "../src/bench.rs"]
mod bench;
#[path = "../src/bench_contact_phases.rs"]
mod bench_contact_phases;
#[path = "../src/bench_engine_bay.rs"]
mod bench_engine_bay;
#[path = "../src/bench_harness.rs"]
mod bench_harness;
#[path = "../src/bench_hose_contact.rs"]
mod bench_hose_contact;
#[path = "../src/bench_newton.rs"]
mod bench_newton;
#[path = "../src/bench_snapshot.rs"]
mod bench_snapshot;
#[path = "../src/bench_worker.rs"]
mod bench_worker;

/// The floor gliding along x at a constant 0.05 m/s: a moving part without the sway's
/// accelerations, whose contacts in its own frame are, once friction has brought the hoses
/// to its speed, those of the floor at rest (Galilean invariance) — but the hoses on it
/// cannot sleep.
fn floor_glide() -> pliant_core::kinematics::PartMotion {
    pliant_core::kinematics::PartMotion::Slide(pliant_core::kinematics::Slide {
        direction: glam::DVec3::X,
        distance: pliant_core::kinematics::Profile::UniformAcceleration {
            start_time: 0.0,
            initial_rate: 0.05,
            acceleration: 0.0,
        },
    })
}
