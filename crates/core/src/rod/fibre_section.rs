//! A yielding cross-section as fibres (SPEC X1): the circular tube (or solid rod) cut
//! into points that each carry the fibre law ([`crate::rod::fibre_law`]), so that the
//! section's moments are the integral of the fibre stresses (a fibre-section model,
//! e.g. Spacone, Filippou & Taucer 1996, EESD 25):
//!
//! * strains of the fibre at (y, z), radius r: ε = κ_y z − κ_z y, γ = τ r, with κ_y, κ_z
//!   the curvatures about the section axes and τ the twist rate;
//! * M_y = Σ σ z A_f, M_z = −Σ σ y A_f, T = Σ τ r A_f — the derivatives of the section's
//!   energy by κ_y, κ_z and τ (so the element's loads stay a gradient).
//!
//! Quadrature: composite Gauss–Legendre in the radius (weight r dr; four points on each
//! of up to four intervals, one per quarter of the outer radius the wall spans) and the
//! midpoint rule in the angle. It integrates A, I and J exactly (polynomials in r of degree ≤ 2n − 1, sin² over
//! n_θ ≥ 3 equal steps), so the elastic section is the tube's EI and GJ to rounding; past
//! yield the stress has a kink at the elastic core, where the rule is second order (the
//! validation compares the moment–curvature curve with its closed form,
//! [`crate::rod::plastic_moment`]).
//!
//! The fibres see bending and torsion; the axial force stays elastic (bimodular, M3) —
//! for a metal line the axial stress is a small fraction of σ_y.

use crate::autodiff::{Scalar, V3};
use crate::rod::fibre_law::FibreLaw;

/// Radial Gauss–Legendre points per radial interval.
pub const RADIAL_POINTS: usize = 4;
/// Angular points (midpoint rule).
pub const ANGULAR_POINTS: usize = 32;
/// History values per fibre: the plastic strains ε_p, γ_p.
pub const HISTORY_PER_FIBRE: usize = 2;

/// Gauss–Legendre abscissae and weights on [−1, 1], four points (Abramowitz & Stegun,
/// table 25.4).
const GAUSS_4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// One fibre: where it lies and the area it stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fibre {
    /// Position along section axis 1 (y) \[m\].
    pub y: f64,
    /// Position along section axis 2 (z) \[m\].
    pub z: f64,
    /// Distance from the axis \[m\].
    pub r: f64,
    /// Area \[m²\].
    pub area: f64,
}

/// A yielding circular section: its fibres and their law.
#[derive(Clone, Debug, PartialEq)]
pub struct FibreSection {
    pub law: FibreLaw,
    pub fibres: Vec<Fibre>,
}

impl FibreSection {
    /// The fibres of a tube of inner and outer diameters `d_inner` (0: solid) and
    /// `d_outer` \[m\] with the fibre law `law`.
    pub fn tube(d_inner: f64, d_outer: f64, law: FibreLaw) -> Self {
        let (ri, ro) = (0.5 * d_inner, 0.5 * d_outer);
        // composite rule: one interval per quarter of the radius the wall spans (a
        // solid rod's elastic core needs the points a thin wall does not)
        let intervals = ((4.0 * (ro - ri) / ro).ceil() as usize).clamp(1, 4);
        let width = (ro - ri) / intervals as f64;
        let step = std::f64::consts::TAU / ANGULAR_POINTS as f64;
        let mut fibres = Vec::with_capacity(intervals * RADIAL_POINTS * ANGULAR_POINTS);
        for interval in 0..intervals {
            let (mid, half) = (ri + (interval as f64 + 0.5) * width, 0.5 * width);
            for (s, w) in GAUSS_4 {
                let r = mid + half * s;
                let area = w * half * r * step;
                for j in 0..ANGULAR_POINTS {
                    let phi = (j as f64 + 0.5) * step;
                    fibres.push(Fibre {
                        y: r * phi.cos(),
                        z: r * phi.sin(),
                        r,
                        area,
                    });
                }
            }
        }
        Self { law, fibres }
    }

    /// History values one hinge of this section keeps.
    pub fn history_len(&self) -> usize {
        HISTORY_PER_FIBRE * self.fibres.len()
    }

    /// The fibre strains at section strains `k` = (τ, κ_y, κ_z).
    #[inline(always)]
    fn strains<T: Scalar>(f: &Fibre, k: V3<T>) -> (T, T) {
        (k.y * f.z - k.z * f.y, k.x * f.r)
    }

    /// The section's moments (T, M_y, M_z) at section strains `k` = (τ, κ_y, κ_z) —
    /// twist rate and curvatures \[1/m\] measured from the rest shape — from the committed
    /// plastic strains `history` (module doc).
    #[inline]
    pub fn moments<T: Scalar>(&self, k: V3<T>, history: &[f64]) -> V3<T> {
        let zero = T::cst(0.0);
        let mut m = V3::new(zero, zero, zero);
        for (f, h) in self
            .fibres
            .iter()
            .zip(history.chunks_exact(HISTORY_PER_FIBRE))
        {
            let (eps, gamma) = Self::strains(f, k);
            let r = self.law.respond(eps, gamma, [h[0], h[1]]);
            m.x = m.x + r.tau * (f.r * f.area);
            m.y = m.y + r.sigma * (f.z * f.area);
            m.z = m.z - r.sigma * (f.y * f.area);
        }
        m
    }

    /// Accepts section strains `k` as the end of a step: each fibre's plastic strains
    /// move by its return mapping's increment.
    pub fn commit(&self, k: [f64; 3], history: &mut [f64]) {
        let k = V3::new(k[0], k[1], k[2]);
        for (f, h) in self
            .fibres
            .iter()
            .zip(history.chunks_exact_mut(HISTORY_PER_FIBRE))
        {
            let (eps, gamma) = Self::strains(f, k);
            let r = self.law.respond(eps, gamma, [h[0], h[1]]);
            h[0] += r.plastic_increment[0];
            h[1] += r.plastic_increment[1];
        }
    }

    /// Energy per length \[J/m\] at section strains `k`: the incremental potential of
    /// the fibres from `history` if `incremental` (the static solver's line search), else
    /// the energy stored with the committed plastic strains.
    pub fn energy(&self, k: [f64; 3], history: &[f64], incremental: bool) -> f64 {
        let k = V3::new(k[0], k[1], k[2]);
        let mut e = 0.0;
        for (f, h) in self
            .fibres
            .iter()
            .zip(history.chunks_exact(HISTORY_PER_FIBRE))
        {
            let (eps, gamma) = Self::strains(f, k);
            let w = if incremental {
                self.law.incremental_energy(eps, gamma, [h[0], h[1]])
            } else {
                self.law.stored_energy(eps, gamma, [h[0], h[1]])
            };
            e += w * f.area;
        }
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn the_elastic_section_is_the_tube() {
        let law = FibreLaw {
            e: 200e9,
            g: 77e9,
            h: 0.0,
            yield_stress: 1e30,
        };
        let (di, da) = (0.006, 0.008);
        let s = FibreSection::tube(di, da, law);
        let area: f64 = s.fibres.iter().map(|f| f.area).sum();
        assert!((area - PI / 4.0 * (da * da - di * di)).abs() < 1e-14 * area);
        let i = PI / 64.0 * (da.powi(4) - di.powi(4));
        let zero = vec![0.0; s.history_len()];
        let m = s.moments(V3::new(0.01, 0.3, -0.2), &zero);
        assert!((m.y - 200e9 * i * 0.3).abs() < 1e-12 * m.y.abs());
        assert!((m.z + 200e9 * i * 0.2).abs() < 1e-12 * m.z.abs());
        assert!((m.x - 77e9 * 2.0 * i * 0.01).abs() < 1e-12 * m.x.abs());
    }
}
