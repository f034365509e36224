//! A fixed number of steps of the bench's single-hose world (`pliant bench`, row
//! "1 hose × 1000" by default), for profilers and instruction counts
//! (`valgrind --tool=callgrind`), where the bench's timed repeats would vary:
//!
//! ```sh
//! cargo run --release -p pliant --example single_hose_steps -- [elements] [steps] [warm-up steps]
//! ```
//!
//! Prints the CPU time per element-step, the hose-contact pair-list rebuilds and a hash of
//! the final positions and velocities' bits (a change that must keep the results bit for
//! bit keeps the hash).

#![allow(dead_code)]

use pliant_core::integrators::explicit;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let elements: usize = args.get(1).map_or(Ok(1000), |s| s.parse())?;
    let steps: u64 = args.get(2).map_or(Ok(18_000), |s| s.parse())?;
    let warm: u64 = args.get(3).map_or(Ok(1_500), |s| s.parse())?;
    let (mut model, mut state) = bench::setup(1, elements, 0)?;
    model.threads = 1;
    run(&model, &mut state, warm);
    let rebuilds = state.hose_contact.rebuilds;
    let t0 = cpu_seconds();
    measured(&model, &mut state, steps);
    let cpu = cpu_seconds() - t0;
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    for v in state.x.iter().chain(state.v.iter()) {
        for c in v.to_array() {
            hash = (hash ^ c.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
    }
    println!(
        "{steps} steps of 1 hose × {elements}: {:.2} ns CPU per element-step, {} pair-list \
         rebuilds, hash {hash:016x}",
        cpu * 1e9 / (steps as f64 * elements as f64),
        state.hose_contact.rebuilds - rebuilds,
    );
    Ok(())
}

/// The measured steps, alone in this function for
/// `valgrind --tool=callgrind --collect-atstart=no --toggle-collect=single_hose_steps::measured`.
#[inline(never)]
fn measured(model: &pliant_core::Model, state: &mut pliant_core::State, steps: u64) {
    run(model, state, std::hint::black_box(steps));
    std::hint::black_box(&state.x);
}

#[inline(never)]
fn run(model: &pliant_core::Model, state: &mut pliant_core::State, steps: u64) {
    for _ in 0..steps {
        explicit::step(model, state);
    }
}

/// User + system CPU time of this process [s].
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
#[path = "../src/bench_engine_bay.rs"]
mod bench_engine_bay;
#[path = "../src/bench_newton.rs"]
mod bench_newton;
