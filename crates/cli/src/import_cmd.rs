//! `pliant import FILE.step`: converts a STEP assembly once with OpenCASCADE (see
//! `pliant_runs::cad_converter`) into the cache entry a scene beside it will read
//! (`.pliant-cache/` in the STEP file's folder, or `--cache-dir`), or into a plain GLB
//! (`--out`, usable as `mesh = "…"`: all solids as one part), and prints what it read.

use anyhow::{anyhow, bail, Context, Result};
use pliant_runs::cad_converter::{converter_id, import_step, MAX_STEP_BYTES};
use pliant_scene::glb_solids::{glb_facts, read_glb_solids};
use pliant_scene::route::unit_scale;
use pliant_scene::step_cache::{mesh_cache_name, DEFAULT_CHORD_TOLERANCE};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// The options of `pliant import`.
pub struct ImportOptions<'a> {
    pub step: &'a Path,
    pub out: Option<&'a Path>,
    pub cache_dir: Option<&'a Path>,
    pub tolerance: Option<&'a str>,
    /// KBL: import only the branch beyond this node or segment.
    pub branch: Option<&'a str>,
    /// KBL: the bundle model's data (TOML) instead of the built-in.
    pub bundle_data: Option<&'a Path>,
    /// KBL: write the protections' default friction between the wires.
    pub bundle_friction: bool,
}

/// A length such as "0.5mm", "0.02 in", "0.0005m"; a bare number is millimetres.
pub fn parse_length(text: &str) -> Result<f64> {
    let t = text.trim();
    let split = t
        .find(|c: char| {
            !(c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+')
        })
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let value: f64 = number
        .parse()
        .map_err(|_| anyhow!("\"{text}\" is not a length (e.g. 0.5mm, 0.02in)"))?;
    let scale = if unit.trim().is_empty() {
        1e-3
    } else {
        unit_scale(unit).ok_or_else(|| {
            anyhow!(
                "unknown unit \"{}\" in \"{text}\"; use mm, cm, m or in",
                unit.trim()
            )
        })?
    };
    let metres = value * scale;
    if !(metres.is_finite() && metres > 0.0) {
        bail!("\"{text}\": the tolerance must be a positive length");
    }
    Ok(metres)
}

/// Whether `path` names harness data (KBL or VEC) rather than STEP.
fn is_harness_file(path: &Path) -> bool {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    matches!(ext.as_str(), "kbl" | "vec" | "xml")
}

/// `pliant import harness.kbl [--out DIR]`: the harness as a scene (see
/// `pliant_harness::import_kbl`); prints what was imported, skipped and assumed.
fn run_harness(o: &ImportOptions) -> Result<ExitCode> {
    if o.cache_dir.is_some() || o.tolerance.is_some() {
        bail!("--cache-dir and --tolerance are for STEP files; a harness takes --out DIR only");
    }
    let out = o.out.map(Path::to_path_buf).unwrap_or_else(|| {
        let stem = o
            .step
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "harness".into());
        o.step.with_file_name(stem)
    });
    let bundle = match o.bundle_data {
        Some(path) => {
            let text = pliant_files::read_regular_text(path, 16 * 1024 * 1024)
                .map_err(|e| anyhow!("{}: cannot read: {}", path.display(), e.kind.into_io()))?;
            pliant_harness::bundle::BundleData::from_toml(&text)
                .map_err(|e| anyhow!("{}: {e}", path.display()))?
        }
        None => pliant_harness::bundle::BundleData::builtin(),
    };
    let options = pliant_harness::ImportOptions {
        branch: o.branch.map(str::to_owned),
        bundle,
        bundle_friction: o.bundle_friction,
        ..Default::default()
    };
    let report =
        pliant_harness::import_kbl_opts(o.step, &out, &options).map_err(|e| anyhow!("{e}"))?;
    print!("{report}");
    println!(
        "run it: pliant run {}   inspect it: pliant inspect {}",
        report.scene.display(),
        report.scene.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// Runs the import; prints the solids, triangles, skipped solids and the time taken.
pub fn run(o: &ImportOptions) -> Result<ExitCode> {
    if is_harness_file(o.step) {
        return run_harness(o);
    }
    if o.branch.is_some() {
        bail!("--branch is for harness files (KBL); a STEP assembly has no branches");
    }
    if o.bundle_data.is_some() || o.bundle_friction {
        bail!("--bundle-data and --bundle-friction are for harness files (KBL); a STEP assembly has no bundles");
    }
    let tolerance = match o.tolerance {
        Some(t) => parse_length(t).context("--tolerance")?,
        None => DEFAULT_CHORD_TOLERANCE,
    };
    let bytes = pliant_files::read_regular_file(o.step, MAX_STEP_BYTES).map_err(|e| anyhow!(e))?;
    let out: PathBuf = match (o.out, o.cache_dir) {
        (Some(_), Some(_)) => bail!("give either --out or --cache-dir, not both"),
        (Some(out), None) => out.to_path_buf(),
        (None, dir) => {
            let dir = dir
                .map(Path::to_path_buf)
                .unwrap_or_else(|| o.step.parent().map(Path::to_path_buf).unwrap_or_default());
            let name = o
                .step
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            // the entry a scene in `dir` naming the file finds (the key ignores the folder)
            dir.join(mesh_cache_name(&name, &bytes, tolerance, converter_id()))
        }
    };
    if let Some(parent) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    let started = Instant::now();
    import_step(o.step, &out, tolerance).map_err(|e| anyhow!("{}: {e}", o.step.display()))?;
    let seconds = started.elapsed().as_secs_f64();
    let glb = std::fs::read(&out).with_context(|| format!("reading {}", out.display()))?;
    let (facts, triangles) = glb_facts(&glb).map_err(|e| anyhow!(e))?;
    let solids = read_glb_solids(&glb).map_err(|e| anyhow!(e))?;
    println!(
        "{}: {} solid(s), {} triangles at chord tolerance {} mm, file unit {}, {:.2} s ({:.2} s reading and tessellating)",
        o.step.display(),
        solids.len(),
        triangles,
        tolerance * 1e3,
        if facts.file_units.is_empty() { "?".to_string() } else { facts.file_units.join(", ") },
        seconds,
        facts.seconds
    );
    for s in &solids {
        println!("  {} ({} triangles)", s.name, s.mesh.triangles.len());
    }
    for s in &facts.skipped {
        eprintln!("warning: skipped {s}");
    }
    println!("wrote {}", out.display());
    Ok(ExitCode::SUCCESS)
}
