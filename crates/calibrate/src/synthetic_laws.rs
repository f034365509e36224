//! Test curves of the inelastic laws made by the simulator itself, not by the fitters'
//! formulas, for the validation tests and the examples: the yielding tube's fibre
//! section ([`pliant_core::rod::fibre_section`]) bent or twisted and unloaded point by
//! point; a
//! relaxing beam element ([`pliant_core::rod::relaxation`]) stretched and held; a
//! hysteretic beam element ([`pliant_core::rod::hysteresis`]) bent back and forth — each
//! committed step by step through [`pliant_core::rod::inelastic::InelasticElements`] or
//! the section's own commit, as a simulation does.

use glam::{DQuat, DVec3};
use pliant_core::material::{Hysteresis, PronyTerm, YieldLaw};
use pliant_core::rod::element::{BeamElement, ElementEnds};
use pliant_core::rod::fibre_law::FibreLaw;
use pliant_core::rod::fibre_section::{Fibre, FibreSection};
use pliant_core::rod::inelastic::{HistoryView, InelasticElements};
use pliant_core::{Material, Section};
use std::fmt::Write as _;

/// The fibre section of a yielding tube as the simulator builds it (E the bending
/// modulus, G for Poisson's ratio `poisson`).
pub fn simulator_section(
    d_inner: f64,
    d_outer: f64,
    e: f64,
    poisson: f64,
    law: &YieldLaw,
) -> FibreSection {
    FibreSection::tube(
        d_inner,
        d_outer,
        FibreLaw::new(e, e / (2.0 * (1.0 + poisson)), law),
    )
}

/// The same fibre law on a finer grid (`radial` Gauss–Legendre 4-point intervals across
/// the wall, `angular` midpoint steps): the simulator's law with a smaller quadrature
/// error, to tell the fitter's error from the section's.
pub fn fine_section(
    d_inner: f64,
    d_outer: f64,
    e: f64,
    poisson: f64,
    law: &YieldLaw,
    (radial, angular): (usize, usize),
) -> FibreSection {
    const GAUSS_4: [(f64, f64); 4] = [
        (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
        (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    ];
    let (ri, ro) = (0.5 * d_inner, 0.5 * d_outer);
    let width = (ro - ri) / radial as f64;
    let step = std::f64::consts::TAU / angular as f64;
    let mut fibres = Vec::with_capacity(radial * 4 * angular);
    for interval in 0..radial {
        let mid = ri + (interval as f64 + 0.5) * width;
        for (s, w) in GAUSS_4 {
            let r = mid + 0.5 * width * s;
            for j in 0..angular {
                let phi = (j as f64 + 0.5) * step;
                fibres.push(Fibre {
                    y: r * phi.cos(),
                    z: r * phi.sin(),
                    r,
                    area: w * 0.5 * width * r * step,
                });
            }
        }
    }
    FibreSection {
        law: FibreLaw::new(e, e / (2.0 * (1.0 + poisson)), law),
        fibres,
    }
}

/// The bending moments of `section` bent through the curvatures `kappa` in order (about
/// one section axis), each committed as an accepted step.
pub fn bend_section(section: &FibreSection, kappa: &[f64]) -> Vec<f64> {
    load_section(section, kappa, 1)
}

/// The torques of `section` twisted through the twist rates `rate` in order, each
/// committed as an accepted step.
pub fn twist_section(section: &FibreSection, rate: &[f64]) -> Vec<f64> {
    load_section(section, rate, 0)
}

/// The section's moment about `axis` (0: twist, 1: bending about y) strained through
/// `values` of that component in order, each committed as an accepted step.
fn load_section(section: &FibreSection, values: &[f64], axis: usize) -> Vec<f64> {
    let mut history = vec![0.0; section.history_len()];
    values
        .iter()
        .map(|v| {
            let mut k = [0.0; 3];
            k[axis] = *v;
            let m = section.moments(pliant_core::autodiff::V3::new(k[0], k[1], k[2]), &history);
            section.commit(k, &mut history);
            if axis == 0 {
                m.x
            } else {
                m.y
            }
        })
        .collect()
}

/// Curvatures rising evenly from 0 to `kappa_max` in `up` steps, then falling to
/// `kappa_end` in `down` steps (a bending test past yield with unloading).
pub fn load_unload(kappa_max: f64, kappa_end: f64, up: usize, down: usize) -> Vec<f64> {
    (0..=up)
        .map(|i| kappa_max * i as f64 / up as f64)
        .chain((1..=down).map(|i| kappa_max + (kappa_end - kappa_max) * i as f64 / down as f64))
        .collect()
}

/// Curvatures cycling between ±`amplitude` from 0: `cycles` full cycles of `per_cycle`
/// points.
pub fn cycles(amplitude: f64, cycles: usize, per_cycle: usize) -> Vec<f64> {
    (0..=cycles * per_cycle)
        .map(|i| {
            let phase = i as f64 / per_cycle as f64; // 0 → 1 per cycle
            let tri = (4.0 * phase + 1.0).rem_euclid(4.0); // triangle wave from 0
            amplitude * if tri < 2.0 { tri - 1.0 } else { 3.0 - tri }
        })
        .collect()
}

fn element(
    material: &Material,
    section: &Section,
    length: f64,
) -> (InelasticElements, BeamElement) {
    let e = BeamElement::new(
        (0, 1),
        [DVec3::ZERO, DVec3::new(length, 0.0, 0.0)],
        [DQuat::IDENTITY; 2],
        section,
        material,
    );
    let mut elements = vec![e];
    let mut registry = InelasticElements::new();
    registry.add_hose(&mut elements, 0, material, |_| *section);
    (registry, elements.remove(0))
}

/// The axial force \[N\] of a relaxing element of `material` and `section` (length
/// 20 mm) stretched at t = 0 to `strain` and held, at the times `t` (increasing, from
/// 0), the history committed at each time as by an integrator's accepted steps.
pub fn held_strain_force(
    material: &Material,
    section: &Section,
    strain: f64,
    t: &[f64],
) -> Vec<f64> {
    let length = 0.02;
    let (registry, e) = element(material, section, length);
    let Some(inelastic) = e.inelastic else {
        return Vec::new();
    };
    let x = [DVec3::ZERO, DVec3::new(length * (1.0 + strain), 0.0, 0.0)];
    let q = [DQuat::IDENTITY; 2];
    let ends = ElementEnds::still(x, q);
    let mut history = vec![0.0; registry.history_len];
    registry.commit(
        std::slice::from_ref(&e),
        (&x[..], &q[..]),
        0.0,
        &mut history,
    );
    let mut last = 0.0;
    t.iter()
        .map(|t| {
            let age = t - last;
            let view = HistoryView {
                values: &history,
                age,
            };
            let force = registry.loads(&e, &inelastic, view, &ends, 0.0).force[1]
                .x
                .abs();
            registry.commit(
                std::slice::from_ref(&e),
                (&x[..], &q[..]),
                age,
                &mut history,
            );
            last = *t;
            force
        })
        .collect()
}

/// The moment \[N·m\] of a hysteretic element of `material` and `section` (length
/// 1 mm) bent (`axis` 1: about the section's y axis) or twisted (`axis` 0) uniformly
/// through the curvatures or twist rates `kappa` in order (end rotations ∓κ l/2), each
/// committed as an accepted step.
pub fn cyclic_moments(
    material: &Material,
    section: &Section,
    kappa: &[f64],
    axis: usize,
) -> Vec<f64> {
    let length = 0.001;
    let (registry, e) = element(material, section, length);
    let Some(inelastic) = e.inelastic else {
        return Vec::new();
    };
    let mut history = vec![0.0; registry.history_len];
    kappa
        .iter()
        .map(|k| {
            let mut half = DVec3::ZERO;
            half[axis.min(2)] = 0.5 * k * length;
            let x = [DVec3::ZERO, DVec3::new(length, 0.0, 0.0)];
            let q = [
                pliant_core::math::exp_map(-half),
                pliant_core::math::exp_map(half),
            ];
            let ends = ElementEnds::still(x, q);
            let view = HistoryView {
                values: &history,
                age: 0.0,
            };
            let m = registry.loads(&e, &inelastic, view, &ends, 0.0).moment[1][axis.min(2)];
            registry.commit(
                std::slice::from_ref(&e),
                (&x[..], &q[..]),
                0.0,
                &mut history,
            );
            -m
        })
        .collect()
}

/// A material of modulus `e` that relaxes by `terms`.
pub fn relaxing_material(e: f64, terms: &[PronyTerm]) -> Material {
    let mut m = Material::isotropic(e, 0.45, 1100.0);
    m.relaxation = terms.to_vec();
    m
}

/// A material of modulus `e` with Dahl friction `law`.
pub fn hysteretic_material(e: f64, law: Hysteresis) -> Material {
    let mut m = Material::isotropic(e, 0.45, 1100.0);
    m.hysteresis = Some(law);
    m
}

/// A CSV text of two columns with the header `header` and Gaussian noise of standard
/// deviation `noise` × the largest |y| added to y (seeded).
pub fn two_column_csv(header: &str, x: &[f64], y: &[f64], noise: f64, seed: u64) -> String {
    let mut rng = crate::synthetic::Rng::new(seed);
    let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut s = format!("{header}\n");
    for (x, y) in x.iter().zip(y) {
        let _ = writeln!(s, "{x:.12e},{:.12e}", y + noise * scale * rng.normal());
    }
    s
}
