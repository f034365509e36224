//! `pliant calibrate`: fits a material's stiffnesses to measured test curves (SPEC M5,
//! D3; docs/calibration.md) and writes material.toml, library_entry.toml,
//! calibration.json and calibration.html; for a bundle (`--kind bundle`), a protection's
//! coupling factor (bundle.toml, calibration.json, calibration.html).

use anyhow::{anyhow, bail};
use comfy_table::{presets::UTF8_FULL_CONDENSED, Table};
use pliant_calibrate::material_entry::num;
use pliant_calibrate::{Spec, TestKind, TestSpec};
use pliant_harness::bundle_calibration::{
    calibrate_bundle, calibrate_bundle_file, is_bundle_spec, BundleSpec, FORMAT_TAG,
};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The bundle's options of one test given on the command line (`--kind bundle`).
pub struct BundleArgs<'a> {
    /// `three_point_bending` or `cantilever`.
    pub bending_test: &'a str,
    pub kbl: Option<&'a Path>,
    pub segment: Option<&'a str>,
    pub protection: Option<&'a str>,
}

/// One test given on the command line instead of a calibration file.
pub struct OneTest<'a> {
    pub kind: Option<&'a str>,
    pub bundle: BundleArgs<'a>,
    pub csv: Option<&'a Path>,
    pub length_mm: Option<f64>,
    pub d_inner_mm: f64,
    pub d_outer_mm: Option<f64>,
    pub name: &'a str,
    pub density_kg_m3: f64,
    pub poisson: Option<f64>,
    /// Relaxation: Prony terms and the held strain.
    pub terms: Option<usize>,
    pub held_strain: Option<f64>,
}

/// The folder of `csv` (its CSV path is relative to it) and its file name.
fn split_csv(csv: &Path) -> anyhow::Result<(PathBuf, String)> {
    let base = csv
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."));
    let file = csv
        .file_name()
        .ok_or_else(|| anyhow!("--csv {}: not a file", csv.display()))?
        .to_string_lossy()
        .to_string();
    Ok((base, file))
}

/// Whether the file at `path` is a bundle calibration ("pliant-bundle-calibration").
fn is_bundle_file(path: &Path) -> bool {
    pliant_files::read_regular_text(path, pliant_calibrate::MAX_FILE_BYTES)
        .is_ok_and(|text| is_bundle_spec(&text))
}

/// `pliant calibrate` of a bundle: from a file, or from `--kind bundle` and its options.
fn run_bundle(
    spec: Option<&Path>,
    one: &OneTest,
    out: &Path,
    json: bool,
) -> anyhow::Result<ExitCode> {
    let calibration = match spec {
        Some(path) => calibrate_bundle_file(path).map_err(|e| anyhow!(e))?,
        None => {
            let b = &one.bundle;
            let Some(csv) = one.csv else {
                bail!("--kind bundle needs --csv (the bending test's force_N,deflection_mm curve)");
            };
            let Some(length) = one.length_mm else {
                bail!("--kind bundle needs --length: the span (three_point_bending) or free length (cantilever) [mm]");
            };
            let (Some(kbl), Some(segment)) = (b.kbl, b.segment) else {
                bail!("--kind bundle needs --kbl FILE and --segment ID (the tested bundle's wires); a wire list goes in a calibration file (docs/calibration.md, Bundles)");
            };
            let kind = TestKind::parse(b.bending_test).ok_or_else(|| {
                anyhow!(
                    "--bending-test {}: expected three_point_bending or cantilever",
                    b.bending_test
                )
            })?;
            let (base, file) = split_csv(csv)?;
            let kbl =
                std::path::absolute(kbl).map_err(|e| anyhow!("--kbl {}: {e}", kbl.display()))?;
            let spec = BundleSpec {
                format: FORMAT_TAG.to_string(),
                kind,
                csv: file,
                length_mm: length,
                protection: b.protection.map(str::to_string),
                kbl: Some(kbl.display().to_string()),
                segment: Some(segment.to_string()),
                wires: Vec::new(),
            };
            let origin = format!(
                "the command line (--kind bundle --csv {} --kbl {} --segment {segment})",
                csv.display(),
                kbl.display()
            );
            calibrate_bundle(spec, &base, &origin).map_err(|e| anyhow!(e))?
        }
    };
    let paths = calibration.write(out).map_err(|e| anyhow!(e))?;
    if json {
        println!("{}", serde_json::to_string_pretty(&calibration.json())?);
        return Ok(ExitCode::SUCCESS);
    }
    let f = &calibration.fit;
    let t = &calibration.test;
    let r = &t.range;
    println!(
        "bundle {} ({} wires), {} test, linear range rows {}–{} of {}, R² {:.5}",
        calibration.bundle,
        f.wire_count,
        t.kind.name(),
        r.first_row + 1,
        r.last_row + 1,
        r.total_points,
        t.line.r_squared
    );
    println!(
        "{} = {} N·m² (95 % CI {} – {}) between the slip bound {} and the bonded bound {}",
        f.stiffness.symbol(),
        num(f.measured),
        num(t.ci95[0]),
        num(t.ci95[1]),
        num(f.slip),
        num(f.bond)
    );
    println!(
        "protection {}: {} = {} (95 % CI {} – {})",
        f.key(),
        f.stiffness.factor(),
        num(f.factor),
        num(calibration.factor_ci95[0]),
        num(calibration.factor_ci95[1])
    );
    for p in &paths {
        println!("  {}", p.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// The fitted laws: one row per parameter with its 95 % interval, and each fit's
/// residual.
fn law_table(laws: &[pliant_calibrate::LawFit]) -> Table {
    let mut table = Table::new();
    table.load_preset(UTF8_FULL_CONDENSED);
    table.set_header(vec![
        "law test",
        "csv",
        "parameter (SI)",
        "95 % CI",
        "points",
        "residual std",
    ]);
    for f in laws {
        for (i, e) in f.fit.estimates.iter().enumerate() {
            let first = i == 0;
            table.add_row(vec![
                if first {
                    f.kind.name().to_string()
                } else {
                    String::new()
                },
                if first { f.csv.clone() } else { String::new() },
                format!("{} = {}", e.name, num(e.value)),
                format!("{} – {}", num(e.ci95[0]), num(e.ci95[1])),
                if first {
                    f.fit.points.to_string()
                } else {
                    String::new()
                },
                if first {
                    format!(
                        "{} {}",
                        num(f.fit.residual_std * f.y_scale),
                        f.y_label
                            .rsplit('[')
                            .next()
                            .unwrap_or("")
                            .trim_end_matches(']')
                    )
                } else {
                    String::new()
                },
            ]);
        }
    }
    table
}

pub fn run(spec: Option<&Path>, one: &OneTest, out: &Path, json: bool) -> anyhow::Result<ExitCode> {
    if spec.is_some() && (one.kind.is_some() || one.csv.is_some()) {
        bail!("give either a calibration file or --kind and --csv, not both");
    }
    if one.kind == Some("bundle") || spec.is_some_and(is_bundle_file) {
        return run_bundle(spec, one, out, json);
    }
    if one.bundle.kbl.is_some() || one.bundle.segment.is_some() || one.bundle.protection.is_some() {
        bail!("--kbl, --segment and --protection are for --kind bundle");
    }
    if spec.is_some() && (one.terms.is_some() || one.held_strain.is_some()) {
        bail!("--terms and --held-strain are for one relaxation test on the command line; in a calibration file they are the test's terms and held_strain");
    }
    let calibration = match spec {
        Some(path) => pliant_calibrate::calibrate_file(path).map_err(|e| anyhow!(e))?,
        None => {
            let (Some(kind), Some(csv)) = (one.kind, one.csv) else {
                bail!("give a calibration file (docs/calibration.md) or --kind and --csv for one test");
            };
            let kind = TestKind::parse(kind).ok_or_else(|| {
                let names: Vec<&str> = TestKind::ALL.iter().map(|k| k.name()).collect();
                anyhow!(
                    "--kind {kind}: expected one of {}, bundle",
                    names.join(", ")
                )
            })?;
            let Some(d_outer) = one.d_outer_mm else {
                bail!("--d-outer (mm) is needed: the specimen's outer diameter");
            };
            let (base, file) = split_csv(csv)?;
            let spec = Spec {
                format: None,
                name: one.name.to_string(),
                description: None,
                d_inner_mm: one.d_inner_mm,
                d_outer_mm: d_outer,
                density_kg_m3: one.density_kg_m3,
                density_source: None,
                poisson: one.poisson,
                min_bend_radius_mm: None,
                tests: vec![TestSpec {
                    kind,
                    csv: file,
                    length_mm: one.length_mm,
                    d_inner_mm: None,
                    d_outer_mm: None,
                    terms: one.terms,
                    held_strain: one.held_strain,
                }],
            };
            let origin = format!(
                "the command line (--kind {} --csv {})",
                kind.name(),
                csv.display()
            );
            pliant_calibrate::calibrate(spec, &base, &origin).map_err(|e| anyhow!(e))?
        }
    };
    let paths = calibration.write(out).map_err(|e| anyhow!(e))?;
    if json {
        println!("{}", serde_json::to_string_pretty(&calibration.json())?);
        return Ok(ExitCode::SUCCESS);
    }
    let mut table = Table::new();
    table.load_preset(UTF8_FULL_CONDENSED);
    table.set_header(vec![
        "test",
        "csv",
        "stiffness",
        "95 % CI",
        "linear range",
        "residual RMS",
        "R²",
    ]);
    for f in &calibration.fits {
        let r = &f.range;
        table.add_row(vec![
            f.kind.name().to_string(),
            f.csv.clone(),
            format!("{} = {} {}", f.symbol, num(f.value_display), f.unit),
            format!("{} – {}", num(f.ci95_display[0]), num(f.ci95_display[1])),
            format!(
                "rows {}–{} of {}: {} {}–{}",
                r.first_row + 1,
                r.last_row + 1,
                r.total_points,
                r.x_label,
                num(r.x_from),
                num(r.x_to)
            ),
            format!(
                "{} {}",
                num(f.line.residual_rms * f.curve.y_scale),
                r.y_label
                    .rsplit('[')
                    .next()
                    .unwrap_or("")
                    .trim_end_matches(']')
            ),
            format!("{:.5}", f.line.r_squared),
        ]);
    }
    if !calibration.fits.is_empty() {
        println!("{table}");
    }
    if !calibration.laws.is_empty() {
        println!("{}", law_table(&calibration.laws));
        for f in &calibration.laws {
            for c in &f.checks {
                println!("{} {}: {c}", f.kind.name(), f.csv);
            }
        }
    }
    for w in &calibration.material.warnings {
        println!("warning: {w}");
    }
    println!("material \"{}\":", calibration.material.name);
    for p in &paths {
        println!("  {}", p.display());
    }
    Ok(ExitCode::SUCCESS)
}
