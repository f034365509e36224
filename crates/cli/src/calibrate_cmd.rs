//! `pliant calibrate`: fits a material's stiffnesses to measured test curves (SPEC M5,
//! D3; docs/calibration.md) and writes material.toml, library_entry.toml,
//! calibration.json and calibration.html.

use anyhow::{anyhow, bail};
use comfy_table::{presets::UTF8_FULL_CONDENSED, Table};
use pliant_calibrate::material_entry::num;
use pliant_calibrate::{Spec, TestKind, TestSpec};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// One test given on the command line instead of a calibration file.
pub struct OneTest<'a> {
    pub kind: Option<&'a str>,
    pub csv: Option<&'a Path>,
    pub length_mm: Option<f64>,
    pub d_inner_mm: f64,
    pub d_outer_mm: Option<f64>,
    pub name: &'a str,
    pub density_kg_m3: f64,
    pub poisson: Option<f64>,
}

pub fn run(spec: Option<&Path>, one: &OneTest, out: &Path, json: bool) -> anyhow::Result<ExitCode> {
    let calibration = match spec {
        Some(path) => {
            if one.kind.is_some() || one.csv.is_some() {
                bail!("give either a calibration file or --kind and --csv, not both");
            }
            pliant_calibrate::calibrate_file(path).map_err(|e| anyhow!(e))?
        }
        None => {
            let (Some(kind), Some(csv)) = (one.kind, one.csv) else {
                bail!("give a calibration file (docs/calibration.md) or --kind and --csv for one test");
            };
            let kind = TestKind::parse(kind).ok_or_else(|| {
                let names: Vec<&str> = TestKind::ALL.iter().map(|k| k.name()).collect();
                anyhow!("--kind {kind}: expected one of {}", names.join(", "))
            })?;
            let Some(d_outer) = one.d_outer_mm else {
                bail!("--d-outer (mm) is needed: the specimen's outer diameter");
            };
            let base = csv
                .parent()
                .map(Path::to_path_buf)
                .unwrap_or_else(|| PathBuf::from("."));
            let file = csv
                .file_name()
                .ok_or_else(|| anyhow!("--csv {}: not a file", csv.display()))?
                .to_string_lossy()
                .to_string();
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
    println!("{table}");
    for w in &calibration.material.warnings {
        println!("warning: {w}");
    }
    println!("material \"{}\":", calibration.material.name);
    for p in &paths {
        println!("  {}", p.display());
    }
    Ok(ExitCode::SUCCESS)
}
