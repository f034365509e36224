//! The bounded fuzz run of the test command: for every target,
//! `PROPTEST_CASES` inputs (default 1 000; deterministic, so every run of the tests
//! tries the same inputs — the long job `pliant-fuzz` tries new ones), each a seed with
//! one to eight edits. A failure is shrunk to a small input and printed; proptest keeps
//! it in `proptest-regressions/` and tries it first from then on. Finds fixed so far
//! are pinned by the named tests below.

use pliant_fuzz::mutate::{apply, Op};
use pliant_fuzz::targets::Target;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn op() -> impl Strategy<Value = Op> {
    (any::<u8>(), any::<u32>(), any::<u32>()).prop_map(|(k, a, b)| Op::from_parts(k, a, b))
}

/// Runs `target` on mutated seeds; panics (with the shrunk input) on a find.
fn fuzz(target: Target) {
    let seeds = target.seeds();
    let others: Vec<&[u8]> = seeds.iter().map(Vec::as_slice).collect();
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(1000);
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    // a fixed seed: the same inputs on every machine and every run
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[target as u8 + 1; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let strategy = (0..seeds.len(), prop::collection::vec(op(), 1..8));
    let result = runner.run(&strategy, |(seed, ops)| {
        let input = apply(&seeds[seed], &ops, &others);
        let outcome = std::panic::catch_unwind(|| target.run(&input));
        match outcome {
            Ok(Ok(())) => Ok(()),
            Ok(Err(broken)) => Err(TestCaseError::fail(format!(
                "{}: {broken}\ninput: {:?}",
                target.name(),
                String::from_utf8_lossy(&input)
            ))),
            Err(_) => Err(TestCaseError::fail(format!(
                "{}: panicked\ninput: {:?}",
                target.name(),
                String::from_utf8_lossy(&input)
            ))),
        }
    });
    if let Err(e) = result {
        panic!("{e}");
    }
}

#[test]
fn fuzz_scene_toml() {
    fuzz(Target::SceneToml);
}

#[test]
fn fuzz_scene_json() {
    fuzz(Target::SceneJson);
}

#[test]
fn fuzz_obj() {
    fuzz(Target::Obj);
}

#[test]
fn fuzz_stl() {
    fuzz(Target::Stl);
}

#[test]
fn fuzz_gltf() {
    fuzz(Target::Gltf);
}

#[test]
fn fuzz_protocol() {
    fuzz(Target::Protocol);
}

#[test]
fn fuzz_session_log() {
    fuzz(Target::SessionLog);
}

#[test]
fn fuzz_calibration_spec() {
    fuzz(Target::CalibrationSpec);
}

#[test]
fn fuzz_calibration_csv() {
    fuzz(Target::CalibrationCsv);
}

#[test]
fn fuzz_kbl() {
    fuzz(Target::Kbl);
}

#[test]
fn fuzz_study() {
    fuzz(Target::Study);
}

#[test]
fn every_seed_passes_its_target() {
    for t in Target::ALL {
        for (k, s) in t.seeds().iter().enumerate() {
            assert_eq!(t.run(s), Ok(()), "{} seed {k}", t.name());
        }
    }
}
