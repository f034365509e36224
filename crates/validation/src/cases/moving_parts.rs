//! Parts that move (SPEC K1), against rigid-body kinematics, Newton's second law and
//! Coulomb's law, under the solvers where the question makes sense:
//! * `moving_carry`: a hose without gravity mounted at both ends to one part that turns
//!   about a hinge (0 → 0.8 rad) and slides; it must move rigidly with the part — no
//!   strain (largest |ε| below 1e-5) and every node within 1e-4 L of where the part
//!   carries its start position — under the explicit, implicit and static solvers; the
//!   explicit supports' reactions must be the inertial load only: |ΣR − M a_G| below 1 %
//!   of the largest M |a_G| (a_G the centroid's acceleration). The ramps take 8 s, slow against the hose's own
//!   dynamics.
//! * `moving_lift`: a hose lying on a plate that rises with constant acceleration
//!   a = 3 m/s²: the plate carries m (g + a) (mean over 0.1 s within 1 %), explicit and
//!   implicit (statics has no inertia).
//! * `moving_drag`: a plate set sliding at 0.2 m/s under a free hose (μ_s = 0.5,
//!   μ_k = 0.4) accelerates it at μ_k g while it slips (speed change from ¼ to ¾ of the
//!   slip time, within 2 %) and then carries it (relative speed below 1 % of the plate's); a plate
//!   accelerating at 0.8 μ_s g carries the hose without slip (relative travel below 1 %
//!   of the plate's). Explicit and implicit.
//! * `moving_hinge`: a cantilever clamped to a part turning about a hinge through the
//!   clamp, 0 → 20° → 40° → 60° (each turn a smooth 3 s, then held 2 s), matches the
//!   static solution clamped at that angle (the static solver's own, from rest) at the
//!   end of each hold: tip within 1e-4 L (explicit, implicit: what is left of the motion's
//!   swing after 2 s at α = 5/s) and 1e-6 L (static: a sequence of poses).
//! * `moving_fast`: a plate moving three hose diameters per explicit step meets a free
//!   hose: no node centre ends behind it (explicit).

use super::contact::{quad, world, G};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::integrators::{Solver, SolverSettings};
use pliant_core::kinematics::{Hinge, PartMotion, Profile, Slide};
use pliant_core::loads::{LoadCase, Mount};
use pliant_core::{Model, RigidPartSpec, SolverKind, State};

fn settings(kind: SolverKind, step: f64) -> SolverSettings {
    SolverSettings {
        kind,
        implicit_time_step: step,
        static_input_step: step,
        ..Default::default()
    }
}

/// A small triangle at `at`, for a part that carries mounts and touches nothing.
fn tab(name: &str, at: DVec3, motion: Option<PartMotion>) -> RigidPartSpec {
    RigidPartSpec {
        name: name.into(),
        vertices: vec![at, at + DVec3::X * 0.01, at + DVec3::Y * 0.01],
        triangles: vec![[0, 1, 2]],
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion,
        parent: None,
        movable: false,
    }
}

fn mount(state: &mut State, node: usize, part: usize) {
    state.loads.add(LoadCase::Mount(Mount {
        node,
        part,
        position: state.x[node],
        orientation: state.q[node],
    }));
}

fn solver_name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Explicit => "explicit",
        SolverKind::Implicit => "implicit",
        SolverKind::Static => "static",
    }
}

/// Runs `solver` until `until`, calling `each` after every step.
fn run_until(
    model: &Model,
    solver: &mut Solver,
    state: &mut State,
    until: f64,
    mut each: impl FnMut(&State),
) -> Result<(), String> {
    while state.time < until - 1e-9 {
        let stats = solver.step(model, state).map_err(|e| e.to_string())?;
        if !stats.converged {
            return Err(format!("step at t = {:.3} s did not converge", state.time));
        }
        each(state);
    }
    Ok(())
}

/// Largest axial strain |l/l₀ − 1| of the elements.
fn max_strain(model: &Model, state: &State) -> f64 {
    model
        .elements
        .iter()
        .map(|e| ((state.x[e.node_b] - state.x[e.node_a]).length() / e.rest_length - 1.0).abs())
        .fold(0.0, f64::max)
}

/// How long the carrying part's ramps take \[s\]: slow enough that the hose's own
/// deflection under the inertial load (peak acceleration ≈ 0.6 m/s², a sag of ≈ 1e-4 of the
/// span's gravity sag) stays below the tolerances.
const CARRY_TIME: f64 = 8.0;

fn carry(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "moving_carry";
    let name = solver_name(kind);
    let motion = PartMotion::Hinge(Hinge {
        point: DVec3::new(-0.2, 0.0, 0.0),
        axis: DVec3::new(0.0, 0.6, 0.8),
        angle: Profile::ramp(0.0, 0.8, 0.0, CARRY_TIME),
    });
    let body = tab("body", DVec3::new(0.0, 0.3, 0.0), None);
    let mut door = tab("door", DVec3::new(0.0, -0.3, 0.0), Some(motion));
    door.parent = Some(0);
    // the body slides too: the door is carried by it (a hierarchy)
    let mut parts = vec![body, door];
    parts[0].motion = Some(PartMotion::Slide(Slide {
        direction: DVec3::X,
        distance: Profile::ramp(0.0, 0.1, 0.0, CARRY_TIME),
    }));
    let model = world(|s| DVec3::new(0.5 * s, 0.0, 0.0), parts, DVec3::ZERO, 0.0);
    let mut state = State::at_rest(&model);
    let start = state.x.clone();
    let last = state.x.len() - 1;
    mount(&mut state, 0, 1);
    mount(&mut state, last, 1);
    let step: f64 = if kind == SolverKind::Explicit {
        0.0
    } else {
        0.01
    };
    let mut solver = match Solver::new(&model, settings(kind, step.max(1e-3))) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed(CASE, name, &e.to_string())],
    };
    let (mut strain, mut off) = (0.0_f64, 0.0_f64);
    let mut inertial = (0.0_f64, 0.0_f64); // largest |ΣR − M a_G|, largest M |a_G|
    let mass: f64 = model.mass.iter().sum();
    let centroid = |s: &State| -> DVec3 {
        s.x.iter()
            .zip(&model.mass)
            .map(|(x, m)| *x * *m)
            .sum::<DVec3>()
            / mass
    };
    let mut history: Vec<(f64, DVec3, DVec3)> = Vec::new();
    let result = run_until(&model, &mut solver, &mut state, CARRY_TIME + 0.2, |s| {
        strain = strain.max(max_strain(&model, s));
        let pose = model.kinematics.placement_at(1, s.time, &s.part_moves).pose;
        for (x, x0) in s.x.iter().zip(&start) {
            off = off.max((*x - pose.apply(*x0)).length());
        }
        if kind == SolverKind::Explicit {
            let reaction: DVec3 = s.reaction_force.iter().copied().sum();
            history.push((s.time, centroid(s), reaction));
        }
    });
    if let Err(e) = result {
        return vec![Check::failed(CASE, name, &e)];
    }
    if kind == SolverKind::Explicit {
        // a_G by central differences of the centroid over 2 steps, against the reaction of
        // the step between
        for w in history.windows(3).step_by(50) {
            let h = w[1].0 - w[0].0;
            let a = (w[2].1 - 2.0 * w[1].1 + w[0].1) / (h * h);
            inertial.0 = inertial.0.max((w[1].2 - mass * a).length());
            inertial.1 = inertial.1.max(mass * a.length());
        }
    }
    let mut out = vec![
        Check::with_error(
            CASE,
            &format!("{name}: max |strain|"),
            strain,
            0.0,
            strain,
            1e-5,
        ),
        Check::with_error(
            CASE,
            &format!("{name}: max distance from the carried shape / L"),
            off / 0.5,
            0.0,
            off / 0.5,
            1e-4,
        ),
    ];
    if kind == SolverKind::Explicit {
        out.push(Check::with_error(
            CASE,
            "explicit: max |sum of reactions - M a_G| / max M |a_G|",
            inertial.0 / inertial.1,
            0.0,
            inertial.0 / inertial.1,
            0.01,
        ));
    }
    out
}

/// A 2 m plate about the origin in z = 0 with a motion.
fn plate(motion: PartMotion, mu: (f64, f64)) -> RigidPartSpec {
    let mut p = quad("plate", DVec3::ZERO, DVec3::X, DVec3::Y, false, mu);
    p.motion = Some(motion);
    p
}

fn lift(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "moving_lift";
    let name = solver_name(kind);
    let a = 3.0;
    let r = crate::harness::hose1().1.outer_radius();
    let motion = PartMotion::Slide(Slide {
        direction: DVec3::Z,
        distance: Profile::UniformAcceleration {
            start_time: 0.2,
            initial_rate: 0.0,
            acceleration: a,
        },
    });
    let model = world(
        |s| DVec3::new(0.5 * s - 0.25, 0.0, r),
        vec![plate(motion, (0.5, 0.4))],
        DVec3::new(0.0, 0.0, -G),
        0.0, // mass damping would add α m v (a drag on the absolute velocity)
    );
    let mut state = State::at_rest(&model);
    let mut solver = match Solver::new(&model, settings(kind, 1e-3)) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed(CASE, name, &e.to_string())],
    };
    let (mut sum, mut n) = (0.0, 0);
    let result = run_until(&model, &mut solver, &mut state, 0.5, |s| {
        if s.time > 0.4 {
            sum += s.contact_force.iter().map(|f| f.z).sum::<f64>();
            n += 1;
        }
    });
    if let Err(e) = result {
        return vec![Check::failed(CASE, name, &e)];
    }
    let mass: f64 = model.mass.iter().sum();
    vec![Check::relative(
        CASE,
        &format!("{name}: mean plate force over 0.4-0.5 s = m (g + a) N"),
        sum / n.max(1) as f64,
        mass * (G + a),
        0.01,
    )]
}

fn drag(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "moving_drag";
    let name = solver_name(kind);
    let mu = (0.5, 0.4);
    let speed = 0.2;
    let r = crate::harness::hose1().1.outer_radius();
    let build = |profile: Profile| {
        world(
            |s| DVec3::new(0.5 * s - 0.25, 0.0, r),
            vec![plate(
                PartMotion::Slide(Slide {
                    direction: DVec3::X,
                    distance: profile,
                }),
                mu,
            )],
            DVec3::new(0.0, 0.0, -G),
            0.0,
        )
    };
    let start = 0.1;
    let mut out = Vec::new();
    // sliding: the plate jumps to `speed`; the hose speeds up at μ_k g until it sticks
    let model = build(Profile::UniformAcceleration {
        start_time: start,
        initial_rate: speed,
        acceleration: 0.0,
    });
    let slip_time = speed / (mu.1 * G);
    let mut state = State::at_rest(&model);
    let mut solver = match Solver::new(&model, settings(kind, 1e-3)) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed(CASE, name, &e.to_string())],
    };
    let mean_vx = |s: &State| s.v.iter().map(|v| v.x).sum::<f64>() / s.v.len() as f64;
    let mean_x = |s: &State| s.x.iter().map(|x| x.x).sum::<f64>() / s.x.len() as f64;
    let mut positions = Vec::new();
    let result = run_until(
        &model,
        &mut solver,
        &mut state,
        start + 2.0 * slip_time + 0.1,
        |s| {
            positions.push((s.time, mean_x(s)));
        },
    );
    if let Err(e) = result {
        return vec![Check::failed(CASE, name, &e)];
    }
    // hose speed at half the slip time, from positions (the explicit velocity is a
    // half-step one): central difference over 2 ms
    let speed_at = |t: f64| {
        let find = |t: f64| {
            positions
                .iter()
                .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
                .copied()
                .unwrap_or((0.0, 0.0))
        };
        let (p, q) = (find(t - 0.001), find(t + 0.001));
        (q.1 - p.1) / (q.0 - p.0)
    };
    // the hose's acceleration while it slips: speed change from ¼ to ¾ of the slip time
    let (t1, t2) = (start + 0.25 * slip_time, start + 0.75 * slip_time);
    let acceleration = (speed_at(t2) - speed_at(t1)) / (t2 - t1);
    out.push(Check::relative(
        CASE,
        &format!("{name}: hose acceleration while slipping = mu_k g m/s2"),
        acceleration,
        mu.1 * G,
        0.02,
    ));
    let relative = (mean_vx(&state) - speed).abs() / speed;
    let relative = if kind == SolverKind::Explicit {
        relative
    } else {
        (speed_at(state.time - 0.002) - speed).abs() / speed
    };
    out.push(Check::with_error(
        CASE,
        &format!("{name}: after the slip, |v_hose - v_plate| / v_plate"),
        relative,
        0.0,
        relative,
        0.01,
    ));
    // sticking: the plate accelerates at 0.8 μ_s g, the hose goes along
    let acc = 0.8 * mu.0 * G;
    let model = build(Profile::UniformAcceleration {
        start_time: start,
        initial_rate: 0.0,
        acceleration: acc,
    });
    let mut state = State::at_rest(&model);
    let x0 = mean_x(&state);
    let mut solver = match Solver::new(&model, settings(kind, 1e-3)) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed(CASE, name, &e.to_string())],
    };
    if let Err(e) = run_until(&model, &mut solver, &mut state, start + 0.2, |_| {}) {
        out.push(Check::failed(CASE, name, &e));
        return out;
    }
    let plate_travel = 0.5 * acc * 0.2 * 0.2;
    let lag = ((mean_x(&state) - x0) - plate_travel).abs() / plate_travel;
    out.push(Check::with_error(
        CASE,
        &format!("{name}: plate at 0.8 mu_s g carries the hose: |travel lag| / travel"),
        lag,
        0.0,
        lag,
        0.01,
    ));
    out
}

fn hinge(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "moving_hinge";
    let name = solver_name(kind);
    // 0 → 20° → 40° → 60°, each turn a smooth 3 s, then held 2 s
    let times = vec![0.0, 3.0, 5.0, 8.0, 10.0, 13.0, 15.0];
    let degrees = [0.0, 20.0, 20.0, 40.0, 40.0, 60.0, 60.0];
    let motion = PartMotion::Hinge(Hinge {
        point: DVec3::ZERO,
        axis: DVec3::Y,
        angle: Profile::Keyframes {
            times: times.clone(),
            values: degrees.iter().map(|d: &f64| -d.to_radians()).collect(),
            smooth: true,
        },
    });
    let clamp = tab("clamp", DVec3::new(-0.05, 0.0, -0.05), Some(motion));
    let model = world(
        |s| DVec3::new(0.5 * s, 0.0, 0.0),
        vec![clamp],
        DVec3::new(0.0, 0.0, -G),
        5.0,
    );
    // the static solution clamped at angle θ, from rest
    let reference = |theta: f64| -> Result<DVec3, String> {
        let mut state = State::at_rest(&model);
        let q = DQuat::from_axis_angle(DVec3::Y, theta);
        state.loads.add(LoadCase::Fix(pliant_core::loads::Fix {
            node: 0,
            position: DVec3::ZERO,
            orientation: q * state.q[0],
        }));
        let mut solver =
            Solver::new(&model, settings(SolverKind::Static, 1.0)).map_err(|e| e.to_string())?;
        let stats = solver.step(&model, &mut state).map_err(|e| e.to_string())?;
        if !stats.converged {
            return Err("reference static solve did not converge".into());
        }
        Ok(state.x[20])
    };
    // start from the static solution at 0 (the explicit run would swing otherwise)
    let mut state = State::at_rest(&model);
    mount(&mut state, 0, 0);
    let step = match kind {
        SolverKind::Explicit => 1e-3,
        SolverKind::Implicit => 0.01,
        SolverKind::Static => 0.05,
    };
    {
        let mut first = match Solver::new(&model, settings(SolverKind::Static, 1e-9)) {
            Ok(s) => s,
            Err(e) => return vec![Check::failed(CASE, name, &e.to_string())],
        };
        if let Err(e) = first.step(&model, &mut state) {
            return vec![Check::failed(CASE, name, &e.to_string())];
        }
        state.time = 0.0;
        state.v.fill(DVec3::ZERO);
        state.w.fill(DVec3::ZERO);
    }
    let mut solver = match Solver::new(&model, settings(kind, step)) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed(CASE, name, &e.to_string())],
    };
    let tolerance = if kind == SolverKind::Static {
        1e-6
    } else {
        1e-4
    };
    let mut out = Vec::new();
    for (t, degrees) in [(5.0, 20.0_f64), (10.0, 40.0), (15.0, 60.0)] {
        if let Err(e) = run_until(&model, &mut solver, &mut state, t, |_| {}) {
            out.push(Check::failed(CASE, name, &e));
            return out;
        }
        let theta = -degrees.to_radians();
        match reference(theta) {
            Ok(tip) => out.push(Check::scaled(
                CASE,
                &format!(
                    "{name}: tip at {degrees:.0} deg (after 2 s held) vs static solution, / L"
                ),
                (state.x[20] - tip).length() / 0.5,
                0.0,
                1.0,
                tolerance,
            )),
            Err(e) => out.push(Check::failed(CASE, name, &e)),
        }
    }
    out
}

fn fast() -> Vec<Check> {
    const CASE: &str = "moving_fast";
    let r = crate::harness::hose1().1.outer_radius();
    // a 0.6 m × 0.6 m plate in x = x₀, moving along +x through where the hose lies
    let x0 = -0.1 - 2.0 * r;
    let build = |speed: f64| {
        let mut wall = quad(
            "wall",
            DVec3::new(x0, 0.0, 0.0),
            DVec3::Y * 0.3,
            DVec3::Z * 0.3,
            false,
            (0.0, 0.0),
        );
        wall.motion = Some(PartMotion::Slide(Slide {
            direction: DVec3::X,
            distance: Profile::UniformAcceleration {
                start_time: 0.0,
                initial_rate: speed,
                acceleration: 0.0,
            },
        }));
        // the hose along y at x = 0
        world(
            |s| DVec3::new(0.0, 0.5 * s - 0.25, 0.0),
            vec![wall],
            DVec3::ZERO,
            0.0,
        )
    };
    // three hose diameters per explicit step: a search at the plate's current pose alone
    // would let it jump over the hose
    let speed = 3.0 * 2.0 * r / build(1.0).time_step;
    let model = build(speed);
    let mut state = State::at_rest(&model);
    let mut solver = match Solver::new(&model, settings(SolverKind::Explicit, 1e-3)) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed(CASE, "explicit", &e.to_string())],
    };
    let mut behind = f64::NEG_INFINITY;
    let until = (0.4 - x0) / speed;
    let result = run_until(&model, &mut solver, &mut state, until, |s| {
        let wall_x = x0 + speed * s.time;
        for x in &s.x {
            behind = behind.max(wall_x - x.x);
        }
    });
    if let Err(e) = result {
        return vec![Check::failed(CASE, "explicit", &e)];
    }
    vec![Check::with_error(
        CASE,
        &format!(
            "explicit, plate at {speed:.0} m/s (3 hose diameters a step): deepest node centre \
             behind the plate / r"
        ),
        behind / r,
        -1.0,
        (behind / r).max(0.0),
        0.0,
    )]
}

pub fn run_carry() -> Vec<Check> {
    [
        SolverKind::Explicit,
        SolverKind::Implicit,
        SolverKind::Static,
    ]
    .into_iter()
    .flat_map(carry)
    .collect()
}

pub fn run_lift() -> Vec<Check> {
    [SolverKind::Explicit, SolverKind::Implicit]
        .into_iter()
        .flat_map(lift)
        .collect()
}

pub fn run_drag() -> Vec<Check> {
    [SolverKind::Explicit, SolverKind::Implicit]
        .into_iter()
        .flat_map(drag)
        .collect()
}

pub fn run_hinge() -> Vec<Check> {
    [
        SolverKind::Explicit,
        SolverKind::Implicit,
        SolverKind::Static,
    ]
    .into_iter()
    .flat_map(hinge)
    .collect()
}

pub fn run_fast() -> Vec<Check> {
    fast()
}
