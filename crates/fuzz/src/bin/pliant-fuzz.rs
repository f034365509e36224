//! The long fuzz job: `pliant-fuzz [--inputs N]
//! [--target NAME] [--seed S] [--hang-seconds T]` runs N inputs per target (default
//! 1 000 000) made from the seeds by random edits, reports inputs per second, the
//! slowest input, the process's peak memory and every find — a broken property, a panic,
//! or an input slower than T seconds (default 10: a hang) — and writes each finding
//! input to `fuzz-finds/<target>-<k>.bin` to become a regression test. An abort (an
//! allocation failure, a stack overflow) ends the process with the signal; the inputs
//! are a function of the seed, so the same command reproduces it. Exit code 1 if
//! anything was found.

use pliant_fuzz::mutate::{apply, Rng};
use pliant_fuzz::targets::Target;
use std::time::Instant;

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1).cloned())
    };
    let inputs: u64 = value("--inputs")
        .and_then(|v| v.parse().ok())
        .unwrap_or(1_000_000);
    let hang_seconds: f64 = value("--hang-seconds")
        .and_then(|v| v.parse().ok())
        .unwrap_or(10.0);
    let seed: u64 = value("--seed")
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x5eed);
    let targets: Vec<Target> = match value("--target") {
        Some(name) => match Target::named(&name) {
            Some(t) => vec![t],
            None => {
                eprintln!(
                    "unknown target {name}; one of {}",
                    Target::ALL.map(Target::name).join(", ")
                );
                return std::process::ExitCode::from(2);
            }
        },
        None => Target::ALL.to_vec(),
    };
    // a find's panic message is reported once, below, not by the default hook
    std::panic::set_hook(Box::new(|_| {}));
    let mut finds = 0u64;
    for target in targets {
        let seeds = target.seeds();
        let others: Vec<&[u8]> = seeds.iter().map(Vec::as_slice).collect();
        let mut rng = Rng::new(seed ^ (target as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let started = Instant::now();
        let mut found = 0u64;
        let mut slowest = 0.0f64;
        for k in 0..inputs {
            let s = &seeds[rng.next_u64() as usize % seeds.len()];
            let ops = rng.ops(8);
            let input = apply(s, &ops, &others);
            let one = Instant::now();
            let outcome = std::panic::catch_unwind(|| target.run(&input));
            let took = one.elapsed().as_secs_f64();
            slowest = slowest.max(took);
            let what = match outcome {
                Ok(Ok(())) if took > hang_seconds => Some(format!("took {took:.1} s (a hang)")),
                Ok(Ok(())) => None,
                Ok(Err(broken)) => Some(broken),
                Err(_) => Some("panicked".to_string()),
            };
            if let Some(what) = what {
                found += 1;
                let _ = std::fs::create_dir_all("fuzz-finds");
                let file = format!("fuzz-finds/{}-{k}.bin", target.name());
                let _ = std::fs::write(&file, &input);
                eprintln!("{}: input {k}: {what} (saved as {file})", target.name());
            }
            if (k + 1) % 100_000 == 0 {
                let rate = (k + 1) as f64 / started.elapsed().as_secs_f64();
                eprintln!("{}: {} inputs, {rate:.0}/s", target.name(), k + 1);
            }
        }
        let secs = started.elapsed().as_secs_f64();
        println!(
            "{}: {inputs} inputs in {secs:.1} s ({:.0}/s), slowest {:.3} s, peak memory {}, {found} finds",
            target.name(),
            inputs as f64 / secs,
            slowest,
            peak_memory()
        );
        finds += found;
    }
    if finds == 0 {
        std::process::ExitCode::SUCCESS
    } else {
        std::process::ExitCode::from(1)
    }
}

/// The process's peak resident memory so far (Linux: `VmHWM`), for the report.
fn peak_memory() -> String {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("VmHWM:").map(|v| v.trim().to_string()))
        })
        .unwrap_or_else(|| "unknown".to_string())
}
