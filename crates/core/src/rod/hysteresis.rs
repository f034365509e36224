//! Hysteretic elements (SPEC X2): the linear element plus a friction moment z per
//! component of its relative end rotation φ = θ_b − θ_a — the twist φₓ and the two
//! bending components φ_y, φ_z, each l₀ times the element's mean curvature (the uniform
//! mode of [`crate::rod::plastic_hinges`]) — acting as end moments ∓z.
//!
//! Each component follows Dahl's law ([`crate::material::Hysteresis`]),
//! dz/dφ = k (1 − s z/M_s), s = sgn(φ̇), k = M_s/φ_s, φ_s = κ_s l₀. It is rate
//! independent and, on a stretch where φ moves one way, integrates in closed form:
//!
//! z(φ) = s M_s − (s M_s − zⁿ) e^{−s (φ − φⁿ)/φ_s}
//!
//! from the committed (φⁿ, zⁿ). The element uses it exactly — every step moves φ one way
//! per component, s = sgn(φ − φⁿ) — so a loop under cycled curvature is the closed-form
//! one whatever the step (on a reversal inside a step the law takes the net motion).
//! At φ = φⁿ the direction of the last motion is kept (the tangent of a continued
//! loading); a virgin element takes s = +1, whose tangent k is the same both ways. The
//! loads are the gradient of the elastic energy plus the incremental potential
//! ∫ z dφ = s M_s Δ + (zⁿ − s M_s)(φ_s/s)(1 − e^{−s Δ/φ_s}), Δ = φ − φⁿ, and dual
//! numbers through the exponential give the consistent tangent.
//!
//! The history (φⁿ, zⁿ and the last direction, three values each) is committed once per
//! accepted step or converged equilibrium ([`crate::rod::inelastic`]).

use crate::autodiff::{Scalar, V3};
use crate::material::{DahlLaw, Hysteresis};
use crate::rod::element::{AxialShift, BeamElement, ElementLoadsOf, EndsOf};
use glam::{DQuat, DVec3};

/// History values of a hysteretic element: φⁿ (3), zⁿ (3), the last direction (3).
pub const HISTORY_LEN: usize = 9;

/// The committed state of one component.
#[derive(Clone, Copy, Debug)]
struct Committed {
    rotation: f64,
    moment: f64,
    direction: f64,
}

fn committed(history: &[f64], k: usize) -> Committed {
    Committed {
        rotation: history[k],
        moment: history[3 + k],
        direction: history[6 + k],
    }
}

/// Dahl's law of component `k` (0 twist, 1 and 2 bending) of `law` over an element of
/// rest length `l0`: (M_s, φ_s), or `None` where the component has no friction.
fn component(law: &Hysteresis, k: usize, l0: f64) -> Option<(f64, f64)> {
    let dahl: DahlLaw = if k == 0 { law.torsion? } else { law.bending };
    (dahl.moment > 0.0).then_some((dahl.moment, dahl.curvature * l0))
}

/// The direction s of a motion `delta` from the committed state (module doc).
fn direction(delta: f64, c: Committed) -> f64 {
    if delta > 0.0 {
        1.0
    } else if delta < 0.0 {
        -1.0
    } else if c.direction != 0.0 {
        c.direction
    } else {
        1.0
    }
}

/// Dahl's closed form z(φ) from the committed state (module doc).
#[inline]
fn friction_moment<T: Scalar>(phi: T, c: Committed, (m, phi_s): (f64, f64)) -> T {
    let delta = phi - c.rotation;
    let s = direction(delta.re(), c);
    let target = s * m;
    (delta * (-s / phi_s)).exp() * (c.moment - target) + target
}

/// The friction moments (z_x, z_y, z_z) at relative rotation `phi` (element axes).
fn friction_moments<T: Scalar>(law: &Hysteresis, l0: f64, history: &[f64], phi: V3<T>) -> V3<T> {
    let at = |k: usize, p: T| match component(law, k, l0) {
        Some(dahl) => friction_moment(p, committed(history, k), dahl),
        None => T::cst(0.0),
    };
    V3::new(at(0, phi.x), at(1, phi.y), at(2, phi.z))
}

/// The loads of hysteretic `element` (law `law`, committed history `history`) —
/// [`BeamElement::loads_of`] with the friction moments as end moments ∓z (module doc),
/// generic so that dual numbers give its tangent.
#[inline]
pub fn loads_of<T: Scalar>(
    element: &BeamElement,
    law: &Hysteresis,
    history: &[f64],
    (x, q, v, w): EndsOf<T>,
    beta: f64,
) -> ElementLoadsOf<T> {
    let l0 = element.axis_length;
    element.loads_with(x, q, v, w, beta, AxialShift::NONE, |theta, damped| {
        let (ma, mb) = element.end_moments(theta[0] + damped[0], theta[1] + damped[1]);
        let z = friction_moments(law, l0, history, theta[1] - theta[0]);
        (ma - z, mb + z)
    })
}

/// The relative end rotation φ = θ_b − θ_a of `element` at its ends' poses.
fn relative_rotation(element: &BeamElement, x: [DVec3; 2], q: [DQuat; 2]) -> DVec3 {
    let d = element.deformation(x, q);
    d.bend_twist[1] - d.bend_twist[0]
}

/// Accepts the ends' poses as the end of a step: each component's friction moment moves
/// to Dahl's closed form at the new rotation, which with the direction of the motion
/// becomes the committed state.
pub fn commit(
    element: &BeamElement,
    law: &Hysteresis,
    (x, q): ([DVec3; 2], [DQuat; 2]),
    history: &mut [f64],
) {
    let phi = relative_rotation(element, x, q).to_array();
    for (k, phi) in phi.into_iter().enumerate() {
        let c = committed(history, k);
        let delta = phi - c.rotation;
        if let Some(dahl) = component(law, k, element.axis_length) {
            if delta != 0.0 {
                history[3 + k] = friction_moment(phi, c, dahl);
                history[6 + k] = direction(delta, c);
            }
        }
        history[k] = phi;
    }
}

/// The strain energy of hysteretic `element` at its ends' poses \[J\]: the elastic
/// energy plus, if `incremental`, the friction's incremental potential from the
/// committed history (the static solver's line search: its gradient is the loads), else
/// the energy the friction holds in its presliding spring, z²/2k per component.
pub fn strain_energy(
    element: &BeamElement,
    law: &Hysteresis,
    history: &[f64],
    (x, q): ([DVec3; 2], [DQuat; 2]),
    incremental: bool,
) -> f64 {
    let d = element.deformation(x, q);
    let elastic = element.energy_at(element.axial_strain(&d), d.bend_twist);
    let phi = (d.bend_twist[1] - d.bend_twist[0]).to_array();
    let mut friction = 0.0;
    for (k, phi) in phi.into_iter().enumerate() {
        let Some((m, phi_s)) = component(law, k, element.axis_length) else {
            continue;
        };
        let c = committed(history, k);
        friction += if incremental {
            let delta = phi - c.rotation;
            let s = direction(delta, c);
            s * m * delta - (c.moment - s * m) * (phi_s / s) * (-s * delta / phi_s).exp_m1()
        } else {
            let z = friction_moment(phi, c, (m, phi_s));
            0.5 * z * z * phi_s / m
        };
    }
    elastic + friction
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::exp_map;
    use crate::rod::element::ElementEnds;
    use crate::rod::inelastic::{HistoryView, InelasticElements};
    use crate::rod::test_elements::check_tangent_and_potential;
    use crate::{Material, Section};

    const LAW: Hysteresis = Hysteresis {
        bending: DahlLaw {
            moment: 0.02,
            curvature: 0.5,
        },
        torsion: Some(DahlLaw {
            moment: 0.01,
            curvature: 0.8,
        }),
    };
    const L0: f64 = 0.02;

    fn hysteretic_element() -> (InelasticElements, BeamElement) {
        let mut mat = Material::isotropic(10e6, 0.45, 1100.0);
        mat.hysteresis = Some(LAW);
        let sec = Section::new(0.01, 0.016);
        let e = BeamElement::new(
            (0, 1),
            [DVec3::ZERO, DVec3::new(L0, 0.0, 0.0)],
            [DQuat::IDENTITY; 2],
            &sec,
            &mat,
        );
        let mut elements = vec![e];
        let mut registry = InelasticElements::new();
        registry.add_hose(&mut elements, 0, &mat, |_| sec);
        (registry, elements.remove(0))
    }

    /// The element bent in its x–y plane to a uniform curvature κ: node b on the arc,
    /// turned by κ l₀ about z.
    fn arc(kappa: f64) -> ([DVec3; 2], [DQuat; 2]) {
        let a = kappa * L0;
        let b = if kappa == 0.0 {
            DVec3::new(L0, 0.0, 0.0)
        } else {
            DVec3::new(a.sin() / kappa, (1.0 - a.cos()) / kappa, 0.0)
        };
        ([DVec3::ZERO, b], [DQuat::IDENTITY, exp_map(DVec3::Z * a)])
    }

    /// Dahl's loop from virgin under a cycled curvature, exactly: the friction moment at
    /// every committed curvature is the closed form of its branch, and the steady loop's
    /// area is 2 [2 κ_a M_s − (M_s + z_a) κ_s (1 − e^{−2κ_a/κ_s})], z_a = M_s tanh(κ_a/κ_s).
    #[test]
    fn cycled_curvature_traces_dahls_closed_form_loop() {
        let (registry, e) = hysteretic_element();
        let inelastic = e.inelastic.expect("hysteretic");
        let (m, ks) = (LAW.bending.moment, LAW.bending.curvature);
        let amplitude = 1.5;
        let mut history = vec![0.0; registry.history_len];
        // the exact branch through the last turning point (κ₀, z₀) in direction s
        let (mut k0, mut z0, mut s) = (0.0, 0.0, 1.0);
        let steps = 40;
        let mut kappa: f64 = 0.0;
        let mut area = 0.0;
        let mut previous_moment = 0.0;
        for i in 1..=steps * 9 {
            // 0 → κ_a, then four half cycles between ±κ_a
            let phase = i as f64 / steps as f64;
            let next = if phase <= 1.0 {
                amplitude * phase
            } else {
                let half = ((phase - 1.0) / 2.0).floor();
                let u = ((phase - 1.0) / 2.0).fract();
                let sign = if half as i64 % 2 == 0 { 1.0 } else { -1.0 };
                sign * amplitude * (1.0 - 2.0 * u)
            };
            if (next - kappa) * s < 0.0 {
                let z_turn = s * m - (s * m - z0) * (-s * (kappa - k0) / ks).exp();
                (k0, z0, s) = (kappa, z_turn, -s);
            }
            let (x, q) = arc(next);
            registry.commit(
                std::slice::from_ref(&e),
                (&x[..], &q[..]),
                0.0,
                &mut history,
            );
            let view = HistoryView {
                values: &history,
                age: 0.0,
            };
            let ends = ElementEnds::still(x, q);
            let l = registry.loads(&e, &inelastic, view, &ends, 0.0);
            // the internal moment at node b about z, less the linear element's
            let friction = e.loads(&ends, 0.0).moment[1].z - l.moment[1].z;
            let exact = s * m - (s * m - z0) * (-s * (next - k0) / ks).exp();
            assert!(
                (friction - exact).abs() < 2e-6 * m,
                "κ {next}: {friction} vs {exact}"
            );
            if phase > 5.0 {
                area += 0.5 * (friction + previous_moment) * (next - kappa);
            }
            previous_moment = friction;
            kappa = next;
        }
        // the second full cycle (phase 5 → 9) against the steady loop; the trapezoid rule
        // on 160 steps of the loop's smooth branches is good to 2.3e-4
        let za = m * (amplitude / ks).tanh();
        let e2 = (-2.0 * amplitude / ks).exp();
        let steady = 2.0 * (2.0 * amplitude * m - (m + za) * ks * (1.0 - e2));
        assert!(
            (area.abs() - steady).abs() < 1e-3 * steady,
            "loop area {area} vs {steady}"
        );
    }

    /// The tangent is the derivative of the loads (central differences), and the loads
    /// are minus the gradient of the incremental potential, after commits in both
    /// directions.
    #[test]
    fn the_tangent_and_the_potential_match_the_loads() {
        let (registry, e) = hysteretic_element();
        let inelastic = e.inelastic.expect("hysteretic");
        let mut history = vec![0.0; registry.history_len];
        for pose in [
            (
                [DVec3::ZERO, DVec3::new(0.0199, 0.0001, 0.0)],
                [exp_map(DVec3::new(0.0, -0.01, 0.02)), DQuat::IDENTITY],
            ),
            (
                [DVec3::ZERO, DVec3::new(0.0199, 0.0002, 0.0)],
                [exp_map(DVec3::new(0.004, 0.02, -0.01)), DQuat::IDENTITY],
            ),
        ] {
            registry.commit(
                std::slice::from_ref(&e),
                (&pose.0[..], &pose.1[..]),
                0.0,
                &mut history,
            );
        }
        let (x, q) = (
            [DVec3::ZERO, DVec3::new(0.0201, 0.0003, -0.0002)],
            [
                exp_map(DVec3::new(0.01, -0.02, 0.01)),
                exp_map(DVec3::new(-0.01, 0.025, -0.012)),
            ],
        );
        let view = HistoryView {
            values: &history,
            age: 0.0,
        };
        check_tangent_and_potential(&registry, (&e, &inelastic), view, (x, q), 1e-8);
    }
}
