//! Records a run: node poses, support reactions and energies as CSV at the scene's record
//! interval, VTK frames for ParaView, and a progress bar. Only states that passed the
//! divergence check reach it, so no NaN is ever written.

use crate::vtk::VtkSeries;
use indicatif::{ProgressBar, ProgressStyle};
use pliant_assembly::{Action, Observer};
use pliant_core::loads::LoadCase;
use pliant_core::{Model, State};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

pub struct Recorder {
    nodes: BufWriter<File>,
    reactions: BufWriter<File>,
    energy: BufWriter<File>,
    vtk: VtkSeries,
    interval: f64,
    next_time: f64,
    vtk_interval: f64,
    next_vtk: f64,
    progress: ProgressBar,
    steps_seen: u64,
    last_written: Option<f64>,
    error: Option<std::io::Error>,
    /// Global node → (hose index, local node), built once.
    node_owner: Vec<(usize, usize)>,
}

impl Recorder {
    /// Creates the output files in `out`. `planned` is the timeline's planned duration.
    pub fn create(
        out: &Path,
        model: &Model,
        interval: f64,
        planned: f64,
        quiet: bool,
    ) -> std::io::Result<Self> {
        let open = |name: &str| File::create(out.join(name)).map(BufWriter::new);
        let mut nodes = open("nodes.csv")?;
        writeln!(nodes, "time_s,hose,node,x_m,y_m,z_m,qw,qx,qy,qz")?;
        let mut reactions = open("reactions.csv")?;
        writeln!(
            reactions,
            "time_s,hose,node,kind,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm"
        )?;
        let mut energy = open("energy.csv")?;
        writeln!(energy, "time_s,kinetic_j,strain_j,gravity_j")?;
        let progress = if quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::new((planned * 1000.0).ceil() as u64)
        };
        progress.set_style(
            ProgressStyle::with_template(
                "{spinner} [{bar:40}] {pos}/{len} ms simulated ({elapsed}) {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        let mut node_owner = vec![(0, 0); model.node_count()];
        for (h, info) in model.hoses.iter().enumerate() {
            for (k, g) in info.nodes().enumerate() {
                node_owner[g] = (h, k);
            }
        }
        Ok(Recorder {
            nodes,
            reactions,
            energy,
            vtk: VtkSeries::create(&out.join("vtk"))?,
            interval,
            next_time: 0.0,
            // at most ~200 VTK frames per run
            vtk_interval: interval.max(planned / 200.0),
            next_vtk: 0.0,
            progress,
            steps_seen: 0,
            last_written: None,
            error: None,
            node_owner,
        })
    }

    fn write(&mut self, model: &Model, state: &State) -> std::io::Result<()> {
        let t = state.time;
        for (g, &(h, k)) in self.node_owner.iter().enumerate() {
            let (x, q) = (state.x[g], state.q[g]);
            writeln!(
                self.nodes,
                "{t:.6},{h},{k},{:.9},{:.9},{:.9},{:.9},{:.9},{:.9},{:.9}",
                x.x, x.y, x.z, q.w, q.x, q.y, q.z
            )?;
        }
        for (_, case) in state.loads.iter() {
            let kind = match case {
                LoadCase::Fix(_) => "fix",
                LoadCase::Drive(_) => "drive",
                LoadCase::DeadLoad(_) => continue,
            };
            let g = case.node();
            let (h, k) = self.node_owner[g];
            let (f, m) = (state.reaction_force[g], state.reaction_moment[g]);
            writeln!(
                self.reactions,
                "{t:.6},{h},{k},{kind},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}",
                f.x, f.y, f.z, m.x, m.y, m.z
            )?;
        }
        let (ke, se, ge) = (
            state.kinetic_energy(model),
            state.strain_energy(model),
            state.gravity_energy(model),
        );
        writeln!(self.energy, "{t:.6},{ke:.6e},{se:.6e},{ge:.6e}")?;
        if t + 1e-12 >= self.next_vtk {
            self.vtk.frame(model, state)?;
            self.next_vtk = t + self.vtk_interval;
        }
        self.last_written = Some(t);
        Ok(())
    }

    /// Records the final state and flushes everything.
    pub fn finish(mut self, model: &Model, state: &State) -> std::io::Result<()> {
        self.progress.finish_and_clear();
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        if self.last_written != Some(state.time) {
            self.next_vtk = 0.0; // the final state always gets a VTK frame
            self.write(model, state)?;
        }
        self.nodes.flush()?;
        self.reactions.flush()?;
        self.energy.flush()?;
        self.vtk.finish()
    }
}

impl Observer for Recorder {
    fn wants_state(&self, time: f64) -> bool {
        time + 1e-12 >= self.next_time
    }

    fn on_state(&mut self, model: &Model, state: &State) {
        if self.error.is_some() {
            return;
        }
        if let Err(e) = self.write(model, state) {
            self.error = Some(e);
        }
        self.next_time = if self.interval > 0.0 {
            state.time + self.interval
        } else {
            0.0
        };
    }

    fn on_action(&mut self, index: usize, action: &Action, _state: &State) {
        let name = format!("{action:?}");
        let short = name.split([' ', '{', '(']).next().unwrap_or("").to_string();
        self.progress
            .set_message(format!("action {}: {short}", index + 1));
    }

    fn on_step(&mut self, time: f64) {
        self.steps_seen += 1;
        if self.steps_seen % 512 == 0 {
            self.progress.set_position((time * 1000.0) as u64);
        }
    }
}
