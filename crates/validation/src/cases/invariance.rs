//! `invariance`: rigid motions produce no internal loads. A curved hose (an arc with a
//! twist-free frame) is translated and rotated by angles up to 350° about skew axes; every
//! nodal force must stay below 1e-9·EA and every moment below 1e-9·EA·l₀.

use crate::harness::{hose1, static_settings};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::rod::forces::internal_loads;
use pliant_core::rod::inelastic::HistoryView;
use pliant_core::rod::node_view::NodeView;
use pliant_core::{HoseSpec, Model, WorldSpec};

pub fn run() -> Vec<Check> {
    let (mat, sec) = hose1();
    let nodes: Vec<DVec3> = (0..=24)
        .map(|i| {
            let a = i as f64 * 0.1;
            DVec3::new(0.3 * a.sin(), 0.3 * (1.0 - a.cos()), 0.02 * a)
        })
        .collect();
    let hose = HoseSpec {
        name: "arc".into(),
        material: mat.clone(),
        nodes,
        sections: vec![sec],
        normal_hint: None,
    };
    let model = Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: Vec::new(),
        settings: static_settings(),
    })
    .expect("arc builds");
    let ea = mat.e_tension * sec.area();
    let l0 = model.elements[0].rest_length;
    let n = model.node_count();
    let zero = vec![DVec3::ZERO; n];
    let (mut f, mut m) = (zero.clone(), zero.clone());
    let mut worst_f: f64 = 0.0;
    let mut worst_m: f64 = 0.0;
    let motions = [
        (DVec3::new(1.0, 2.0, 3.0), 0.5),
        (DVec3::new(-1.0, 0.3, 0.2), 3.0),
        (DVec3::new(0.2, 1.0, -0.7), 200f64.to_radians()),
        (DVec3::new(0.0, 0.0, 1.0), 350f64.to_radians()),
    ];
    for (axis, angle) in motions {
        let r = DQuat::from_axis_angle(axis.normalize(), angle);
        let shift = DVec3::new(5.0, -2.0, 0.7);
        let x: Vec<DVec3> = model.rest_x.iter().map(|p| r * *p + shift).collect();
        let q: Vec<DQuat> = model.rest_q.iter().map(|p| r * *p).collect();
        internal_loads(
            &model,
            &NodeView {
                x: &x,
                q: &q,
                v: &zero,
                w: &zero,
                inelastic_history: HistoryView::NONE,
            },
            0.0,
            &mut f,
            &mut m,
        );
        worst_f = f.iter().map(|v| v.length()).fold(worst_f, f64::max);
        worst_m = m.iter().map(|v| v.length()).fold(worst_m, f64::max);
    }
    vec![
        Check::with_error(
            "invariance",
            "max nodal force / EA",
            worst_f / ea,
            0.0,
            worst_f / ea,
            1e-9,
        ),
        Check::with_error(
            "invariance",
            "max nodal moment / (EA*l0)",
            worst_m / (ea * l0),
            0.0,
            worst_m / (ea * l0),
            1e-9,
        ),
    ]
}
