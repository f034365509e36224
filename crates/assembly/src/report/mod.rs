//! The outputs of a study, the same whichever shell ran it (`pliant run`, `pliant
//! replay`, a live session's report, Python): the recorder's CSV time series and VTK
//! frames, `fasteners.csv`, `report.json` and `report.html` with the verdict,
//! `summary.json`, and a range-of-motion study's `motion.csv` and swept envelopes
//! (`envelope-<hose>.stl`).

pub mod drawing;
mod envelope_section;
pub mod html;
pub mod part_outline;
mod profile_plot;
pub mod recorder;
mod scene_picture;
pub mod summary;
mod svg;
mod sweep_plots;
mod vtk;
mod worker_picture;
pub mod worker_section;

pub use drawing::Drawing;
pub use html::write_reports;
pub use recorder::{HandSample, Recorder};
pub use summary::{
    final_state, peak_rows, FinalHose, OtherStop, PeakRow, StopReason, Stopped, Summary,
};

use crate::ergonomics::ErgonomicProfile;
use crate::workcell::{RunSummary, Verdict};
use pliant_core::{Model, SolverKind, State};
use std::path::Path;

/// Writes `value` as pretty JSON to `path`, streamed through a buffer (never the whole
/// text in memory); the error names the file.
pub(crate) fn write_json(path: &Path, value: &impl serde::Serialize) -> std::io::Result<()> {
    use std::io::Write as _;
    let named = |e: std::io::Error| {
        std::io::Error::new(e.kind(), format!("writing {}: {e}", path.display()))
    };
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).map_err(named)?);
    serde_json::to_writer_pretty(&mut file, value).map_err(|e| named(e.into()))?;
    file.flush().map_err(named)
}

/// Writes `text` to `path`; the error names the file.
pub(crate) fn write_file(path: &Path, text: String) -> std::io::Result<()> {
    std::fs::write(path, text)
        .map_err(|e| std::io::Error::new(e.kind(), format!("writing {}: {e}", path.display())))
}

/// What a finished study hands to [`write_outputs`].
pub struct Outputs<'a> {
    pub scene_name: &'a str,
    pub source: &'a str,
    pub model: &'a Model,
    pub state: &'a State,
    pub run: &'a RunSummary,
    /// Why the study stopped early, if it did.
    pub diverged: Option<&'a Stopped>,
    /// The recorder's hand samples.
    pub hand_series: &'a [HandSample],
    pub profile: &'a ErgonomicProfile,
    pub solver: SolverKind,
    /// The step the solver advanced by \[s\].
    pub time_step: f64,
    /// Wall-clock time the study took \[s\] (for the real-time factor).
    pub wall_time: f64,
    /// The worker's posed instants (`worker.csv`; empty without a worker).
    pub worker_series: &'a [crate::worker::WorkerSample],
}

/// Writes `fasteners.csv`, `report.json`, `report.html` and `summary.json` into `out`
/// (which must exist; the recorder has written the time series there) and returns the
/// verdict and the summary.
pub fn write_outputs(out: &Path, o: &Outputs) -> std::io::Result<(Verdict, Summary)> {
    let run = o.run;
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
    write_file(&out.join("fasteners.csv"), csv)?;
    write_file(&out.join("checks.csv"), checks_csv(&run.checks))?;
    write_file(&out.join("check_profiles.csv"), profiles_csv(&run.checks))?;
    if run.worker.is_some() {
        write_file(
            &out.join("worker.csv"),
            worker_section::worker_csv(o.worker_series),
        )?;
    }
    if let Some(sweep) = &run.checks.sweep {
        write_file(&out.join("motion.csv"), sweep.csv())?;
    }
    // Presentation data, made here once per report: a hull over every vertex of every
    // part, the swept envelopes (never on the live path).
    let drawing = Drawing::of(o.model, run);
    let verdict = write_reports(
        out,
        o.scene_name,
        run,
        &drawing,
        o.diverged.map(|s| s.message.as_str()),
        o.hand_series,
        o.profile,
        o.worker_series,
    )?;
    let summary = Summary {
        pliant_version: env!("CARGO_PKG_VERSION"),
        scene: o.scene_name.to_string(),
        source: o.source.to_string(),
        completed: o.diverged.is_none(),
        diverged: o.diverged.cloned(),
        steps: run.steps,
        simulated_time_s: run.simulated_time,
        time_step_s: o.time_step,
        time_step: o.model.time_step_report.clone(),
        solver: o.solver.name(),
        wall_time_s: o.wall_time,
        realtime_factor: run.simulated_time / o.wall_time.max(1e-9),
        elements: o.model.elements.len(),
        actions_completed: run.actions_completed,
        settles: run.settles.clone(),
        newton: run.solver.clone(),
        warnings: run
            .solver_warnings
            .iter()
            .map(ToString::to_string)
            .collect(),
        peaks: peak_rows(o.model, run),
        final_state: final_state(o.model, o.state),
        worker: run.worker.as_ref().map(|w| summary::WorkerReport {
            findings: w.findings(),
            summary: w.clone(),
        }),
        envelopes: drawing.envelopes,
    };
    write_json(&out.join("summary.json"), &summary)?;
    Ok((verdict, summary))
}

/// `checks.csv`: one row per violation of an installation check (SPEC V3), SI units.
fn checks_csv(checks: &crate::checks::ChecksSummary) -> String {
    let mut csv = String::from(
        "check,hose,arc_length_m,time_s,value,limit,unit,first_time_s,last_time_s,instants,stub\n",
    );
    for v in &checks.violations {
        csv.push_str(&format!(
            "{},{},{:.6},{:.6},{:.6e},{:.6e},{},{:.6},{:.6},{},{}\n",
            v.check.name(),
            v.hose_name.replace(',', ";"),
            v.arc_length,
            v.time,
            v.value,
            v.limit,
            v.check.unit(),
            v.first_time,
            v.last_time,
            v.instants,
            v.at.as_deref().unwrap_or("").replace(',', ";"),
        ));
    }
    csv
}

/// `check_profiles.csv`: per hose and beam, the curvature at the instant of the hose's
/// smallest bend radius and the twist (relative to the routed hose) at the instant of
/// its largest twist, with their limits.
fn profiles_csv(checks: &crate::checks::ChecksSummary) -> String {
    let mut csv = String::from(
        "hose,arc_length_m,curvature_1_m,curvature_time_s,allowed_curvature_1_m,twist_rad_m,twist_time_s,twist_limit_rad_m\n",
    );
    for p in &checks.profiles {
        for (k, s) in p.arc_length.iter().enumerate() {
            let allowed = p.allowed_curvature.get(k).copied().unwrap_or(0.0);
            csv.push_str(&format!(
                "{},{s:.6},{:.6e},{:.6},{:.6e},{:.6e},{:.6},{:.6e}\n",
                p.hose_name.replace(',', ";"),
                p.curvature[k],
                p.min_bend_radius_time,
                allowed,
                p.twist[k],
                p.max_twist_time,
                p.twist_limit,
            ));
        }
    }
    csv
}

/// Replays an input log into `cell` (a fresh workcell of the log's scene and options)
/// with a recorder sampling every `record_interval` seconds into `out`, and writes the
/// outputs, as `pliant run` does for a timeline: the report of a live session
/// (SPEC W2). `observer` also sees the replay (progress display).
pub fn replay_with_outputs(
    out: &Path,
    mut cell: crate::Workcell,
    log: &crate::workcell::log::InputLog,
    scene_name: &str,
    record_interval: f64,
    observer: &mut dyn crate::Observer,
) -> Result<(Verdict, Summary), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("creating {}: {e}", out.display()))?;
    let planned = log.end_tick as f64 * cell.time_step();
    let model = cell.model().clone();
    let mut recorder = Recorder::create(out, &model, record_interval, planned)
        .map_err(|e| format!("creating output files in {}: {e}", out.display()))?;
    let started = std::time::Instant::now();
    let outcome = {
        let mut both = Both(&mut recorder, observer);
        crate::workcell::replay::replay(&mut cell, &log.inputs, log.end_tick, &mut both)
    };
    let wall = started.elapsed().as_secs_f64();
    let hand_series = recorder
        .finish(&model, cell.state())
        .map_err(|e| format!("writing outputs: {e}"))?;
    let diverged = match &outcome {
        Ok(()) => cell.diverged().map(Stopped::diverged),
        Err(crate::workcell::replay::ReplayError::Diverged(d)) => Some(Stopped {
            message: outcome.as_ref().unwrap_err().to_string(),
            ..Stopped::diverged(d)
        }),
        Err(
            e @ (crate::workcell::replay::ReplayError::Refused { index, .. }
            | crate::workcell::replay::ReplayError::Late { index, .. }),
        ) => Some(Stopped::other(
            OtherStop::ReplayRefused { input: *index },
            e.to_string(),
        )),
    };
    let mut run = cell.summary();
    run.actions_completed = log.inputs.len();
    let outputs = Outputs {
        scene_name,
        source: &log.header.scene_source,
        model: &model,
        state: cell.state(),
        run: &run,
        diverged: diverged.as_ref(),
        hand_series: &hand_series,
        profile: cell.profile(),
        solver: cell.solver().kind(),
        time_step: cell.time_step(),
        wall_time: wall,
        worker_series: cell.worker_series(),
    };
    write_outputs(out, &outputs).map_err(|e| e.to_string())
}

/// Two observers as one (the first one's wishes decide the sampling).
pub struct Both<'a>(
    pub &'a mut dyn crate::Observer,
    pub &'a mut dyn crate::Observer,
);

impl crate::Observer for Both<'_> {
    fn wants_state(&self, time: f64) -> bool {
        self.0.wants_state(time) || self.1.wants_state(time)
    }
    fn on_state(&mut self, model: &Model, state: &State) {
        self.0.on_state(model, state);
        self.1.on_state(model, state);
    }
    fn on_action(&mut self, index: usize, action: &crate::Action, state: &State) {
        self.0.on_action(index, action, state);
        self.1.on_action(index, action, state);
    }
    fn on_step(&mut self, time: f64) {
        self.0.on_step(time);
        self.1.on_step(time);
    }
    fn on_hands(&mut self, time: f64, hands: &[crate::HandRecord]) {
        self.0.on_hands(time, hands);
        self.1.on_hands(time, hands);
    }
}
