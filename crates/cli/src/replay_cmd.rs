//! `pliant replay SESSION [--out DIR] [--timeline FILE]`: replays a session's input log
//! (SPEC W2) on a fresh workcell of its scene — bit for bit the session — and writes the
//! same outputs as `pliant run`; `--timeline` also writes the log as an ordinary scene
//! file whose timeline re-enacts it.

use crate::progress::Progress;
use crate::run_cmd::print_outcome;
use anyhow::{anyhow, Context};
use pliant_assembly::report::replay_with_outputs;
use pliant_scene::session::Session;
use std::path::Path;
use std::process::ExitCode;

pub fn run(
    session: &Path,
    out: Option<&Path>,
    timeline: Option<&Path>,
    quiet: bool,
) -> anyhow::Result<ExitCode> {
    let s = Session::open(session).map_err(|e| anyhow!(e))?;
    let cell = s.workcell().map_err(|e| anyhow!(e))?;
    if let Some(path) = timeline {
        let text = pliant_scene::session::log_to_scene(&s.scene, &s.log, cell.time_step())
            .map_err(|e| anyhow!(e))?;
        std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?;
        eprintln!(
            "pliant: the session as a scene timeline: {}",
            path.display()
        );
    }
    let default_out = if session.is_dir() {
        session.join("replay")
    } else {
        session.with_extension("replay")
    };
    let out = out.unwrap_or(&default_out);
    eprintln!(
        "pliant: replaying {} input(s) over {} steps of scene '{}'",
        s.log.inputs.len(),
        s.log.end_tick,
        s.scene.name
    );
    let planned = s.log.end_tick as f64 * cell.time_step();
    let mut progress = Progress::new(planned, quiet);
    let result = replay_with_outputs(
        out,
        cell,
        &s.log,
        &s.scene.name,
        s.scene.record_interval,
        &mut progress,
    );
    progress.finish();
    let (verdict, summary) = result.map_err(|e| anyhow!(e))?;
    print_outcome(&verdict, &summary, out);
    if let Some(msg) = &summary.diverged {
        eprintln!("error: {msg}");
        return Ok(ExitCode::from(3));
    }
    Ok(ExitCode::SUCCESS)
}
