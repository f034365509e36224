//! `thesis_1` … `thesis_4`: the dissertation's four validation experiments (§6.2, SPEC §7)
//! as shipped in `examples/thesis_N.toml`: a straight hose, 500 mm, 20 elements,
//! d_a = 40 mm, d_i = 30 mm, E = mean of E_t and E_c, a 1 mm imperfection in z at the
//! middle node; node 0 fixed, the last node driven over 20 s (and held):
//! (1) stretched 50 mm, (2) compressed 120 mm, (3) moved (−120, 120, 120) mm,
//! (4) compressed 120 mm while turned 90° about y. Run for materials 1 and 4, with the
//! scene's own explicit dynamics (damped, slow drive), and compared at eight instants of
//! the drive with the independent Kirchhoff-rod shooting solver (`crates/reference`)
//! clamped at exactly the pose the driven node had.
//!
//! Tolerances: end force within 2 % of the experiment's peak reference force, node
//! positions within 2 mm (0.4 % of L), fixed before the first run. Measured (see
//! docs/validation.md): forces within 0.5–1 % of the peak, shapes within 0.4–1.9 mm, the
//! largest for the post-buckled compression of the soft, heavy material 4. Their sources:
//! the 20-element discretisation (O(h²); these shapes turn through large angles over 25 mm
//! elements) and the dynamic drive (inertia and damping of a 20 s move). The thesis accepted
//! 10 % of the peak force and 23 mm against PAMCRASH and Madymo; these bounds are five and
//! ten times stricter.

use crate::harness::library_hose;
use crate::reference_bridge::{end_pose, solver_for, to_glam};
use crate::Check;
use glam::DVec3;
use pliant_assembly::{Action, Observer, Runner};
use pliant_core::{Material, Model, State};
use pliant_reference::EndCondition;
use std::path::PathBuf;

const SAMPLES: usize = 8;
const FORCE_TOLERANCE: f64 = 0.02;
const SHAPE_TOLERANCE_MM: f64 = 2.0;

/// The library hoses whose materials the thesis used (the two with the largest difference
/// between E_t and E_c), with the label used in the report.
const MATERIALS: [(&str, &str); 2] = [("material 1", "hose1"), ("material 4", "hose4")];

fn scene_path(k: usize) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"))
        .join(format!("thesis_{k}.toml"))
}

/// Captures the driven node's pose, its support force and all node positions at
/// SAMPLES evenly spaced instants of the drive.
struct Sampler {
    end: usize,
    drive_start: Option<f64>,
    drive_duration: f64,
    next: usize,
    samples: Vec<(DVec3, glam::DQuat, DVec3, Vec<DVec3>)>,
}

impl Sampler {
    fn next_time(&self) -> Option<f64> {
        let t0 = self.drive_start?;
        (self.next < SAMPLES)
            .then(|| t0 + self.drive_duration * (self.next + 1) as f64 / SAMPLES as f64)
    }
}

impl Observer for Sampler {
    fn wants_state(&self, time: f64) -> bool {
        self.next_time().is_some_and(|t| time + 1e-9 >= t)
    }
    fn on_state(&mut self, _model: &Model, s: &State) {
        self.samples.push((
            s.x[self.end],
            s.q[self.end],
            s.reaction_force[self.end],
            s.x.clone(),
        ));
        self.next += 1;
    }
    fn on_action(&mut self, _index: usize, action: &Action, state: &State) {
        if let Action::Move { duration, .. } = action {
            self.drive_start = Some(state.time);
            self.drive_duration = *duration;
        }
    }
}

fn experiment(k: usize, (mat_name, library_name): (&str, &str)) -> Vec<Check> {
    let case = format!("thesis_{k}");
    let (lib, _) = library_hose(library_name);
    let fail = |why: String| vec![Check::failed(&case, mat_name, &why)];
    let mut scene = match pliant_scene::load_scene_file(&scene_path(k)) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    // the thesis gave PAMCRASH and Madymo the mean of E_t and E_c for every modulus
    let mean = 0.5 * (lib.e_tension + lib.e_compression);
    scene.world.hoses[0].material = Material {
        e_tension: mean,
        e_compression: mean,
        e_bending: Some(mean),
        ..lib
    };
    let model = match Model::build(&scene.world) {
        Ok(m) => m,
        Err(e) => return fail(e.to_string()),
    };
    let end = model.hoses[0].first_node + model.hoses[0].node_count - 1;
    let mut sampler = Sampler {
        end,
        drive_start: None,
        drive_duration: 0.0,
        next: 0,
        samples: Vec::new(),
    };
    let mut state = State::at_rest(&model);
    if let Err(e) = Runner::new(&model).run(&scene.timeline, &mut state, &mut sampler) {
        return fail(e.to_string());
    }
    let solver = match solver_for(&model, 0) {
        Ok(s) => s,
        Err(e) => return fail(e),
    };
    let rest_end = solver.rod().rest_end_pose();
    let targets: Vec<EndCondition> = sampler
        .samples
        .iter()
        .map(|(x, q, _, _)| EndCondition::clamped(end_pose(&model, end, &rest_end, *x, *q)))
        .collect();
    let solutions = match solver.solve_path(&targets) {
        Ok(s) => s,
        Err(e) => return fail(format!("reference solver: {e}")),
    };
    let arc = solver.rod().node_arc_lengths().to_vec();
    let peak_ref = solutions
        .iter()
        .map(|s| s.end_reaction().force.norm())
        .fold(0.0, f64::max);
    let mut worst_force: (f64, f64, f64) = (0.0, 0.0, 0.0); // (error, computed |F|, reference |F|)
    let mut worst_shape: f64 = 0.0;
    for ((_, _, f_sim, xs), sol) in sampler.samples.iter().zip(&solutions) {
        let f_ref = to_glam(&sol.end_reaction().force);
        let err = (*f_sim - f_ref).length() / peak_ref;
        if err >= worst_force.0 {
            worst_force = (err, f_sim.length(), f_ref.length());
        }
        let Ok(sections) = sol.sample(&arc) else {
            return fail("reference sampling failed".into());
        };
        for (x, sec) in xs[model.hoses[0].nodes()].iter().zip(&sections) {
            worst_shape = worst_shape.max((*x - to_glam(&sec.position)).length() * 1000.0);
        }
    }
    vec![
        Check::with_error(
            &case,
            &format!("{mat_name}: end force |F| at worst instant N (error of peak)"),
            worst_force.1,
            worst_force.2,
            worst_force.0,
            FORCE_TOLERANCE,
        ),
        Check::with_error(
            &case,
            &format!("{mat_name}: max node distance mm (abs)"),
            worst_shape,
            0.0,
            worst_shape,
            SHAPE_TOLERANCE_MM,
        ),
    ]
}

fn run_experiment(k: usize) -> Vec<Check> {
    MATERIALS.iter().flat_map(|m| experiment(k, *m)).collect()
}

pub fn run_1() -> Vec<Check> {
    run_experiment(1)
}
pub fn run_2() -> Vec<Check> {
    run_experiment(2)
}
pub fn run_3() -> Vec<Check> {
    run_experiment(3)
}
pub fn run_4() -> Vec<Check> {
    run_experiment(4)
}
