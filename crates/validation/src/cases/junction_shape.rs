//! `junction_shape_rest` and `junction_shape_impact`: a junction body with a shape
//! (SPEC N1; `[[junctions]] body = { mass_kg, part = "NAME" }`, the part a box of
//! `[[parts]]`), written in a scene file as a user's would be. Hose `a` along x ends
//! in the piece, whose other outlet starts hose `b` further along x; the piece's shape
//! is a box between the outlets, wider than the hoses, that rides on the body. The
//! explicit solver only: the Newton solvers refuse a junction shape, checked here too.
//!
//! * `junction_shape_rest` (statics by dynamic relaxation): `a` is clamped at its start
//!   and stiff (EI = 100 N·m², its tip slope under the load ≈ 3e-4 rad); hose `c` lies
//!   across the box's top (the box 0.2 m wide, `c` 0.16 m long: it rests on the face
//!   only), touching nothing else. At rest the clamp carries every weight, the resting
//!   hose's through the box, the piece and `a`: R_z = g Σ m (the hoses' lumped masses
//!   and the piece's own), and the bending moment M_y = −g Σ m x (rest shape; the stiff
//!   hoses move the lever arms by second-order terms only). Without the shape's reaction
//!   on the body, `c`'s weight (28 % of R_z) would be missing from both. The explicit
//!   contact against the light piece keeps a small limit cycle (the free nodes'
//!   out-of-balance force ≈ 0.3 % of the weight; kinetic damping does not remove it), so
//!   the reaction is averaged over 0.2 s after 0.2 s of kinetic-damping relaxation,
//!   within 1 % (the resting hose's share within 3 %).
//! * `junction_shape_impact` (dynamics): no gravity, no damping; the free network
//!   (`a`, piece, `b`) is hit on the box's top by hose `c` falling at 1 m/s. Contact is
//!   the only force between `c` and the network, and its reaction acts on the body, so
//!   the total linear momentum Σ m_i v_i stays that of `c` before the hit, to round-off;
//!   the network takes up momentum (more than a tenth of `c`'s); and `c` does not pass
//!   through the box: its lowest node stays above the box's top (in the box's frame, as
//!   the body moves and turns) to within a tenth of its radius.

use crate::harness::clamp;
use crate::Check;
use glam::DVec3;
use pliant_core::integrators::{explicit, StaticSolver};
use pliant_core::relax::stop;
use pliant_core::{Model, State};

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

/// The rest case: the clamp's reaction against the weights (module doc), and the
/// Newton solvers' refusal.
pub fn run_rest() -> Vec<Check> {
    const CASE: &str = "junction_shape_rest";
    let model = match scene((G, 0.0), 0.0, (1e6, 100.0, 10.0)) {
        Ok(m) => m,
        Err(e) => return vec![Check::failed(CASE, "scene", &e)],
    };
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let weight = G * (PIECE_MASS + model.mass.iter().sum::<f64>());
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
    if !(force.is_finite() && moment.is_finite()) {
        return vec![Check::failed(CASE, "rest", "the reaction is not finite")];
    }
    let lever: f64 = (0..model.node_count())
        .map(|i| model.mass[i] * model.rest_x[i].x)
        .sum::<f64>()
        + PIECE_MASS * (L + 0.5 * GAP);
    let c_weight = G * nodes(&model, 2).map(|i| model.mass[i]).sum::<f64>();
    let refused = match StaticSolver::new(&model) {
        Err(e) => {
            let text = e.to_string();
            text.contains("junction 'tee'") && text.contains("explicit")
        }
        Ok(_) => false,
    };
    vec![
        Check::relative(
            CASE,
            "clamp force R_z / g Σ m (every weight, the resting hose's through the box)",
            force.z / weight,
            1.0,
            1e-2,
        ),
        Check::relative(
            CASE,
            "resting hose's weight at the clamp (R_z − g Σ m of the rest) / g m_c",
            (force.z - (weight - c_weight)) / c_weight,
            1.0,
            3e-2,
        ),
        Check::relative(
            CASE,
            "clamp bending moment M_y / −g Σ m x",
            moment.y / (-G * lever),
            1.0,
            1e-2,
        ),
        Check::with_error(
            CASE,
            "static solver refuses the shape, naming the junction (1: yes)",
            f64::from(u8::from(refused)),
            1.0,
            f64::from(u8::from(!refused)),
            0.0,
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
