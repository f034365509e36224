//! Contact with rigid parts (SPEC L4), against statics and Coulomb's law:
//! * `contact_rest`: a hose lying on a floor under gravity — the floor carries exactly the
//!   weight (within 1 %) and nothing sinks in by more than 1 % of the radius; the same with
//!   the floor's triangles wound the wrong way.
//! * `contact_incline`: a hose lying down the slope of an incline with μ_s = 0.5,
//!   μ_k = 0.4 sticks for tan φ = 0.8 μ_s and slides for tan φ = 1.2 μ_s with the
//!   acceleration g (sin φ − μ_k cos φ) (within 2 %).
//! * `tunnelling`: a hose flying at 2 m/s against a 1 mm sheet stays on its side, and a
//!   hose falling onto a 2 mm wide ridge between two of its nodes rests on the ridge
//!   (contact along the beam, not only at nodes).

use crate::harness::{hose1, straight_hose};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::{integrators::explicit, Model, RigidPartSpec, SimSettings, State, WorldSpec};

pub(super) const G: f64 = 9.81;

/// A rectangle of two triangles: centre, two half-edge vectors; `flip` reverses winding.
pub(super) fn quad(
    name: &str,
    centre: DVec3,
    u: DVec3,
    v: DVec3,
    flip: bool,
    mu: (f64, f64),
) -> RigidPartSpec {
    let vertices = vec![
        centre - u - v,
        centre + u - v,
        centre + u + v,
        centre - u + v,
    ];
    let triangles = if flip {
        vec![[0, 2, 1], [0, 3, 2]]
    } else {
        vec![[0, 1, 2], [0, 2, 3]]
    };
    RigidPartSpec {
        name: name.into(),
        vertices,
        triangles,
        friction_static: mu.0,
        friction_sliding: mu.1,
        motion: None,
        parent: None,
        movable: false,
    }
}

/// A closed box (12 triangles) centred at `c` with half extents `h`.
fn cuboid(name: &str, c: DVec3, h: DVec3) -> RigidPartSpec {
    let mut vertices = Vec::new();
    for i in 0..8 {
        let s = DVec3::new(
            if i & 1 == 0 { -1.0 } else { 1.0 },
            if i & 2 == 0 { -1.0 } else { 1.0 },
            if i & 4 == 0 { -1.0 } else { 1.0 },
        );
        vertices.push(c + s * h);
    }
    let faces = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    let triangles = faces
        .iter()
        .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
        .collect();
    RigidPartSpec {
        name: name.into(),
        vertices,
        triangles,
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion: None,
        parent: None,
        movable: false,
    }
}

pub(super) fn world(
    hose_nodes: impl Fn(f64) -> DVec3,
    parts: Vec<RigidPartSpec>,
    gravity: DVec3,
    damping: f64,
) -> Model {
    let (mat, sec) = hose1();
    let mut hose = straight_hose(20, 0.5, &mat, sec, |_| DVec3::ZERO);
    for (i, p) in hose.nodes.iter_mut().enumerate() {
        *p = hose_nodes(i as f64 / 20.0);
    }
    let settings = SimSettings {
        gravity,
        damping_mass: damping,
        damping_stiffness: None,
        ..Default::default()
    };
    Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: parts,
        settings,
    })
    .expect("contact model builds")
}

fn run_for(model: &Model, state: &mut State, seconds: f64) {
    for _ in 0..(seconds / model.time_step).round() as u64 {
        explicit::step(model, state);
    }
}

/// A hose lying on a floor under gravity for 2 s: the floor must carry its weight, and no
/// node may sink in. `flip` winds the floor's triangles the wrong way; `stiffened` makes
/// the middle fifth a rigid metal section (SPEC M6), which rests by penalty contact.
fn floor_case(flip: bool, stiffened: bool) -> Vec<Check> {
    let (_, sec) = hose1();
    let r = sec.outer_radius();
    let floor = quad(
        "floor",
        DVec3::ZERO,
        DVec3::X * 2.0,
        DVec3::Y * 2.0,
        flip,
        (0.5, 0.4),
    );
    let mut model = world(
        |s| DVec3::new(0.5 * s, 0.0, r),
        vec![floor],
        DVec3::new(0.0, 0.0, -G),
        5.0,
    );
    if stiffened {
        let span = pliant_core::rod::stiffened::StiffenedSpan {
            hose: 0,
            first: 8,
            last: 12,
        };
        model = match model.with_stiffened_spans(&[span]) {
            Ok(m) => m,
            Err(e) => {
                return vec![Check::failed(
                    "contact_rest",
                    "stiffened span",
                    &e.to_string(),
                )]
            }
        };
    }
    let mut state = State::at_rest(&model);
    run_for(&model, &mut state, 2.0);
    let weight: f64 = model.mass.iter().sum::<f64>() * G;
    let carried: f64 = state.contact_force.iter().map(|f| f.z).sum();
    let sink = state
        .x
        .iter()
        .map(|x| r - x.z)
        .fold(f64::MIN, f64::max)
        .max(0.0);
    let tag = match (flip, stiffened) {
        (true, _) => " (triangles wound wrong)",
        (_, true) => " (stiffened middle, penalty)",
        _ => "",
    };
    vec![
        Check::relative(
            "contact_rest",
            &format!("floor force = weight N{tag}"),
            carried,
            weight,
            0.01,
        ),
        Check::with_error(
            "contact_rest",
            &format!("max penetration / r{tag}"),
            sink / r,
            0.0,
            sink / r,
            0.01,
        ),
    ]
}

pub fn run_rest() -> Vec<Check> {
    let mut out = floor_case(false, false);
    out.extend(floor_case(true, false));
    out.extend(floor_case(false, true));
    out
}

/// A 2 m × 2 m plane through the origin tilted by `phi` about y, rising towards +x, with
/// friction coefficients `mu` (static, sliding); with its downhill direction and normal.
pub(super) fn incline_plane(phi: f64, mu: (f64, f64)) -> (RigidPartSpec, DVec3, DVec3) {
    let tilt = DQuat::from_axis_angle(DVec3::Y, -phi);
    let plane = quad(
        "incline",
        DVec3::ZERO,
        tilt * DVec3::X * 2.0,
        DVec3::Y * 2.0,
        false,
        mu,
    );
    (plane, tilt * DVec3::NEG_X, tilt * DVec3::Z)
}

/// Displacement along the slope after `seconds`, for an incline of angle φ.
fn slide(phi: f64, seconds: f64) -> (f64, f64) {
    let (_, sec) = hose1();
    let r = sec.outer_radius();
    let (plane, down, normal) = incline_plane(phi, (0.5, 0.4));
    let model = world(
        |s| -down * (0.5 * s - 0.25) + normal * r,
        vec![plane],
        DVec3::new(0.0, 0.0, -G),
        0.0,
    );
    let mut state = State::at_rest(&model);
    let start = state.x[10];
    run_for(&model, &mut state, seconds);
    (
        (state.x[10] - start).dot(down),
        G * (phi.sin() - 0.4 * phi.cos()),
    )
}

pub fn run_incline() -> Vec<Check> {
    let stick = (0.8f64 * 0.5).atan();
    let (d_stick, _) = slide(stick, 0.5);
    let sliding = (1.2f64 * 0.5).atan();
    let t = 0.3;
    let (d_slide, a) = slide(sliding, t);
    vec![
        Check::with_error(
            "contact_incline",
            "creep at tan(phi)=0.8 mu_s over 0.5 s m (abs)",
            d_stick,
            0.0,
            d_stick.abs(),
            1e-5,
        ),
        Check::relative(
            "contact_incline",
            "slide at tan(phi)=1.2 mu_s: distance in 0.3 s m",
            d_slide,
            0.5 * a * t * t,
            0.02,
        ),
    ]
}

pub fn run_tunnelling() -> Vec<Check> {
    let (_, sec) = hose1();
    let r = sec.outer_radius();
    // (1) flying at 2 m/s into a 1 mm sheet at x = 0.1, hose along y
    let sheet = cuboid(
        "sheet",
        DVec3::new(0.1, 0.0, 0.0),
        DVec3::new(0.0005, 1.0, 1.0),
    );
    let model = world(
        |s| DVec3::new(0.0, 0.5 * s - 0.25, 0.0),
        vec![sheet],
        DVec3::ZERO,
        0.0,
    );
    let mut state = State::at_rest(&model);
    state.v.fill(DVec3::new(2.0, 0.0, 0.0));
    run_for(&model, &mut state, 0.3);
    let front = state.x.iter().map(|x| x.x).fold(f64::MIN, f64::max);
    let limit = 0.1 - 0.0005;
    // (2) falling onto a 2 mm ridge across the hose, midway between nodes 10 and 11
    let ridge_x = 0.5 * 10.5 / 20.0;
    let ridge = cuboid(
        "ridge",
        DVec3::new(ridge_x, 0.0, -0.01),
        DVec3::new(0.001, 0.2, 0.01),
    );
    let model2 = world(
        |s| DVec3::new(0.5 * s, 0.0, r + 0.002),
        vec![ridge],
        DVec3::new(0.0, 0.0, -G),
        5.0,
    );
    let mut st2 = State::at_rest(&model2);
    // hold both ends level so the hose bridges over the ridge
    st2.loads
        .add(pliant_core::loads::LoadCase::Fix(pliant_core::loads::Fix {
            node: 0,
            position: st2.x[0],
            orientation: st2.q[0],
        }));
    st2.loads
        .add(pliant_core::loads::LoadCase::Fix(pliant_core::loads::Fix {
            node: 20,
            position: st2.x[20],
            orientation: st2.q[20],
        }));
    run_for(&model2, &mut st2, 1.0);
    let mid = 0.5 * (st2.x[10] + st2.x[11]);
    let clearance = mid.z - r; // centre line above the ridge top (z = 0) minus the radius
    vec![
        Check::with_error(
            "tunnelling",
            "front past the sheet face at 2 m/s, m (abs)",
            front - (limit - r),
            0.0,
            (front - (limit - r)).max(0.0),
            0.01 * r,
        ),
        Check::with_error(
            "tunnelling",
            "sinking into a ridge between nodes / r",
            -clearance / r,
            0.0,
            (-clearance / r).max(0.0),
            0.01,
        ),
    ]
}
