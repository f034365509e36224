//! Exact solutions of Euler's inextensible elastica under a dead axial end load (Love,
//! "A Treatise on the Mathematical Theory of Elasticity", 4th ed., §263; Timoshenko &
//! Gere, "Theory of Elastic Stability", 2nd ed., §2.7), from the complete elliptic
//! integrals K(k), E(k) with modulus k = sin(α/2), α the largest slope:
//!
//! * a cantilever of length ℓ with the load P at its free end: ℓ √(P/EI) = K(k); tip
//!   deflection across the load δ = 2k/√(P/EI), tip position along it
//!   x = (2E(k) − K(k))/√(P/EI);
//! * a column with both ends clamped is four such quarter waves of length L/4 (inflection
//!   points at L/4 and 3L/4): P = EI (4K(k)/L)², end distance D = L (2E(k)/K(k) − 1),
//!   mid-span deflection w = L k / K(k).

use std::f64::consts::PI;

/// Complete elliptic integrals of the first and second kind, K(k) and E(k), by the
/// arithmetic–geometric mean (Abramowitz & Stegun 17.6), to round-off.
pub fn elliptic_k_e(k: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    let mut sum = 0.5 * k * k;
    let mut power = 0.5;
    for _ in 0..40 {
        let c = 0.5 * (a - b);
        power *= 2.0;
        sum += power * c * c;
        let next_a = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = next_a;
        if c.abs() < 1e-17 {
            break;
        }
    }
    let big_k = PI / (2.0 * a);
    (big_k, big_k * (1.0 - sum))
}

/// The modulus k ∈ (0, 1) where the increasing function `f(k)` reaches `target`
/// (bisection to round-off).
fn solve_modulus(target: f64, f: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (0.0_f64, 1.0 - 1e-15);
    for _ in 0..200 {
        let k = 0.5 * (lo + hi);
        if f(k) < target {
            lo = k;
        } else {
            hi = k;
        }
    }
    0.5 * (lo + hi)
}

/// A post-buckled cantilever: where its tip is.
#[derive(Clone, Copy, Debug)]
pub struct Cantilever {
    /// Tip deflection across the load, δ/ℓ.
    pub deflection: f64,
    /// Tip position along the load line from the clamp, x/ℓ.
    pub reach: f64,
}

/// The cantilever of length ℓ under an axial tip load P = `load_ratio` · P_cr,
/// P_cr = π² EI / (4 ℓ²); `None` below the critical load (the column stays straight).
pub fn cantilever(load_ratio: f64) -> Option<Cantilever> {
    if load_ratio <= 1.0 {
        return None;
    }
    // ℓ √(P/EI) = (π/2) √(P/P_cr) = K(k)
    let target = 0.5 * PI * load_ratio.sqrt();
    let k = solve_modulus(target, |k| elliptic_k_e(k).0);
    let (big_k, big_e) = elliptic_k_e(k);
    Some(Cantilever {
        deflection: 2.0 * k / big_k,
        reach: 2.0 * big_e / big_k - 1.0,
    })
}

/// A post-buckled column with both ends clamped.
#[derive(Clone, Copy, Debug)]
pub struct ClampedColumn {
    /// End load over the Euler load 4π² EI / L².
    pub load_ratio: f64,
    /// Mid-span deflection w/L.
    pub deflection: f64,
}

/// The clamped–clamped column whose ends are `end_distance` · L apart (< 1).
pub fn clamped_column(end_distance: f64) -> ClampedColumn {
    // D/L = 2E/K − 1 falls from 1 as k grows
    let k = solve_modulus(-end_distance, |k| {
        let (big_k, big_e) = elliptic_k_e(k);
        -(2.0 * big_e / big_k - 1.0)
    });
    let (big_k, _) = elliptic_k_e(k);
    ClampedColumn {
        // P = EI (4K/L)², over 4π²EI/L²: (2K/π)²
        load_ratio: (2.0 * big_k / PI).powi(2),
        deflection: k / big_k,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// K(0) = E(0) = π/2; K(1/√2) = 1.854075, E(1/√2) = 1.350644 (A&S table 17.1).
    #[test]
    fn elliptic_integrals_match_tables() {
        let (k0, e0) = elliptic_k_e(0.0);
        assert!((k0 - PI / 2.0).abs() < 1e-15 && (e0 - PI / 2.0).abs() < 1e-15);
        let (k, e) = elliptic_k_e(std::f64::consts::FRAC_1_SQRT_2);
        assert!((k - 1.854_074_677).abs() < 1e-9, "{k}");
        assert!((e - 1.350_643_881).abs() < 1e-9, "{e}");
    }

    /// Near the bifurcation the elastica meets the linear theory: D/L → 1, P → P_cr.
    #[test]
    fn elastica_starts_at_the_euler_load() {
        let c = clamped_column(1.0 - 1e-8);
        assert!((c.load_ratio - 1.0).abs() < 1e-6);
        let t = cantilever(1.0 + 1e-8).unwrap();
        assert!(t.deflection < 1e-3 && (t.reach - 1.0).abs() < 1e-6);
    }
}
