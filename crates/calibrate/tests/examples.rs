//! The example calibration in examples/calibration/ (synthetic curves with known
//! answers) recovers its answers. Regenerate the files with
//! `PLIANT_WRITE_EXAMPLES=1 cargo test --release -p pliant-calibrate --test examples`.

use pliant_calibrate::synthetic::{example_files, Truth};
use std::path::Path;

/// Noise (relative to each curve's largest value) and seed of the shipped example.
const NOISE: f64 = 0.002;
const SEED: u64 = 1;

fn folder() -> &'static Path {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/calibration"
    ))
}

#[test]
fn the_example_recovers_its_known_stiffness() {
    let truth = Truth::EXAMPLE;
    if std::env::var_os("PLIANT_WRITE_EXAMPLES").is_some() {
        std::fs::create_dir_all(folder()).unwrap();
        let (files, _) = example_files(&truth, NOISE, SEED);
        for (name, text) in files {
            std::fs::write(folder().join(name), text).unwrap();
        }
    }
    let c = pliant_calibrate::calibrate_file(&folder().join("hose.toml")).unwrap();
    let want = [
        truth.e_tension,
        truth.e_compression,
        truth.ei(),
        truth.gj(),
        truth.ei(),
    ];
    assert_eq!(c.fits.len(), want.len());
    for (f, w) in c.fits.iter().zip(want) {
        let rel = (f.value - w) / w;
        eprintln!(
            "{:>20}: {} = {:.6e} (truth {w:.6e}, error {:+.3} %), 95 % CI [{:.6e}, {:.6e}] {}, range rows {}-{}",
            f.kind.name(),
            f.symbol,
            f.value,
            100.0 * rel,
            f.ci95[0],
            f.ci95[1],
            if f.ci95[0] <= w && w <= f.ci95[1] { "covers" } else { "MISSES" },
            f.range.first_row,
            f.range.last_row
        );
        assert!(rel.abs() < 0.01, "{:?}: {} vs {w}", f.kind, f.value);
    }
    let m = &c.material;
    assert!((m.e_tension_mpa.value - 11.583).abs() < 0.1);
    assert!((m.poisson.value - 0.45).abs() < 0.02);
}
