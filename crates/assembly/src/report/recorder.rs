//! Records a run: node poses, support reactions and energies as CSV at the scene's record
//! interval and VTK frames for ParaView. Only states that passed the
//! divergence check reach it, so no NaN is ever written.

use super::vtk::VtkSeries;
use crate::workcell::{HandRecord, Observer};
use pliant_core::loads::LoadCase;
use pliant_core::{Model, State};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// One hand's load at one recorded time, for the report.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct HandSample {
    pub time: f64,
    pub hand: usize,
    pub force: f64,
    pub torque: f64,
    /// Worst load/limit ratio and the limit it was judged against.
    pub ratio: f64,
    pub limit: f64,
}

impl HandSample {
    /// The sample of hand record `r` at time `t` (ratio and limit of its worst load
    /// kind; 0 when it was not assessed).
    pub fn new(time: f64, r: &HandRecord) -> Self {
        let (ratio, limit) = r
            .assessment
            .as_ref()
            .map_or((0.0, 0.0), |a| (a.worst().ratio, a.worst().limit));
        HandSample {
            time,
            hand: r.hand,
            force: r.load.force.length(),
            torque: r.load.torque.length(),
            ratio,
            limit,
        }
    }
}

pub struct Recorder {
    nodes: BufWriter<File>,
    reactions: BufWriter<File>,
    energy: BufWriter<File>,
    hands: BufWriter<File>,
    contacts: BufWriter<File>,
    colours: BufWriter<File>,
    /// Hand samples kept for the report's plots.
    pub hand_series: Vec<HandSample>,
    /// Colour value per hose at the current record (scratch).
    hose_colour: Vec<f64>,
    vtk: VtkSeries,
    interval: f64,
    next_time: f64,
    vtk_interval: f64,
    next_vtk: f64,
    last_written: Option<f64>,
    error: Option<std::io::Error>,
    /// Global node → (hose index, local node), built once.
    node_owner: Vec<(usize, usize)>,
}

impl Recorder {
    /// Creates the output files in `out`. `planned` is the study's planned duration
    /// (it spaces the VTK frames: at most about 200).
    pub fn create(out: &Path, model: &Model, interval: f64, planned: f64) -> std::io::Result<Self> {
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
        let mut hands = open("hands.csv")?;
        writeln!(
            hands,
            "time_s,hand,hose,x_m,y_m,z_m,fx_n,fy_n,fz_n,tx_nm,ty_nm,tz_nm,force_n,torque_nm,kind,ratio,limit,colour,axial_n,lateral_n,twist_nm,bending_nm"
        )?;
        let mut contacts = open("contacts.csv")?;
        writeln!(contacts, "time_s,hose,node,with,fx_n,fy_n,fz_n")?;
        let mut colours = open("colours.csv")?;
        writeln!(colours, "time_s,hose,colour")?;
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
            hands,
            contacts,
            colours,
            hand_series: Vec::new(),
            hose_colour: vec![0.0; model.hoses.len()],
            vtk: VtkSeries::create(&out.join("vtk"))?,
            interval,
            next_time: 0.0,
            // at most ~200 VTK frames per run
            vtk_interval: interval.max(planned / 200.0),
            next_vtk: 0.0,
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
                LoadCase::Mount(_) => "mount",
                LoadCase::Drive(_) => "drive",
                LoadCase::Support(_) => "support",
                LoadCase::DeadLoad(_) => continue,
                LoadCase::Tie(tie) => {
                    // the tie's pull on each of its two nodes (equal and opposite)
                    let pull = tie.load_in(model, state, 0.0).force;
                    for (g, f) in tie.nodes.into_iter().zip([pull, -pull]) {
                        let (h, k) = self.node_owner[g];
                        writeln!(
                            self.reactions,
                            "{t:.6},{h},{k},tie,{:.6e},{:.6e},{:.6e},0,0,0",
                            f.x, f.y, f.z
                        )?;
                    }
                    continue;
                }
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
        for (g, &(h, k)) in self.node_owner.iter().enumerate() {
            for (with, f) in [
                ("part", state.contact_force[g]),
                ("hose", state.hose_contact_force[g]),
            ] {
                if f != glam::DVec3::ZERO {
                    writeln!(
                        self.contacts,
                        "{t:.6},{h},{k},{with},{:.6e},{:.6e},{:.6e}",
                        f.x, f.y, f.z
                    )?;
                }
            }
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

    /// Hand loads with their ergonomic classification, and the colour value per hose
    /// (SPEC I4: c = min(|f|/f_max, 1) of the hands holding it, 0 for a hose nobody holds).
    fn write_hands(&mut self, t: f64, hands: &[HandRecord]) -> std::io::Result<()> {
        self.hose_colour.fill(0.0);
        for r in hands {
            let (p, f, m) = (r.load.position, r.load.force, r.load.torque);
            let (kind, ratio, limit, colour) = match &r.assessment {
                Some(a) => {
                    let w = a.worst();
                    (w.kind.name(), w.ratio, w.limit, a.colour_value())
                }
                None => ("none", 0.0, 0.0, 0.0),
            };
            let [axial, lateral, twist, bending] = r.assessment.map_or([0.0; 4], |a| {
                [
                    a.axial_force,
                    a.lateral_force,
                    a.twist.magnitude,
                    a.bending.magnitude,
                ]
            });
            writeln!(
                self.hands,
                "{t:.6},{},{},{:.6},{:.6},{:.6},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{kind},{ratio:.4},{limit},{colour:.4},{axial:.6e},{lateral:.6e},{twist:.6e},{bending:.6e}",
                r.hand, r.load.hose, p.x, p.y, p.z, f.x, f.y, f.z, m.x, m.y, m.z, f.length(), m.length()
            )?;
            self.hose_colour[r.load.hose] = self.hose_colour[r.load.hose].max(colour);
            self.hand_series.push(HandSample::new(t, r));
        }
        for (h, c) in self.hose_colour.iter().enumerate() {
            writeln!(self.colours, "{t:.6},{h},{c:.4}")?;
        }
        Ok(())
    }

    /// Records the final state (unless it failed the health check) and flushes
    /// everything.
    /// Returns the hand samples for the report.
    pub fn finish(mut self, model: &Model, state: &State) -> std::io::Result<Vec<HandSample>> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let healthy = pliant_core::health::check(model, state).is_ok();
        if healthy && self.last_written != Some(state.time) {
            self.next_vtk = 0.0; // the final state always gets a VTK frame
            self.write(model, state)?;
        }
        self.nodes.flush()?;
        self.reactions.flush()?;
        self.energy.flush()?;
        self.hands.flush()?;
        self.contacts.flush()?;
        self.colours.flush()?;
        self.vtk.finish()?;
        Ok(std::mem::take(&mut self.hand_series))
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

    fn on_hands(&mut self, time: f64, hands: &[HandRecord]) {
        if self.error.is_some() {
            return;
        }
        if let Err(e) = self.write_hands(time, hands) {
            self.error = Some(e);
        }
    }
}
