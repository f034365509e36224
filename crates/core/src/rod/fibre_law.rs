//! The elastic–plastic law of one fibre of a yielding wall (SPEC X1): normal strain ε
//! (bending) and engineering shear strain γ (torsion) in, normal stress σ and shear stress
//! τ out, with the fibre's plastic strains (ε_p, γ_p) as history.
//!
//! The law is von Mises plasticity for the beam's stress state (σ, τ), linear kinematic
//! hardening (Prager), integrated by backward Euler — the closest-point return mapping
//! (Simo & Hughes, *Computational Inelasticity*, 1998, §2.3 for the uniaxial case, §3.3
//! for J2 with kinematic hardening; reduced to σ, τ as in beam fibre models):
//!
//! * σ = E (ε − ε_p), τ = G (γ − γ_p); relative stresses ξ_σ = σ − H ε_p,
//!   ξ_τ = τ − (H/3) γ_p (back stresses of Prager's rule for the fibre's stress state);
//! * yield: q = √(ξ_σ² + 3 ξ_τ²) ≤ σ_y;
//! * flow (associative, Δλ the equivalent plastic strain increment): Δε_p = Δλ ξ_σ/q,
//!   Δγ_p = 3 Δλ ξ_τ/q.
//!
//! With trial values ξ* (plastic strains frozen) the return gives, for μ = Δλ/σ_y,
//! ξ_σ = ξ_σ*/(1 + a μ), ξ_τ = ξ_τ*/(1 + b μ), a = E + H, b = 3G + H, and μ is the root
//! of g(μ) = ξ_σ*²/(1 + a μ)² + 3 ξ_τ*²/(1 + b μ)² − σ_y² — convex and decreasing, so
//! Newton's method from μ = 0 climbs to it monotonically. For pure bending (ξ_τ* = 0) the
//! root is closed-form, μ = (|ξ_σ*|/σ_y − 1)/a.
//!
//! The stress is generic over [`Scalar`]: μ is found on the values, then one Newton
//! correction in the scalar type carries the derivative −g_p/g_μ (implicit function
//! theorem), so dual numbers give the consistent (algorithmic) tangent of the return
//! mapping exactly (Simo & Taylor 1985, CMAME 48), which the Newton solvers need for
//! quadratic convergence.
//!
//! The incremental potential W(ε, γ) = ½E(ε−ε_p)² + ½G(γ−γ_p)² + ½H ε_p² + (H/6) γ_p² +
//! σ_y Δλ, evaluated at the returned plastic strains, has σ = ∂W/∂ε and τ = ∂W/∂γ
//! (the variational form of the return mapping: Ortiz & Stainier 1999, CMAME 171): the
//! static solver's line search uses it as the energy of a yielding fibre.

use crate::autodiff::Scalar;
use crate::material::YieldLaw;

/// The constants of one fibre's law, all SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreLaw {
    /// Young's modulus E \[Pa\].
    pub e: f64,
    /// Shear modulus G \[Pa\].
    pub g: f64,
    /// Kinematic hardening modulus H \[Pa\].
    pub h: f64,
    /// Yield stress σ_y \[Pa\].
    pub yield_stress: f64,
}

/// A fibre's stresses after the return mapping, and its plastic strain increments.
#[derive(Clone, Copy, Debug)]
pub struct FibreResponse<T> {
    /// Normal stress σ \[Pa\].
    pub sigma: T,
    /// Shear stress τ \[Pa\].
    pub tau: T,
    /// Plastic strain increments Δε_p, Δγ_p (zero when the step is elastic).
    pub plastic_increment: [f64; 2],
    /// Equivalent plastic strain increment Δλ (zero when elastic).
    pub equivalent_increment: f64,
}

/// Most Newton iterations of the return mapping's scalar equation (it converges
/// quadratically and monotonically; a handful are needed).
const RETURN_ITERATIONS: usize = 60;

impl FibreLaw {
    /// The law of a wall of elastic moduli `e`, `g` yielding by `law`.
    pub fn new(e: f64, g: f64, law: &YieldLaw) -> Self {
        Self {
            e,
            g,
            h: law.hardening_modulus,
            yield_stress: law.yield_stress,
        }
    }

    /// The return mapping at strains (`eps`, `gamma`) from committed plastic strains
    /// `plastic` = (ε_p, γ_p) (module doc).
    #[inline]
    pub fn respond<T: Scalar>(&self, eps: T, gamma: T, plastic: [f64; 2]) -> FibreResponse<T> {
        let [ep, gp] = plastic;
        let sigma_trial = (eps - ep) * self.e;
        let tau_trial = (gamma - gp) * self.g;
        let xs = sigma_trial - self.h * ep;
        let xt = tau_trial - self.h / 3.0 * gp;
        let sy2 = self.yield_stress * self.yield_stress;
        let (xs0, xt0) = (xs.re(), xt.re());
        if xs0 * xs0 + 3.0 * xt0 * xt0 <= sy2 {
            return FibreResponse {
                sigma: sigma_trial,
                tau: tau_trial,
                plastic_increment: [0.0; 2],
                equivalent_increment: 0.0,
            };
        }
        let (a, b) = (self.e + self.h, 3.0 * self.g + self.h);
        let mu = self.multiplier(xs0, xt0);
        // one Newton correction in T: value unchanged to rounding, derivative −g_p/g_μ
        let (sa, sb) = (1.0 / (1.0 + a * mu), 1.0 / (1.0 + b * mu));
        let g = xs * xs * (sa * sa) + xt * xt * (3.0 * sb * sb) - sy2;
        let dg = -2.0 * a * xs0 * xs0 * sa * sa * sa - 6.0 * b * xt0 * xt0 * sb * sb * sb;
        let mu_t = (g / dg) * -1.0 + mu;
        let xs_new = xs / (mu_t * a + 1.0);
        let xt_new = xt / (mu_t * b + 1.0);
        let d_ep = mu_t * xs_new;
        let d_gp = mu_t * xt_new * 3.0;
        FibreResponse {
            sigma: sigma_trial - d_ep * self.e,
            tau: tau_trial - d_gp * self.g,
            plastic_increment: [d_ep.re(), d_gp.re()],
            equivalent_increment: mu_t.re() * self.yield_stress,
        }
    }

    /// μ = Δλ/σ_y of the return from relative trial stresses (`xs`, `xt`) outside the
    /// yield surface: the root of g (module doc), by Newton's method from 0.
    fn multiplier(&self, xs: f64, xt: f64) -> f64 {
        let (a, b) = (self.e + self.h, 3.0 * self.g + self.h);
        let sy = self.yield_stress;
        if xt == 0.0 {
            return (xs.abs() / sy - 1.0) / a;
        }
        let mut mu = 0.0;
        for _ in 0..RETURN_ITERATIONS {
            let (sa, sb) = (1.0 / (1.0 + a * mu), 1.0 / (1.0 + b * mu));
            let g = xs * xs * sa * sa + 3.0 * xt * xt * sb * sb - sy * sy;
            let dg = -2.0 * a * xs * xs * sa * sa * sa - 6.0 * b * xt * xt * sb * sb * sb;
            let step = g / dg;
            mu -= step;
            if step.abs() <= 1e-15 * mu.abs() {
                break;
            }
        }
        mu
    }

    /// The incremental potential W at (`eps`, `gamma`) from `plastic` (module doc) \[J/m³\].
    pub fn incremental_energy(&self, eps: f64, gamma: f64, plastic: [f64; 2]) -> f64 {
        let r = self.respond(eps, gamma, plastic);
        let ep = plastic[0] + r.plastic_increment[0];
        let gp = plastic[1] + r.plastic_increment[1];
        self.stored_energy(eps, gamma, [ep, gp]) + self.yield_stress * r.equivalent_increment
    }

    /// The energy stored at (`eps`, `gamma`) with plastic strains `plastic`: elastic
    /// ½E(ε−ε_p)² + ½G(γ−γ_p)² and hardening ½H ε_p² + (H/6) γ_p² \[J/m³\].
    pub fn stored_energy(&self, eps: f64, gamma: f64, plastic: [f64; 2]) -> f64 {
        let [ep, gp] = plastic;
        0.5 * self.e * (eps - ep).powi(2)
            + 0.5 * self.g * (gamma - gp).powi(2)
            + 0.5 * self.h * ep * ep
            + self.h / 6.0 * gp * gp
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::autodiff::Dual;

    fn steel(h: f64) -> FibreLaw {
        FibreLaw {
            e: 210e9,
            g: 80e9,
            h,
            yield_stress: 300e6,
        }
    }

    /// Uniaxial: elastic to σ_y, then slope E H/(E + H); unloading elastic.
    #[test]
    fn uniaxial_bilinear_curve_and_elastic_unloading() {
        let law = steel(2e9);
        let ey = 300e6 / 210e9;
        let r = law.respond(0.5 * ey, 0.0, [0.0; 2]);
        assert_eq!(r.sigma, 0.5 * 300e6);
        let eps = 5.0 * ey;
        let r = law.respond(eps, 0.0, [0.0; 2]);
        let tangent = 210e9 * 2e9 / 212e9;
        let want = 300e6 + tangent * (eps - ey);
        assert!(
            (r.sigma - want).abs() < 1e-6 * want,
            "{} vs {want}",
            r.sigma
        );
        let plastic = r.plastic_increment;
        let back = law.respond(eps - ey, 0.0, plastic);
        assert!((back.sigma - (r.sigma - 300e6)).abs() < 1e-6 * 300e6);
        assert_eq!(back.plastic_increment, [0.0; 2]);
    }

    /// Combined σ and τ: the returned stress lies on the yield surface, and the dual
    /// derivative equals central differences of the stress (the consistent tangent).
    #[test]
    fn combined_return_lies_on_the_surface_with_its_tangent() {
        let law = steel(1e9);
        let plastic = [1e-4, -2e-4];
        let (eps, gamma) = (4e-3, 3e-3);
        let r = law.respond(eps, gamma, plastic);
        let ep = plastic[0] + r.plastic_increment[0];
        let gp = plastic[1] + r.plastic_increment[1];
        let q = ((r.sigma - law.h * ep).powi(2) + 3.0 * (r.tau - law.h / 3.0 * gp).powi(2)).sqrt();
        assert!((q - 300e6).abs() < 1e-8 * 300e6, "q {q}");
        let d = law.respond(
            Dual::<2>::variable(eps, 0),
            Dual::<2>::variable(gamma, 1),
            plastic,
        );
        let h = 1e-9;
        for (k, (de, dg)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
            let p = law.respond(eps + de, gamma + dg, plastic);
            let m = law.respond(eps - de, gamma - dg, plastic);
            for (got, fd) in [
                (d.sigma.eps[k], (p.sigma - m.sigma) / (2.0 * h)),
                (d.tau.eps[k], (p.tau - m.tau) / (2.0 * h)),
            ] {
                assert!((got - fd).abs() < 1e-5 * 210e9, "{k}: {got} vs {fd}");
            }
        }
        // and the stresses are the gradient of the incremental potential
        let w = |e: f64, g: f64| law.incremental_energy(e, g, plastic);
        let fd_s = (w(eps + h, gamma) - w(eps - h, gamma)) / (2.0 * h);
        let fd_t = (w(eps, gamma + h) - w(eps, gamma - h)) / (2.0 * h);
        assert!(
            (fd_s - r.sigma).abs() < 1e-4 * 300e6,
            "{fd_s} vs {}",
            r.sigma
        );
        assert!((fd_t - r.tau).abs() < 1e-4 * 300e6, "{fd_t} vs {}", r.tau);
    }

    /// Pure shear yields at τ = σ_y/√3 (von Mises).
    #[test]
    fn pure_shear_yields_at_the_mises_stress() {
        let law = steel(0.0);
        let r = law.respond(0.0, 0.05, [0.0; 2]);
        assert!((r.tau - 300e6 / 3f64.sqrt()).abs() < 1e-6 * 300e6);
    }
}
