//! `frames`: hose networks (SPEC N1) — segments joined at junctions, written in a scene
//! file as a user's would be — against closed-form frame solutions (Euler–Bernoulli,
//! small loads; the cubic element is exact at its nodes). Each deflection is the linear
//! response: the run at load P and at P/2 extrapolated to zero load (Richardson,
//! δ_lin(P) = 4 δ(P/2) − δ(P), which removes the geometric non-linearity's
//! first-order term — in the in-plane L the column's corner turns by PL_hL_v/EI ≈ 5e-4
//! rad, enough to move the tip by 1e-4 of its linear deflection):
//!
//! * in-plane L-frame: a column of height L_v clamped at its foot, a beam of length L_h
//!   welded to its top at a right angle, a load P across the beam's tip in the frame's
//!   plane: δ = PL_h³/3EI + PL_h²L_v/EI + PL_v/EA (the beam's bending, the column bent by
//!   the moment PL_h, the column shortened);
//! * out-of-plane L-frame: an arm a along x clamped at its root, an arm b along y welded
//!   to its tip, a load P along z at b's tip: δ = P(a³ + b³)/3EI + P a b²/GJ (the first
//!   arm twisted by Pb);
//! * symmetric T: a stem L_s clamped at its root, two arms L_a welded to its tip on
//!   either side, a load P on each arm tip: δ = 2PL_s³/3EI + PL_a³/3EI, both tips alike;
//! * the out-of-plane L with a junction body: arm b starts at an outlet c beside arm a's
//!   tip, a rigid piece between them: δ = P(a³ + b³)/3EI + P a (b + c)²/GJ.

use crate::harness::{clamp, dead_load, settle_to};
use crate::Check;
use glam::DVec3;
use pliant_core::{Model, State};

/// Elements per segment.
pub(super) const ELEMENTS: usize = 20;
/// Section stiffnesses [N, N·m²] given directly (a cable-like section).
pub(super) const EA: f64 = 2.0e3;
pub(super) const EI: f64 = 0.05;
pub(super) const GJ: f64 = 0.04;
/// Small-load ratio PL²/EI with L = 1 m.
const LAMBDA: f64 = 1e-3;
/// Linear checks: the element is exact at its nodes, the extrapolation leaves terms of
/// order λ² and the rest tolerance 1e-6 of the load.
const TOLERANCE: f64 = 1e-4;

/// A scene of straight segments `(name, start, end)` (metres) joined by `junctions`
/// (TOML text), without gravity.
pub(super) fn network(segments: &[(&str, DVec3, DVec3)], junctions: &str) -> Result<Model, String> {
    network_with(segments, junctions, DVec3::ZERO, (EA, EI, GJ))
}

/// [`network`] under `gravity` \[m/s²\], the segments' section stiffnesses `(EA, EI, GJ)`
/// given.
pub(super) fn network_with(
    segments: &[(&str, DVec3, DVec3)],
    junctions: &str,
    gravity: DVec3,
    (ea, ei, gj): (f64, f64, f64),
) -> Result<Model, String> {
    let mut text = format!(
        r#"
format = "pliant-scene"
version = 1
name = "frame validation"
length_unit = "m"
[simulation]
gravity = [{}, {}, {}]
damping_mass_per_s = 0
"#,
        gravity.x, gravity.y, gravity.z
    );
    for (name, a, b) in segments {
        text += &format!(
            r#"
[[hoses]]
name = "{name}"
material = "hose1"
section = {{ d_inner = 0, d_outer = 0.01, ea_n = {ea}, ei1_n_m2 = {ei}, ei2_n_m2 = {ei}, gj_n_m2 = {gj} }}
elements = {ELEMENTS}
start = [{}, {}, {}]
path = [{{ line = {{ to = [{}, {}, {}] }} }}]
"#,
            a.x, a.y, a.z, b.x, b.y, b.z
        );
    }
    text += junctions;
    let scene =
        pliant_scene::load_scene_str(&text, "frames validation").map_err(|e| e.to_string())?;
    scene.build_model()
}

/// Global index of the last node of hose `h`.
pub(super) fn tip(model: &Model, h: usize) -> usize {
    let info = &model.hoses[h];
    info.first_node + info.node_count - 1
}

/// The linear displacement of each node in `watch` under dead `loads` (node, force), the
/// first node of hose 0 clamped: 4 d(loads/2) − d(loads) (see the module doc).
fn displaced(
    model: &Model,
    loads: &[(usize, DVec3)],
    watch: &[usize],
) -> Result<Vec<DVec3>, String> {
    let half: Vec<(usize, DVec3)> = loads.iter().map(|&(i, f)| (i, 0.5 * f)).collect();
    let full = displaced_under(model, loads, watch)?;
    let halved = displaced_under(model, &half, watch)?;
    // d(P) = P a + P² b → P a = 4 d(P/2) − d(P)
    Ok(full
        .iter()
        .zip(&halved)
        .map(|(f, h)| 4.0 * *h - *f)
        .collect())
}

/// The displacement of each node in `watch` under dead `loads` (node, force), the first
/// node of hose 0 clamped.
fn displaced_under(
    model: &Model,
    loads: &[(usize, DVec3)],
    watch: &[usize],
) -> Result<Vec<DVec3>, String> {
    let state = at_rest_under(model, loads, 1)?;
    Ok(watch
        .iter()
        .map(|&i| state.x[i] - model.rest_x[i])
        .collect())
}

/// The network at rest under dead `loads` (node, force), the first node of hose 0
/// clamped; the loads grow in `increments` equal steps, each brought to rest, so that the
/// solver follows the equilibrium path from the rest shape.
pub(super) fn at_rest_under(
    model: &Model,
    loads: &[(usize, DVec3)],
    increments: usize,
) -> Result<State, String> {
    let mut state = State::at_rest(model);
    clamp(&mut state, 0);
    let total: f64 = loads.iter().map(|(_, force)| force.length()).sum();
    let mut active = Vec::with_capacity(loads.len());
    for k in 1..=increments {
        for id in active.drain(..) {
            state.loads.remove(id);
        }
        let scale = k as f64 / increments as f64;
        for &(node, force) in loads {
            active.push(state.loads.add(dead_load(node, scale * force, DVec3::ZERO)));
        }
        settle_to(model, &mut state, total, 1.0, 1e-6)?;
    }
    Ok(state)
}

/// A `[[junctions]]` table welding the given hose ends `(hose, "start" | "end")`.
pub(super) fn weld(name: &str, ends: &[(&str, &str)]) -> String {
    let ends: Vec<String> = ends
        .iter()
        .map(|(h, e)| format!("{{ hose = \"{h}\", end = \"{e}\" }}"))
        .collect();
    format!(
        "\n[[junctions]]\nname = \"{name}\"\nends = [{}]\n",
        ends.join(", ")
    )
}

fn in_plane_l(out: &mut Vec<Check>) -> Result<(), String> {
    let (lv, lh) = (0.6, 0.8);
    let model = network(
        &[
            ("column", DVec3::ZERO, DVec3::new(0.0, 0.0, lv)),
            ("beam", DVec3::new(0.0, 0.0, lv), DVec3::new(lh, 0.0, lv)),
        ],
        &weld("corner", &[("column", "end"), ("beam", "start")]),
    )?;
    let p = LAMBDA * EI;
    let t = tip(&model, 1);
    let d = displaced(&model, &[(t, DVec3::new(0.0, 0.0, -p))], &[t])?[0];
    let exact = p * lh.powi(3) / (3.0 * EI) + p * lh * lh * lv / EI + p * lv / EA;
    out.push(Check::relative(
        "frames",
        "in-plane L-frame tip deflection / (PL_h³/3EI + PL_h²L_v/EI + PL_v/EA)",
        -d.z / exact,
        1.0,
        TOLERANCE,
    ));
    Ok(())
}

/// The out-of-plane L, arm b starting `c` beside arm a's tip (0: welded; else joined by
/// a junction body).
fn out_of_plane_l(out: &mut Vec<Check>, c: f64) -> Result<(), String> {
    let (a, b) = (0.7, 0.5);
    let joint = if c == 0.0 {
        weld("corner", &[("a", "end"), ("b", "start")])
    } else {
        weld("corner", &[("a", "end"), ("b", "start")]) + "body = { mass_kg = 0.01 }\n"
    };
    let model = network(
        &[
            ("a", DVec3::ZERO, DVec3::new(a, 0.0, 0.0)),
            ("b", DVec3::new(a, c, 0.0), DVec3::new(a, c + b, 0.0)),
        ],
        &joint,
    )?;
    let p = LAMBDA * EI;
    let t = tip(&model, 1);
    let d = displaced(&model, &[(t, DVec3::new(0.0, 0.0, p))], &[t])?[0];
    let exact = p * (a.powi(3) + b.powi(3)) / (3.0 * EI) + p * a * (b + c).powi(2) / GJ;
    let what = if c == 0.0 {
        "out-of-plane L-frame tip deflection / (P(a³ + b³)/3EI + Pab²/GJ)"
    } else {
        "L-frame with a junction body: tip deflection / (P(a³ + b³)/3EI + Pa(b + c)²/GJ)"
    };
    out.push(Check::relative("frames", what, d.z / exact, 1.0, TOLERANCE));
    Ok(())
}

fn symmetric_t(out: &mut Vec<Check>) -> Result<(), String> {
    let (ls, la) = (0.6, 0.4);
    let end = DVec3::new(ls, 0.0, 0.0);
    let model = network(
        &[
            ("stem", DVec3::ZERO, end),
            ("left", end, end + DVec3::new(0.0, la, 0.0)),
            ("right", end, end - DVec3::new(0.0, la, 0.0)),
        ],
        &weld(
            "tee",
            &[("stem", "end"), ("left", "start"), ("right", "start")],
        ),
    )?;
    let p = LAMBDA * EI;
    let (l, r) = (tip(&model, 1), tip(&model, 2));
    let load = DVec3::new(0.0, 0.0, -p);
    let d = displaced(&model, &[(l, load), (r, load)], &[l, r])?;
    let exact = 2.0 * p * ls.powi(3) / (3.0 * EI) + p * la.powi(3) / (3.0 * EI);
    out.push(Check::relative(
        "frames",
        "symmetric T: left tip deflection / (2PL_s³/3EI + PL_a³/3EI)",
        -d[0].z / exact,
        1.0,
        TOLERANCE,
    ));
    out.push(Check::relative(
        "frames",
        "symmetric T: right tip deflection / (2PL_s³/3EI + PL_a³/3EI)",
        -d[1].z / exact,
        1.0,
        TOLERANCE,
    ));
    Ok(())
}

pub fn run() -> Vec<Check> {
    let mut out = Vec::new();
    type Part = fn(&mut Vec<Check>) -> Result<(), String>;
    let parts: [(&str, Part); 4] = [
        ("in-plane L-frame", in_plane_l),
        ("out-of-plane L-frame", |out| out_of_plane_l(out, 0.0)),
        ("symmetric T", symmetric_t),
        ("L-frame with a junction body", |out| {
            out_of_plane_l(out, 0.05)
        }),
    ];
    for (name, part) in parts {
        if let Err(e) = part(&mut out) {
            out.push(Check::failed("frames", name, &e));
        }
    }
    out
}
