//! `pliant run [SCENE] [--out DIR]`: load a scene, run its timeline, write the outputs.

use crate::recorder::Recorder;
use crate::report::write_reports;
use crate::summary::{final_state, peak_rows, peak_table, Summary};
use anyhow::{anyhow, Context};
use pliant_assembly::ergonomics::ErgonomicProfile;
use pliant_assembly::Runner;
use pliant_core::{Model, SolverKind, State};
use pliant_scene::{demo_scene, load_scene_file};
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

pub fn run(
    scene_path: Option<&Path>,
    out: &Path,
    quiet: bool,
    ergonomics: Option<&str>,
    solver: Option<SolverKind>,
) -> anyhow::Result<ExitCode> {
    let scene = match scene_path {
        Some(p) => load_scene_file(p)?,
        None => demo_scene()?,
    };
    let model = Model::build(&scene.world)
        .and_then(|m| m.with_stiffened_spans(&scene.stiffened_spans()))
        .with_context(|| format!("building the model of {}", scene.source))?;
    std::fs::create_dir_all(out)
        .with_context(|| format!("creating output folder {}", out.display()))?;
    let elements = model.elements.len();
    eprintln!(
        "pliant: scene '{}' ({}): {} hose(s), {} elements, time step {:.3e} s (stable limit {:.3e} s, safety {})",
        scene.name,
        scene.source,
        model.hoses.len(),
        elements,
        model.time_step,
        model.time_step_report.critical,
        model.time_step_report.safety
    );
    let planned = Runner::planned_duration(&scene.timeline);
    let mut recorder = Recorder::create(out, &model, scene.record_interval, planned, quiet)
        .with_context(|| format!("creating output files in {}", out.display()))?;
    let mut state = State::at_rest(&model);
    let started = Instant::now();
    // the command line's profile, if given, overrides the scene's [ergonomics]
    let profile: ErgonomicProfile = match ergonomics {
        Some(text) => text
            .parse()
            .with_context(|| format!("--ergonomics '{text}'"))?,
        None => scene.ergonomics,
    };
    let (stubs, clips) = scene.fastener_sites(&model).map_err(|e| anyhow!(e))?;
    let mut runner = Runner::new(&model);
    if let Some(kind) = solver {
        runner = runner.with_solver(kind);
    }
    let solver_kind = runner.solver().kind();
    let solver_step = runner.solver().time_step(&model);
    if solver_kind != SolverKind::Explicit {
        eprintln!("pliant: solver {solver_kind}, step {solver_step:.3e} s");
    }
    let outcome = runner
        .with_ergonomics(profile)
        .with_fasteners(stubs, clips)
        .run(&scene.timeline, &mut state, &mut recorder);
    let wall = started.elapsed().as_secs_f64();
    let hand_series = recorder.finish(&model, &state).context("writing outputs")?;
    let (run, diverged) = match outcome {
        Ok(run) => (run, None),
        Err(e) => (e.partial.clone(), Some(e.divergence.to_string())),
    };
    let summary = Summary {
        pliant_version: env!("CARGO_PKG_VERSION"),
        scene: scene.name.clone(),
        source: scene.source.clone(),
        completed: diverged.is_none(),
        diverged: diverged.clone(),
        steps: run.steps,
        simulated_time_s: run.simulated_time,
        time_step_s: solver_step,
        time_step: model.time_step_report.clone(),
        solver: solver_kind.name(),
        wall_time_s: wall,
        realtime_factor: run.simulated_time / wall.max(1e-9),
        elements,
        actions_completed: run.actions_completed,
        settles: run.settles.clone(),
        newton_iterations_max: run.newton_iterations_max,
        newton_unconverged_steps: run.newton_unconverged_steps,
        peaks: peak_rows(&model, &run),
        final_state: final_state(&model, &state),
    };
    let verdict = write_reports(
        out,
        &scene.name,
        &run,
        diverged.as_deref(),
        &hand_series,
        &profile,
    )?;
    let write = |name: &str, text: String| {
        let path = out.join(name);
        std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))
    };
    let mut csv = String::from("time_s,kind,name,force_n\n");
    for x in &run.fastener_series {
        let f = &run.fasteners[x.fastener];
        csv.push_str(&format!(
            "{:.6},{},{},{:.6e}\n",
            x.time,
            f.kind,
            f.name.replace(',', ";"),
            x.force
        ));
    }
    write("fasteners.csv", csv)?;
    let word = match verdict.feasible {
        Some(true) => "FEASIBLE",
        Some(false) => "NOT FEASIBLE",
        None => "not assessed",
    };
    println!("verdict: {word}");
    for r in &verdict.reasons {
        println!("  - {r}");
    }
    let path = out.join("summary.json");
    std::fs::write(&path, serde_json::to_string_pretty(&summary)?)
        .with_context(|| format!("writing {}", path.display()))?;
    println!("{}", peak_table(&summary.peaks));
    for s in &summary.settles {
        let word = if s.at_rest {
            "at rest"
        } else {
            "NOT at rest (max duration reached)"
        };
        println!(
            "settle (action {}): {word} at t = {:.3} s, kinetic energy {:.3e} J",
            s.action + 1,
            s.time,
            s.kinetic_energy
        );
    }
    println!(
        "{} steps, {:.3} s simulated in {:.3} s wall ({:.1}× real time); outputs in {}",
        summary.steps,
        summary.simulated_time_s,
        wall,
        summary.realtime_factor,
        out.display()
    );
    if let Some(msg) = diverged {
        eprintln!("error: {msg}\n(outputs hold the run up to the last healthy state)");
        return Ok(ExitCode::from(3));
    }
    Ok(ExitCode::SUCCESS)
}
