//! `junction_shape_rest` and `junction_shape_impact`: a junction body with a shape
//! (SPEC N1; `[[junctions]] body = { mass_kg, part = "NAME" }`, the part a box of
//! `[[parts]]`), written in a scene file as a user's would be. Hose `a` along x ends
//! in the piece, whose other outlet starts hose `b` further along x; the piece's shape
//! is a box between the outlets, wider than the hoses, that rides on the body.
//!
//! * `junction_shape_rest` (statics, under every solver): `a` is clamped at its start
//!   and stiff (EI = 100 N·m², its tip slope under the load ≈ 3e-4 rad); hose `c` lies
//!   across the box's top (the box 0.2 m wide, `c` 0.16 m long: it rests on the face
//!   only), touching nothing else. At rest the clamp carries every weight, the resting
//!   hose's through the box, the piece and `a`: R_z = g Σ m (the hoses' lumped masses
//!   and the piece's own), and the bending moment M_y = −g Σ m x (rest shape). Without
//!   the shape's reaction on the body, `c`'s weight (28 % of R_z) would be missing from
//!   both. The force balance is exact at any equilibrium; the moment moves with the lever
//!   arms: the box's tilt θ ≈ 3e-4 shifts `c`, 15 mm above the axis, by 15 mm · θ along
//!   x — (15 mm / 0.32 m) θ ≈ 1.4e-5 of its lever, 4e-6 of M_y with its 28 % share.
//!   - explicit (dynamic relaxation): the contact against the light piece keeps a small
//!     limit cycle (the free nodes' out-of-balance force ≈ 0.3 % of the weight; kinetic
//!     damping does not remove it), so the reaction is averaged over 0.2 s after 0.2 s of
//!     kinetic-damping relaxation, within 1 % (the resting hose's share within 3 %);
//!   - static (Newton, the shape's contact coupling hose and body nodes,
//!     [`pliant_core::newton::shape_contact`]): the force balance to 1e-9 (the solve's
//!     residual is 1e-10 of the weight), the resting hose's share to 1e-8, M_y to 1e-5;
//!   - implicit, damped to rest (HHT-α steps of 50 ms, each from rest, until the free
//!     nodes' residual is below 1e-7 of the weight): the force balance to 1e-6, the
//!     share to 1e-5, M_y to 1e-5.
//! * `junction_shape_impact` (dynamics): no gravity, no damping; the free network
//!   (`a`, piece, `b`) is hit on the box's top by hose `c` falling at 1 m/s. Contact is
//!   the only force between `c` and the network, and its reaction acts on the body, so
//!   the total linear momentum Σ m_i v_i stays that of `c` before the hit, to round-off;
//!   the network takes up momentum (more than a tenth of `c`'s); and `c` does not pass
//!   through the box: its lowest node stays above the box's top (in the box's frame, as
//!   the body moves and turns) to within a tenth of its radius.

use crate::harness::{clamp, implicit_to_rest};
use crate::Check;
use glam::DVec3;
use pliant_core::integrators::{explicit, StaticSolver};
use pliant_core::newton::Tolerance;
use pliant_core::relax::stop;
use pliant_core::{Model, SolverKind, State};

const G: f64 = 9.81;
/// Hose `a`'s length, the outlets' gap and hose `b`'s length \[m\].
const L: f64 = 0.3;
const GAP: f64 = 0.04;
const B_LENGTH: f64 = 0.1;
/// The box: x between the outlets, y across, z up \[m\].
const BOX: [f64; 3] = [GAP, 0.2, 0.02];
/// Hose outer radius \[m\] (d_outer = 10 mm).
const R: f64 = 0.005;
/// Hose `c`'s half length \[m\].
const C_HALF: f64 = 0.08;

/// The scene: hoses `a`, `b` and `c` (`c` along y over the box's centre, its axis
/// `lift` above touching), the piece "tee" with its box "tee_box", gravity `g`.
fn scene(
    (g, damping): (f64, f64),
    lift: f64,
    (ea, ei, gj): (f64, f64, f64),
) -> Result<Model, String> {
    let centre = DVec3::new(L + 0.5 * GAP, 0.0, 0.0);
    let c_z = 0.5 * BOX[2] + R + lift;
    let hose = |name: &str, a: DVec3, b: DVec3, elements: usize| {
        format!(
            r#"
[[hoses]]
name = "{name}"
material = "hose1"
section = {{ d_inner = 0, d_outer = {d}, ea_n = {ea}, ei1_n_m2 = {ei}, ei2_n_m2 = {ei}, gj_n_m2 = {gj} }}
elements = {elements}
start = [{}, {}, {}]
path = [{{ line = {{ to = [{}, {}, {}] }} }}]
"#,
            a.x,
            a.y,
            a.z,
            b.x,
            b.y,
            b.z,
            d = 2.0 * R
        )
    };
    let mut text = format!(
        r#"
format = "pliant-scene"
version = 1
name = "junction shape validation"
length_unit = "m"
[simulation]
gravity = [0, 0, {}]
damping_mass_per_s = {damping}
"#,
        -g
    );
    text += &hose("a", DVec3::ZERO, DVec3::new(L, 0.0, 0.0), 15);
    text += &hose(
        "b",
        DVec3::new(L + GAP, 0.0, 0.0),
        DVec3::new(L + GAP + B_LENGTH, 0.0, 0.0),
        5,
    );
    text += &hose(
        "c",
        centre + DVec3::new(0.0, -C_HALF, c_z),
        centre + DVec3::new(0.0, C_HALF, c_z),
        8,
    );
    text += &format!(
        r#"
[[parts]]
name = "tee_box"
box = {{ size = [{}, {}, {}] }}
position = [{}, 0, 0]
friction = {{ static = 0.5, sliding = 0.4 }}

[[junctions]]
name = "tee"
ends = [{{ hose = "a", end = "end" }}, {{ hose = "b", end = "start" }}]
body = {{ mass_kg = {PIECE_MASS}, centre_of_mass = [{}, 0, 0], inertia_kg_m2 = [{}, {}, {}], part = "tee_box" }}
"#,
        BOX[0],
        BOX[1],
        BOX[2],
        centre.x,
        centre.x,
        box_inertia(1, 2),
        box_inertia(0, 2),
        box_inertia(0, 1)
    );
    let scene = pliant_scene::load_scene_str(&text, "junction shape validation")
        .map_err(|e| e.to_string())?;
    scene.build_model()
}

/// The piece's own mass \[kg\]: a solid box's moments of inertia about its centre,
/// m (a² + b²)/12 over the two other edges.
const PIECE_MASS: f64 = 0.02;

fn box_inertia(a: usize, b: usize) -> f64 {
    PIECE_MASS * (BOX[a] * BOX[a] + BOX[b] * BOX[b]) / 12.0
}

/// Index of hose `h`'s nodes.
fn nodes(model: &Model, h: usize) -> std::ops::Range<usize> {
    model.hoses[h].nodes()
}

/// Seconds of kinetic-damping relaxation before the reaction is read, and the window it
/// is averaged over (module doc).
const SETTLE: f64 = 0.2;
const WINDOW: f64 = 0.2;

/// The rest case: the clamp's reaction against the weights (module doc), under the
/// explicit solver (kinetic damping, the reaction averaged), the static solver and the
/// implicit one damped to rest.
pub fn run_rest() -> Vec<Check> {
    const CASE: &str = "junction_shape_rest";
    let model = match scene((G, 0.0), 0.0, (1e6, 100.0, 10.0)) {
        Ok(m) => m,
        Err(e) => return vec![Check::failed(CASE, "scene", &e)],
    };
    let mut out = Vec::new();
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    // kinetic damping: every velocity zeroed at each peak of the kinetic energy
    let (settle, window) = (
        (SETTLE / model.time_step).ceil() as usize,
        (WINDOW / model.time_step).ceil() as usize,
    );
    let (mut last, mut force, mut moment) = (0.0, DVec3::ZERO, DVec3::ZERO);
    for k in 0..settle + window {
        explicit::step(&model, &mut state);
        let energy = state.kinetic_energy(&model);
        if energy < last {
            stop(&mut state);
            last = 0.0;
        } else {
            last = energy;
        }
        if k >= settle {
            force += state.reaction_force[0] / window as f64;
            moment += state.reaction_moment[0] / window as f64;
        }
    }
    out.extend(rest_checks(&model, "", (force, moment), EXPLICIT));
    for (kind, tolerances) in [
        (SolverKind::Static, STATIC),
        (SolverKind::Implicit, IMPLICIT),
    ] {
        let label = format!("{kind}: ");
        match newton_rest(&model, kind) {
            Ok(reaction) => out.extend(rest_checks(&model, &label, reaction, tolerances)),
            Err(e) => out.push(Check::failed(CASE, &format!("{label}rest"), &e)),
        }
    }
    out
}

/// The rest checks' tolerances: clamp force, the resting hose's share, clamp moment.
type RestTolerances = (f64, f64, f64);
/// Explicit: the contact's small limit cycle, averaged (module doc).
const EXPLICIT: RestTolerances = (1e-2, 3e-2, 1e-2);
/// Static: an exact equilibrium; the force balance to the solve's residual, the moment
/// to the lever arms' change in the rest shape (module doc).
const STATIC: RestTolerances = (1e-9, 1e-8, 1e-5);
/// Implicit, damped to rest: as static, the force balance to its rest test's residual.
const IMPLICIT: RestTolerances = (1e-6, 1e-5, 1e-5);

/// The clamp's reaction (force, moment) at rest under the static solver, or the
/// implicit one damped to rest ([`implicit_to_rest`]).
fn newton_rest(model: &Model, kind: SolverKind) -> Result<(DVec3, DVec3), String> {
    let mut state = State::at_rest(model);
    clamp(&mut state, 0);
    let weight = G * (PIECE_MASS + model.mass.iter().sum::<f64>());
    let (force, moment) = (1e-10 * weight, 1e-10 * weight * L);
    if kind == SolverKind::Static {
        let mut solver = StaticSolver::new(model).map_err(|e| e.to_string())?;
        solver.options.tolerance = Tolerance::absolute(force, moment);
        let r = solver.solve(model, &mut state).map_err(|e| e.to_string())?;
        if !r.converged {
            return Err(format!(
                "no equilibrium in {} iterations (residual {:.3e} N)",
                r.iterations, r.residual_force
            ));
        }
    } else {
        let newton = Tolerance::absolute(1e-3 * force, 1e-3 * moment);
        let r = implicit_to_rest(model, &mut state, newton, 1e3 * force, 1e3 * moment)?;
        if !r.converged {
            return Err(format!("not at rest after {} steps", r.steps));
        }
    }
    Ok((state.reaction_force[0], state.reaction_moment[0]))
}

/// The clamp's reaction `(force, moment)` against the weights (module doc), rows named
/// after `label`.
fn rest_checks(
    model: &Model,
    label: &str,
    (force, moment): (DVec3, DVec3),
    (total, share, bending): RestTolerances,
) -> Vec<Check> {
    const CASE: &str = "junction_shape_rest";
    if !(force.is_finite() && moment.is_finite()) {
        return vec![Check::failed(
            CASE,
            &format!("{label}rest"),
            "the reaction is not finite",
        )];
    }
    let weight = G * (PIECE_MASS + model.mass.iter().sum::<f64>());
    let lever: f64 = (0..model.node_count())
        .map(|i| model.mass[i] * model.rest_x[i].x)
        .sum::<f64>()
        + PIECE_MASS * (L + 0.5 * GAP);
    let c_weight = G * nodes(model, 2).map(|i| model.mass[i]).sum::<f64>();
    vec![
        Check::relative(
            CASE,
            &format!(
                "{label}clamp force R_z / g Σ m (every weight, the resting hose's through the box)"
            ),
            force.z / weight,
            1.0,
            total,
        ),
        Check::relative(
            CASE,
            &format!("{label}resting hose's weight at the clamp (R_z − g Σ m of the rest) / g m_c"),
            (force.z - (weight - c_weight)) / c_weight,
            1.0,
            share,
        ),
        Check::relative(
            CASE,
            &format!("{label}clamp bending moment M_y / −g Σ m x"),
            moment.y / (-G * lever),
            1.0,
            bending,
        ),
    ]
}

/// The impact case: momentum kept, momentum passed on, no passing through (module doc).
pub fn run_impact() -> Vec<Check> {
    const CASE: &str = "junction_shape_impact";
    let lift = 0.002;
    let model = match scene((0.0, 0.0), lift, (2e5, 0.5, 0.4)) {
        Ok(m) => m,
        Err(e) => return vec![Check::failed(CASE, "scene", &e)],
    };
    let mut state = State::at_rest(&model);
    let v0 = DVec3::new(0.0, 0.0, -1.0);
    for i in nodes(&model, 2) {
        state.v[i] = v0;
    }
    // the body's momentum M V (its nodes' and its own mass's), the free nodes' m_i v_i
    let body = model.junctions[0].body;
    let of_body = |s: &State| model.bodies[body].mass * s.bodies[body].velocity;
    let free = |s: &State, h: usize| -> DVec3 {
        nodes(&model, h)
            .filter(|&i| model.body_of[i].is_none())
            .map(|i| model.mass[i] * s.v[i])
            .sum()
    };
    let momentum = |s: &State| free(s, 0) + free(s, 1) + free(s, 2) + of_body(s);
    let network = |s: &State| free(s, 0) + free(s, 1) + of_body(s);
    let p0 = momentum(&state);
    let scale = p0.length();
    let top = 0.5 * BOX[2];
    let mut deepest = f64::INFINITY;
    let mut drift = 0.0_f64;
    let steps = (0.02 / model.time_step).ceil() as usize;
    for _ in 0..steps {
        explicit::step(&model, &mut state);
        drift = drift.max((momentum(&state) - p0).length());
        let place = model.junction_shape_placement(0, &state.bodies[body]);
        // c's lowest node above the box top, in the box's frame (its centre at rest is
        // (L + GAP/2, 0, 0), the reference placement)
        let centre = DVec3::new(L + 0.5 * GAP, 0.0, 0.0);
        for i in nodes(&model, 2) {
            let local = place.pose.inverse_apply(state.x[i]) - centre;
            if local.x.abs() <= 0.5 * BOX[0] && local.y.abs() <= 0.5 * BOX[1] {
                deepest = deepest.min(local.z - top - R);
            }
        }
    }
    if !deepest.is_finite() {
        return vec![Check::failed(CASE, "hit", "hose c never came over the box")];
    }
    let taken = network(&state).length();
    vec![
        Check::scaled(
            CASE,
            "largest drift of the total momentum, norm of (Σ m_i v_i − p₀) / norm of p₀",
            drift,
            0.0,
            scale,
            1e-9,
        ),
        Check::with_error(
            CASE,
            "momentum the network took up / norm of p₀ (≥ 0.1)",
            taken / scale,
            0.1,
            (0.1 - taken / scale).max(0.0),
            0.0,
        ),
        Check::with_error(
            CASE,
            "deepest penetration of c into the box top / r (≤ 0.1)",
            (-deepest / R).max(0.0),
            0.0,
            (-deepest / R - 0.1).max(0.0),
            0.0,
        ),
    ]
}
