//! Random elements and configurations for the tests of the element kernel and its
//! tangent (test builds only).

use crate::math::exp_map;
use crate::rod::element::{rotate, BeamElement, ElementEnds};
use crate::section::SectionProperties;
use crate::{Material, Section};
use glam::{DQuat, DVec3};

/// splitmix64: a small deterministic generator for the random configurations.
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
    pub fn vec(&mut self, r: f64) -> DVec3 {
        DVec3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }
    /// A random rotation vector of length up to `max`.
    pub fn rotation(&mut self, max: f64) -> DVec3 {
        let axis = loop {
            let v = self.vec(1.0);
            if v.length() > 0.1 && v.length() <= 1.0 {
                break v.normalize();
            }
        };
        axis * self.range(0.0, max)
    }
}

/// A random element between nodes 2k and 2k+1 (so that lanes are separate elements),
/// with a random rest shape, a bimodular material and either a tube or a section with
/// given, unequal bending stiffnesses.
pub fn random_element(rng: &mut Rng, k: usize) -> BeamElement {
    let l0 = rng.range(0.01, 0.2);
    let rest_a = rng.vec(1.0);
    let rest_b = rest_a + rng.rotation(std::f64::consts::PI).normalize() * l0;
    let rest_q = [
        exp_map(rng.rotation(std::f64::consts::PI)),
        exp_map(rng.rotation(std::f64::consts::PI)),
    ];
    let material = Material {
        e_tension: rng.range(5e6, 2e7),
        e_compression: rng.range(5e6, 2e7),
        e_bending: None,
        poisson: 0.45,
        density: 1000.0,
        plasticity: None,
        relaxation: Vec::new(),
        hysteresis: None,
    };
    let mut section = Section::new(0.01, 0.016);
    if rng.next() < 0.5 {
        section.given.bending = [Some(rng.range(0.01, 0.5)), Some(rng.range(0.01, 0.5))];
        section.given.torsion = Some(rng.range(0.01, 0.5));
    }
    let props = SectionProperties::of(&section, &material);
    BeamElement::with_properties((2 * k, 2 * k + 1), [rest_a, rest_b], rest_q, &props)
}

/// A deformed, moving configuration of `e`: end rotations relative to the rest frames
/// up to `bend` rad, the chord stretched or shortened by up to 20 %, then the whole
/// element turned by a random large rotation and moved.
pub fn random_ends(
    rng: &mut Rng,
    e: &BeamElement,
    rest: ([DVec3; 2], [DQuat; 2]),
    bend: f64,
) -> ElementEnds {
    let (rest_x, rest_q) = rest;
    let whole = exp_map(rng.rotation(std::f64::consts::PI));
    let shift = rng.vec(1.0);
    let chord = (rest_x[1] - rest_x[0]) * rng.range(0.8, 1.2) + rng.vec(0.05 * e.rest_length);
    let x = [shift, shift + whole * chord];
    let q = [0, 1].map(|i| (whole * exp_map(rng.rotation(bend)) * rest_q[i]).normalize());
    ElementEnds {
        x,
        q,
        v: [rng.vec(2.0), rng.vec(2.0)],
        w: [rng.vec(50.0), rng.vec(50.0)],
    }
}

/// The ends' poses with increment `s` in the element's increment `j` (0–11: δx_a, δθ_a,
/// δx_b, δθ_b), for central differences against the tangent.
pub fn perturbed_pose(
    (x, q): ([DVec3; 2], [DQuat; 2]),
    j: usize,
    s: f64,
) -> ([DVec3; 2], [DQuat; 2]) {
    let (mut xp, mut qp) = (x, q);
    let node = j / 6;
    let mut d = DVec3::ZERO;
    d[j % 3] = s;
    if j % 6 < 3 {
        xp[node] += d;
    } else {
        qp[node] = rotate(q[node], d);
    }
    (xp, qp)
}

/// Checks an inelastic element at `pose` under `view`: its tangent is the derivative of
/// its loads (central differences of step `h`, to 1e-5 of the largest entry) and its loads
/// are minus the gradient of its incremental potential (to 1e-4 of the largest load).
pub fn check_tangent_and_potential(
    registry: &crate::rod::inelastic::InelasticElements,
    (e, inelastic): (&BeamElement, &crate::rod::inelastic::Inelastic),
    view: crate::rod::inelastic::HistoryView,
    (x, q): ([DVec3; 2], [DQuat; 2]),
    h: f64,
) {
    use crate::rod::element::ElementLoads;
    let flat = ElementLoads::to_array;
    let ends = ElementEnds::still(x, q);
    let (_, k) =
        crate::rod::tangent::inelastic_tangent(registry, (e, inelastic), view, &ends, 0.0, 0.0);
    let kmax = k.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let base = flat(&registry.loads(e, inelastic, view, &ends, 0.0));
    for j in 0..12 {
        let at = |s: f64| {
            let (xp, qp) = perturbed_pose((x, q), j, s);
            let l = registry.loads(e, inelastic, view, &ElementEnds::still(xp, qp), 0.0);
            (
                flat(&l),
                registry.strain_energy(e, inelastic, view, (xp, qp), true),
            )
        };
        let ((p, wp), (m, wm)) = (at(h), at(-h));
        for i in 0..12 {
            let fd = -(p[i] - m[i]) / (2.0 * h);
            assert!((fd - k[(i, j)]).abs() < 1e-5 * kmax, "K[{i},{j}]");
        }
        let grad = -(wp - wm) / (2.0 * h);
        let scale = base.iter().fold(1e-3_f64, |m, v| m.max(v.abs()));
        assert!(
            (grad - base[j]).abs() < 1e-4 * scale,
            "load {j}: {} vs {grad}",
            base[j]
        );
    }
}
