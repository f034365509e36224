//! Hose–hose contact in `pliant bench --only contact`: a grid of hoses lying across each
//! other, timed with and without hose–hose contact at fixed steps of its world.
//!
//! The world ([`crossed_grid`]): five hoses along x and, 1 mm above them, five along y,
//! each of 30 elements of library material 1, clamped at both ends (position and
//! orientation). Under gravity each hose sags by up to ≈ 24 mm (clamped–clamped,
//! q L⁴ / 384 EI), so the upper layer falls onto the lower one and rests on it at the 25
//! crossings (SPEC L5 penalty contact between beam capsules, [`pliant_core::contact::hose_hose`]).
//! Without contact (`model.hose_contact.active = false`, no broad phase either) the
//! upper layer falls through the lower one; the elements do the same work.
//!
//! Two windows, each timed in five chunks (median), as for the rigid floor
//! ([`crate::bench_contact_phases`]):
//! - **falling**: steps 1 000–6 000, the upper layer landing and bouncing on the lower
//!   (≈ 5–9 pairs in contact);
//! - **lying**: steps 40 000–45 000, the layers lying on each other (≈ 14–20 pairs in
//!   contact), still swaying gently: their kinetic energy has fallen to ≈ 1 % of its
//!   peak, not to rest.

use crate::bench::{self, ELEMENT_LENGTH};
use crate::bench_contact_phases::time_chunks;
use anyhow::{bail, Context, Result};
use glam::DVec3;
use pliant_core::health;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{HoseSpec, Model, SimSettings, State, WorldSpec};
use serde::Serialize;

/// Hoses per layer of the grid.
pub const HOSES_PER_LAYER: usize = 5;
/// Elements per hose.
pub const ELEMENTS: usize = 30;
/// Gap between the layers' surfaces at the start \[m\].
const LAYER_GAP: f64 = 0.001;

/// One window of steps, without and with hose–hose contact.
#[derive(Clone, Debug, Serialize)]
pub struct HoseContactPhase {
    pub name: &'static str,
    /// The window's first step and its length.
    pub first_step: u64,
    pub steps: u64,
    /// Wall ns per step (median of five chunks) without and with hose–hose contact.
    pub ns_per_step_free: f64,
    pub ns_per_step_contact: f64,
    /// ns_per_step_contact / ns_per_step_free.
    pub ratio: f64,
    /// Beam pairs in contact per step, over the window.
    pub pairs_in_contact_per_step: f64,
}

/// The grid's hoses and elements, and its windows.
#[derive(Clone, Debug, Serialize)]
pub struct HoseContactCost {
    pub hoses: usize,
    pub elements_per_hose: usize,
    pub phases: Vec<HoseContactPhase>,
}

/// The windows: name, first step, steps (`quick`: a smoke-test size).
fn windows(quick: bool) -> [(&'static str, u64, u64); 2] {
    if quick {
        [("falling", 200, 100), ("lying", 500, 100)]
    } else {
        [("falling", 1_000, 5_000), ("lying", 40_000, 5_000)]
    }
}

/// The grid of hoses lying across each other (see the module doc): the model and its
/// initial state, every hose straight and clamped at both ends.
pub fn crossed_grid() -> Result<(Model, State)> {
    let (material, section) = bench::material_1()?;
    let radius = 0.5 * section.d_outer;
    let length = ELEMENTS as f64 * ELEMENT_LENGTH;
    let straight = |name: String, start: DVec3, along: DVec3| HoseSpec {
        name,
        material: material.clone(),
        nodes: (0..=ELEMENTS)
            .map(|i| start + along * (i as f64 * ELEMENT_LENGTH))
            .collect(),
        sections: vec![section],
        normal_hint: Some(DVec3::Z),
    };
    let spacing = 0.1;
    let span = (HOSES_PER_LAYER - 1) as f64 * spacing;
    let mut hoses: Vec<HoseSpec> = (0..HOSES_PER_LAYER)
        .map(|h| {
            straight(
                format!("lower{h}"),
                DVec3::new(0.0, spacing * h as f64, 0.0),
                DVec3::X,
            )
        })
        .collect();
    // the upper layer crosses the lower one at equal steps along it, centred on its span
    let (step_x, z) = (
        length / (HOSES_PER_LAYER + 1) as f64,
        2.0 * radius + LAYER_GAP,
    );
    hoses.extend((0..HOSES_PER_LAYER).map(|h| {
        let start = DVec3::new(step_x * (h + 1) as f64, 0.5 * (span - length), z);
        straight(format!("upper{h}"), start, DVec3::Y)
    }));
    let world = WorldSpec {
        hoses,
        rigid_parts: Vec::new(),
        settings: SimSettings::default(),
    };
    let model = Model::build(&world).context("building the hose-contact benchmark model")?;
    let mut state = State::at_rest(&model);
    for h in &model.hoses {
        for n in [h.first_node, h.first_node + h.element_count] {
            state.loads.add(LoadCase::Fix(Fix {
                node: n,
                position: state.x[n],
                orientation: state.q[n],
            }));
        }
    }
    Ok((model, state))
}

/// Per window: wall ns per step (median over the chunks) and pairs in contact per step,
/// with hose–hose contact on or off.
fn time_windows(contact: bool, quick: bool) -> Result<Vec<(f64, f64)>> {
    let (mut model, mut state) = crossed_grid()?;
    model.threads = 1;
    model.hose_contact.active = contact;
    let mut step = 0u64;
    let mut out = Vec::new();
    for (name, first, steps) in windows(quick) {
        bench::run_steps(&model, &mut state, first - step);
        let pairs = |s: &State| s.hose_contact.pairs_in_contact;
        let (ns, pairs, done) = time_chunks(&model, &mut state, steps, pairs);
        step = first + done;
        if let Err(d) = health::check(&model, &state) {
            bail!("hose-contact benchmark ({name} window) diverged: {d}");
        }
        out.push((ns, pairs));
    }
    Ok(out)
}

/// Measures both windows without and with hose–hose contact.
pub fn measure(quick: bool) -> Result<HoseContactCost> {
    let free = time_windows(false, quick)?;
    let contact = time_windows(true, quick)?;
    let phases = windows(quick)
        .iter()
        .zip(free.iter().zip(&contact))
        .map(
            |(&(name, first_step, steps), (&(f, _), &(c, pairs)))| HoseContactPhase {
                name,
                first_step,
                steps,
                ns_per_step_free: f,
                ns_per_step_contact: c,
                ratio: c / f,
                pairs_in_contact_per_step: pairs,
            },
        )
        .collect();
    Ok(HoseContactCost {
        hoses: 2 * HOSES_PER_LAYER,
        elements_per_hose: ELEMENTS,
        phases,
    })
}

/// One line per window, for the terminal.
pub fn render(cost: &HoseContactCost) -> String {
    let mut out = format!(
        "{} hoses × {} lying across each other, hose–hose contact over none:\n",
        cost.hoses, cost.elements_per_hose
    );
    for p in &cost.phases {
        out += &format!(
            "  {} (steps {}–{}): {:.0} ns/step without, {:.0} ns/step with contact \
             ({:.1} pairs in contact): ×{:.2}\n",
            p.name,
            p.first_step,
            p.first_step + p.steps,
            p.ns_per_step_free,
            p.ns_per_step_contact,
            p.pairs_in_contact_per_step,
            p.ratio
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid's upper layer comes to rest on the lower one: pairs in contact in both
    /// windows, and none without contact (the layers pass through each other).
    #[test]
    fn the_layers_touch_with_contact_and_not_without() {
        let (model, mut state) = crossed_grid().unwrap();
        assert_eq!(model.hoses.len(), 2 * HOSES_PER_LAYER);
        assert!(model.hose_contact.active);
        bench::run_steps(&model, &mut state, 3_000);
        assert!(
            state.hose_contact.pairs_in_contact >= HOSES_PER_LAYER,
            "{} pairs in contact",
            state.hose_contact.pairs_in_contact
        );
        health::check(&model, &state).unwrap();
    }
}
