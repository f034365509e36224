//! `pliant replay SESSION [--out DIR] [--timeline FILE] [--up-to-damage]`: replays a
//! session's input log (SPEC W2) on a fresh workcell of its scene — bit for bit the
//! session — and writes the same outputs as `pliant run`; `--timeline` also writes the
//! log as an ordinary scene file whose timeline re-enacts it.
//!
//! A damaged log is refused, naming the line and what would be lost
//! (exit 2); `--up-to-damage` replays it up to the damaged line, says so in the output
//! and `summary.json` (`log_damage`) and exits 4. A last line torn by a writer killed
//! mid-line is no damage: the log replays up to it, and the tear is said (`log_torn_tail`).

use crate::progress::Progress;
use crate::run_cmd::{add_to_summary, print_outcome};
use anyhow::{anyhow, bail, Context};
use pliant_assembly::report::replay_with_outputs;
use pliant_assembly::workcell::log::log_path;
use pliant_runs::session::Session;
use std::path::Path;
use std::process::ExitCode;

/// Exit code of a replay of a damaged log up to its damage.
pub const EXIT_REPLAYED_UP_TO_DAMAGE: u8 = 4;

pub fn run(
    session: &Path,
    out: Option<&Path>,
    timeline: Option<&Path>,
    up_to_damage: bool,
    quiet: bool,
    max_steps: u64,
) -> anyhow::Result<ExitCode> {
    let s = Session::open_up_to_damage(session).map_err(|e| anyhow!(e))?;
    let shown = log_path(session).display().to_string();
    if let Some(d) = &s.damage {
        if !up_to_damage {
            bail!("{shown}: {d}; `pliant replay --up-to-damage` replays the log up to the damaged line");
        }
        eprintln!("pliant: warning: {shown}: {d}; replaying up to the damage (--up-to-damage)");
    }
    if let Some(t) = &s.torn_tail {
        eprintln!(
            "pliant: note: {shown}: the last line (line {}, {} bytes) was cut short by a writer stopped mid-line; replaying up to the line before it",
            t.line, t.bytes
        );
    }
    if !s.sealed {
        eprintln!(
            "pliant: note: {shown} is a version 1 log without checksums: a changed line is found only where it breaks the log's form"
        );
    }
    let cell = s.workcell().map_err(|e| anyhow!(e))?;
    pliant_scene::budget::check_step_count(s.log.end_tick, cell.time_step(), max_steps).map_err(
        |e| {
            anyhow!(
                "{shown}: replaying to its last tick {}: {e}",
                s.log.end_tick
            )
        },
    )?;
    if let Some(path) = timeline {
        let text = pliant_runs::session::log_to_scene(&s.scene, &s.log, cell.time_step())
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
    if let Some(d) = &s.damage {
        let note = serde_json::json!({
            "line": d.line,
            "reason": d.reason,
            "replayed_to_tick": d.readable_to,
            "inputs_lost": d.inputs_after,
            "last_tick_lost": d.last_tick_after,
        });
        add_to_summary(out, "log_damage", note).context("writing summary.json")?;
    }
    if let Some(t) = &s.torn_tail {
        let note = serde_json::json!({ "line": t.line, "bytes": t.bytes });
        add_to_summary(out, "log_torn_tail", note).context("writing summary.json")?;
    }
    print_outcome(&verdict, &summary, out);
    if let Some(stopped) = &summary.diverged {
        eprintln!("error: {}", stopped.message);
        return Ok(ExitCode::from(3));
    }
    if let Some(d) = &s.damage {
        eprintln!(
            "error: the log is damaged at line {}: the outputs hold the session up to tick {} only ({} input(s) after it lost)",
            d.line, d.readable_to, d.inputs_after
        );
        return Ok(ExitCode::from(EXIT_REPLAYED_UP_TO_DAMAGE));
    }
    Ok(ExitCode::SUCCESS)
}
