//! `pliant run [SCENE] [--out DIR]`: load a scene, run its timeline on the scene's
//! workcell, write the outputs.

use crate::progress::Progress;
use anyhow::{anyhow, Context};
use pliant_assembly::ergonomics::ErgonomicProfile;
use pliant_assembly::report::{write_outputs, Both, Outputs, Recorder, Summary};
use pliant_assembly::{run_timeline, Runner, Verdict, WorkcellOptions};
use pliant_cli::table::peak_table;
use pliant_core::SolverKind;
use pliant_scene::{demo_scene, load_scene_file_with, LoadOptions};
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

pub fn run(
    scene_path: Option<&Path>,
    out: &Path,
    quiet: bool,
    ergonomics: Option<&str>,
    solver: Option<SolverKind>,
    load: &LoadOptions,
) -> anyhow::Result<ExitCode> {
    let scene = match scene_path {
        Some(p) => load_scene_file_with(p, load)?,
        None => demo_scene()?,
    };
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    let mut setup = scene.workcell_setup().map_err(|e| anyhow!(e))?;
    // the command line's profile, if given, overrides the scene's [ergonomics]
    if let Some(text) = ergonomics {
        let profile: ErgonomicProfile = text
            .parse()
            .with_context(|| format!("--ergonomics '{text}'"))?;
        setup.profile = profile;
    }
    let options = WorkcellOptions {
        solver,
        ..Default::default()
    };
    let mut cell = Runner::from_setup(setup, options)
        .workcell()
        .map_err(|e| anyhow!(e))?;
    let model = cell.model().clone();
    std::fs::create_dir_all(out)
        .with_context(|| format!("creating output folder {}", out.display()))?;
    eprintln!(
        "pliant: scene '{}' ({}): {} hose(s), {} elements, time step {:.3e} s (stable limit {:.3e} s, safety {})",
        scene.name,
        scene.source,
        model.hoses.len(),
        model.elements.len(),
        model.time_step,
        model.time_step_report.critical,
        model.time_step_report.safety
    );
    let solver_kind = cell.solver().kind();
    if solver_kind != SolverKind::Explicit {
        eprintln!(
            "pliant: solver {solver_kind}, step {:.3e} s",
            cell.time_step()
        );
    }
    let planned = Runner::planned_duration(&scene.timeline);
    scene
        .check_planned_steps(cell.time_step(), load.limits.max_steps)
        .map_err(|e| anyhow!(e))?;
    eprintln!(
        "pliant: {}",
        cost_hint(
            planned,
            cell.time_step(),
            model.elements.len(),
            solver_kind,
            &scene.estimate
        )
    );
    let mut recorder = Recorder::create(out, &model, scene.record_interval, planned)
        .with_context(|| format!("creating output files in {}", out.display()))?;
    let mut progress = Progress::new(planned, quiet);
    let started = Instant::now();
    let outcome = run_timeline(
        &mut cell,
        &scene.timeline,
        &mut Both(&mut recorder, &mut progress),
    );
    let wall = started.elapsed().as_secs_f64();
    progress.finish();
    let hand_series = recorder
        .finish(&model, cell.state())
        .context("writing outputs")?;
    let (run, stopped) = match outcome {
        Ok(run) => (run, None),
        Err(e) => (
            e.partial.clone(),
            Some((e.stopped.clone(), e.divergence.is_some())),
        ),
    };
    let outputs = Outputs {
        scene_name: &scene.name,
        source: &scene.source,
        model: &model,
        state: cell.state(),
        run: &run,
        diverged: stopped.as_ref().map(|(s, _)| s),
        hand_series: &hand_series,
        profile: cell.profile(),
        solver: solver_kind,
        time_step: cell.time_step(),
        wall_time: wall,
        worker_series: cell.worker_series(),
    };
    let (verdict, summary) = write_outputs(out, &outputs).context("writing outputs")?;
    note_scene_warnings(out, &scene.warnings).context("writing summary.json")?;
    print_outcome(&verdict, &summary, out);
    if !scene.warnings.is_empty() {
        println!("scene warnings (what loading left out, also in summary.json):");
        for w in &scene.warnings {
            println!("  - {w}");
        }
    }
    match stopped {
        Some((s, true)) => {
            eprintln!(
                "error: {}\n(outputs hold the run up to the last healthy state)",
                s.message
            );
            Ok(ExitCode::from(3))
        }
        Some((s, false)) => {
            eprintln!(
                "error: {}\n(outputs hold the run up to that action)",
                s.message
            );
            Ok(ExitCode::from(2))
        }
        None => Ok(ExitCode::SUCCESS),
    }
}

/// The verdict, the peak table and the settles, as `pliant run` and `pliant replay`
/// print them.
pub fn print_outcome(verdict: &Verdict, summary: &Summary, out: &Path) {
    println!("verdict: {}", verdict.word());
    for r in &verdict.reasons {
        println!("  - {r}");
    }
    if !verdict.warnings.is_empty() {
        println!("warnings (do not decide feasibility):");
        for w in &verdict.warnings {
            println!("  - {w}");
        }
    }
    println!("{}", peak_table(&summary.peaks));
    for s in &summary.settles {
        let word = if s.at_rest {
            "at rest"
        } else {
            "NOT at rest (max duration reached)"
        };
        println!(
            "settle (action {}): {word} at t = {:.3} s, residual {:.3e} N, {:.3e} N·m, kinetic energy {:.3e} J",
            s.action + 1,
            s.time,
            s.residual_force,
            s.residual_moment,
            s.kinetic_energy
        );
        if let Some(t) = s.static_solve_time {
            println!("  finished by the static solver from t = {t:.3} s");
        }
    }
    println!(
        "{} steps, {:.3} s simulated in {:.3} s wall ({:.1}× real time); outputs in {}",
        summary.steps,
        summary.simulated_time_s,
        summary.wall_time_s,
        summary.realtime_factor,
        out.display()
    );
}

/// Cost of one explicit step per element on the reference machine (2 shared cores),
/// from `pliant bench` and runs of 10 000–50 000 elements: ≈ 0.6 µs. Only for the hint
/// printed before a run; the progress bar's ETA measures the real rate.
const EXPLICIT_SECONDS_PER_ELEMENT_STEP: f64 = 0.6e-6;

/// What a run will cost, said before it starts: steps, element-steps, memory and, for
/// the explicit solver, a rough time.
fn cost_hint(
    planned: f64,
    step: f64,
    elements: usize,
    solver: SolverKind,
    estimate: &pliant_scene::Estimate,
) -> String {
    let steps = (planned / step).ceil();
    let work = steps * elements as f64;
    let memory = pliant_scene::budget::human_bytes(estimate.memory_bytes());
    let mut text = format!(
        "planned {planned:.2} s simulated: ≈ {steps:.3e} steps × {elements} elements = {work:.2e} element-steps, memory ≈ {memory}"
    );
    if solver == SolverKind::Explicit {
        let seconds = work * EXPLICIT_SECONDS_PER_ELEMENT_STEP;
        text += &format!(", ≈ {} of computing", human_duration(seconds));
        if seconds > 600.0 {
            text += " — long: a larger time_step_safety or fewer elements shortens it; --solver implicit takes 10 ms steps";
        }
    }
    text
}

/// `seconds` as "12 s", "3.5 min" or "2.1 h".
fn human_duration(seconds: f64) -> String {
    if seconds < 90.0 {
        format!("{seconds:.0} s")
    } else if seconds < 5400.0 {
        format!("{:.1} min", seconds / 60.0)
    } else {
        format!("{:.1} h", seconds / 3600.0)
    }
}

/// Adds the scene's load warnings (e.g. STEP solids that could not be read) to
/// `summary.json` as `scene_warnings`, so that they reach every reader of the run.
fn note_scene_warnings(out: &Path, warnings: &[String]) -> anyhow::Result<()> {
    if warnings.is_empty() {
        return Ok(());
    }
    add_to_summary(out, "scene_warnings", serde_json::json!(warnings))
}

/// Adds the member `key` to the `summary.json` written into `out`.
pub(crate) fn add_to_summary(
    out: &Path,
    key: &str,
    value: serde_json::Value,
) -> anyhow::Result<()> {
    let path = out.join("summary.json");
    let text = std::fs::read_to_string(&path)?;
    let mut summary: serde_json::Value = serde_json::from_str(&text)?;
    if let Some(map) = summary.as_object_mut() {
        map.insert(key.to_string(), value);
    }
    std::fs::write(&path, serde_json::to_string_pretty(&summary)?)?;
    Ok(())
}
