//! `pliant export DIR [--out OUT] [--solver S] [--kbl FILE]`: the settled, installed route
//! of an imported harness back to CAD (SPEC N3). `DIR` is what `pliant import
//! harness.kbl --out DIR` wrote (`scene.toml`, `harness.json`); the scene's timeline runs
//! (by default the harness held at its fixings and connectors, then at rest), and each
//! segment's settled centre line — its hose's nodes — goes into `OUT/harness.kbl` (a copy
//! of the original KBL with the new centre curves, node positions and lengths) and
//! `OUT/harness.step` (one named curve per segment, AP214).

use anyhow::{anyhow, bail, Context, Result};
use pliant_core::SolverKind;
use pliant_harness::{export_kbl, export_step, SettledHarness, StepNames};
use pliant_scene::load_scene_file_with;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The options of `pliant export`.
pub struct ExportOptions<'a> {
    pub dir: &'a Path,
    pub out: Option<&'a Path>,
    pub solver: Option<SolverKind>,
    pub kbl: Option<&'a Path>,
    /// The settling run is refused when planned beyond this many steps.
    pub max_steps: u64,
}

/// Which hose carries which KBL segment, and where the KBL came from (`harness.json`).
struct Sidecar {
    source: PathBuf,
    segments: Vec<(String, String)>,
}

fn read_sidecar(path: &Path) -> Result<Sidecar> {
    let text = pliant_files::read_regular_text(path, 64 * 1024 * 1024).map_err(|e| anyhow!(e))?;
    let v: serde_json::Value =
        serde_json::from_str(&text).with_context(|| format!("{}: not JSON", path.display()))?;
    let field = |name: &str| {
        anyhow!(
            "{}: no `{name}` (not written by `pliant import`?)",
            path.display()
        )
    };
    let source = v["source"].as_str().ok_or_else(|| field("source"))?;
    let mut segments = Vec::new();
    for (k, s) in v["segments"]
        .as_array()
        .ok_or_else(|| field("segments"))?
        .iter()
        .enumerate()
    {
        let (Some(id), Some(hose)) = (s["kbl_id"].as_str(), s["hose"].as_str()) else {
            bail!("{}: segments[{k}] lacks kbl_id or hose", path.display());
        };
        segments.push((id.to_string(), hose.to_string()));
    }
    Ok(Sidecar {
        source: PathBuf::from(source),
        segments,
    })
}

/// Runs the scene, then writes the settled route as KBL and STEP.
pub fn run(o: &ExportOptions) -> Result<ExitCode> {
    let scene_path = o.dir.join("scene.toml");
    let sidecar = read_sidecar(&o.dir.join("harness.json"))?;
    let original = o
        .kbl
        .map(Path::to_path_buf)
        .unwrap_or(sidecar.source.clone());
    if !original.is_file() {
        bail!(
            "the original KBL {} is not there; give it with --kbl FILE",
            original.display()
        );
    }
    let scene = load_scene_file_with(&scene_path, &pliant_runs::load_options())
        .map_err(|e| anyhow!("{e}"))?;
    eprintln!(
        "settling {} ({} segments, {} junctions) …",
        scene_path.display(),
        scene.world.hoses.len(),
        scene.junctions.len()
    );
    let (cell, summary) =
        pliant_runs::run_within(&scene, o.solver, o.max_steps).map_err(|e| anyhow!(e))?;
    for s in summary.settles.iter().filter(|s| !s.at_rest) {
        eprintln!(
            "warning: not at rest after the settle of action {} (t = {:.2} s, residual {:.2e} N, {:.2e} N·m, kinetic energy {:.2e} J); exporting the route as it is",
            s.action, s.time, s.residual_force, s.residual_moment, s.kinetic_energy
        );
    }
    let model = cell.model();
    let state = cell.state();
    let mut settled = SettledHarness::new();
    for (id, hose) in &sidecar.segments {
        let Some(info) = model.hoses.iter().find(|h| &h.name == hose) else {
            bail!("harness.json names hose {hose} (segment {id}), which the scene lacks");
        };
        settled.insert(id.clone(), info.nodes().map(|i| state.x[i]).collect());
    }
    let out = o
        .out
        .map(Path::to_path_buf)
        .unwrap_or_else(|| o.dir.join("export"));
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    let kbl =
        export_kbl(&original, &settled, &out.join("harness.kbl")).map_err(|e| anyhow!("{e}"))?;
    let product = original
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "harness".into());
    let step = export_step(
        &settled,
        &StepNames::new(product),
        &out.join("harness.step"),
    )
    .map_err(|e| anyhow!("{e}"))?;
    print!("{kbl}");
    println!(
        "{}: {} curve(s), {} point(s)",
        step.out.display(),
        step.curves,
        step.points
    );
    Ok(ExitCode::SUCCESS)
}
