//! The main harness settled in its installed state, then `updates` updates of a hand
//! moving back and forth in 2 mm steps (`pliant bench --harness`'s world and motion,
//! `bench_harness::hand_offset`; `pulled` as an argument: the middle of the longest
//! segment dragged 2 mm further each update, the bench's pulled-hard row), printing each update's wall time,
//! Newton iterations and load steps — for profilers, where the bench reports a median:
//!
//! ```sh
//! cargo run --release -p pliant --example harness_updates -- [updates] [chain] [pulled]
//! ```
//!
//! With `chain` as the second argument the world is the bench's single chain of as many
//! elements instead. To profile the updates alone, start `perf record` disabled with a
//! control fifo and name the fifo in `PERF_CTL_FIFO`; the example enables it after the
//! settle:
//!
//! ```sh
//! mkfifo /tmp/perf.ctl
//! PERF_CTL_FIFO=/tmp/perf.ctl perf record -g -D -1 --control=fifo:/tmp/perf.ctl \
//!     target/release/examples/harness_updates 200
//! ```

#![allow(dead_code)]

use glam::DVec3;
use pliant_assembly::{Grip, Input, NoObserver};
use std::time::Instant;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let updates: usize = args.get(1).map_or(Ok(30), |s| s.parse())?;
    let chain = args.iter().skip(2).any(|s| s == "chain");
    let pulled = args.iter().skip(2).any(|s| s == "pulled");
    let offset = if pulled {
        bench_harness::pulled_offset
    } else {
        bench_harness::hand_offset
    };
    let harness = bench_harness::import_main_harness()?;
    let scene = if chain {
        let (cell, _) = bench_harness::settled(&harness)?;
        let length: f64 = cell.model().elements.iter().map(|e| e.rest_length).sum();
        bench_harness::chain(cell.model().elements.len(), length)?
    } else {
        harness
    };
    let t0 = Instant::now();
    let (mut cell, _) = bench_harness::settled(&scene)?;
    eprintln!(
        "settled in {:.2} s; pair-list skin {:.2} mm",
        t0.elapsed().as_secs_f64(),
        cell.model().hose_contact.skin * 1e3
    );
    let (at, direction) = if chain {
        (cell.state().x[20], DVec3::Y)
    } else if pulled {
        bench_harness::middle_of_longest(&cell)
    } else {
        bench_harness::grab_point(&cell)
    };
    let grabbed = (0..cell.state().x.len())
        .min_by(|&a, &b| {
            let x = &cell.state().x;
            x[a].distance(at).total_cmp(&x[b].distance(at))
        })
        .unwrap_or(0);
    eprintln!("the hand grabs node {grabbed}");
    cell.apply(Input::Grab {
        hand: 1,
        at,
        grip: Grip::Firm,
    })
    .map_err(|r| anyhow::anyhow!("{r:?}"))?;
    let step = cell.time_step();
    if let Some(fifo) = std::env::var_os("PERF_CTL_FIFO") {
        std::fs::write(fifo, "enable\n")?;
    }
    for k in 1..=updates {
        cell.apply(Input::MoveHand {
            hand: 1,
            waypoints: vec![at + direction * offset(k)],
            rotation: DVec3::ZERO,
            duration: step,
        })
        .map_err(|r| anyhow::anyhow!("{r:?}"))?;
        let rebuilds = cell.state().hose_contact.rebuilds;
        let reused = cell.solver().factorizations_reused();
        let cpu = bench::thread_cpu_seconds();
        let start = Instant::now();
        cell.step(&mut NoObserver)
            .map_err(|d| anyhow::anyhow!("update {k} diverged: {d}"))?;
        let s = cell.solver().last;
        let contact = &cell.state().hose_contact;
        let wall = start.elapsed().as_secs_f64() * 1e3;
        let cpu = (bench::thread_cpu_seconds() - cpu) * 1e3;
        println!(
            "update {k}: {wall:.2} ms ({cpu:.2} ms CPU), {} iterations, {} load steps, \
             {} factorisations reused, {} pair-list rebuilds, {} candidate pairs, {} in contact, \
             residual {:.3e} N (limit {:.3e} N), hand force {:.2} N",
            s.iterations,
            s.substeps,
            cell.solver().factorizations_reused() - reused,
            contact.rebuilds - rebuilds,
            contact.candidates.len(),
            contact.pairs_in_contact,
            s.residual_force,
            s.force_limit,
            cell.state().reaction_force[grabbed].length(),
        );
    }
    // a change that must keep the results bit for bit keeps this hash
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    for v in cell.state().x.iter() {
        for c in v.to_array() {
            hash = (hash ^ c.to_bits()).wrapping_mul(0x0100_0000_01b3);
        }
    }
    println!("hash of the final positions {hash:016x}");
    Ok(())
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
