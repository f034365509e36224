//! Closed forms of the elastic–perfectly plastic circular tube (and solid rod, r_i = 0)
//! in bending and in torsion: the curves the fibre section ([`crate::rod::fibre_section`])
//! is validated against, and what a user reads off a metal line's yield.
//!
//! **Bending** (plane sections, σ = E κ y in the elastic core |y| ≤ c = σ_y/(E κ), ±σ_y
//! outside): the moment of a disc of radius R is, with c ≤ R,
//!
//! M_disc(R, c) = 2σ_y [ ((c/4)(2c² − R²)√(R² − c²) + (R⁴/4) asin(c/R))/c + (2/3)(R² − c²)^{3/2} ]
//!
//! (∫σ y b(y) dy with the chord b(y) = 2√(R² − y²), integrated in closed form); at c = R it
//! is the first-yield moment M_e = σ_y I/R, as c → 0 the plastic moment
//! M_p = (4/3) σ_y R³. A tube is the outer disc less the inner one (the stress is a
//! function of y alone): M = M_disc(r_o, c) − M_disc(r_i, c), the inner term being the
//! elastic σ_y π r_i⁴/(4c) when c ≥ r_i. So M_e = σ_y π(r_o⁴ − r_i⁴)/(4 r_o) and
//! M_p = (4/3) σ_y (r_o³ − r_i³) (the plastic section modulus Z = (d_o³ − d_i³)/6; the
//! textbook derivation for beams, e.g. Lubliner, *Plasticity Theory*, 1990, ch. 4).
//!
//! **Torsion** (von Mises: shear yield τ_y = σ_y/√3; τ = G θ' r up to the elastic radius
//! ρ = τ_y/(G θ'), τ_y beyond): T = 2π [∫ G θ' r³ dr over the elastic part + ∫ τ_y r² dr
//! over the plastic part], the fully plastic torque T_p = (2π/3) τ_y (r_o³ − r_i³).
//! With linear kinematic hardening H (the fibre law's shear back stress (H/3) γ_p) a
//! yielded fibre's shear stress rises past τ_y with the tangent G_t = G H/(3G + H), which
//! adds 2π G_t ∫_ρ^{r_o} (θ' r − γ_y) r² dr, γ_y = τ_y/G.

use std::f64::consts::PI;

/// Moment of a disc of radius `r` whose fibres beyond `c` from the neutral axis have
/// yielded, per unit yield stress (module doc) \[m³\].
fn disc(r: f64, c: f64) -> f64 {
    if r <= 0.0 {
        return 0.0;
    }
    if c >= r {
        return PI * r.powi(4) / (4.0 * c);
    }
    let root = (r * r - c * c).sqrt();
    let core = ((c / 4.0) * (2.0 * c * c - r * r) * root + r.powi(4) / 4.0 * (c / r).asin()) / c;
    2.0 * (core + 2.0 / 3.0 * root.powi(3))
}

/// Bending moment \[N·m\] of an elastic–perfectly plastic tube (inner and outer radii
/// `ri`, `ro` \[m\], Young's modulus `e`, yield stress `sy` \[Pa\]) bent monotonically to
/// curvature `kappa` \[1/m\] (module doc).
pub fn bending_moment(ri: f64, ro: f64, e: f64, sy: f64, kappa: f64) -> f64 {
    let k = kappa.abs();
    if k == 0.0 {
        return 0.0;
    }
    let c = sy / (e * k);
    if c >= ro {
        return kappa * e * PI / 4.0 * (ro.powi(4) - ri.powi(4));
    }
    kappa.signum() * sy * (disc(ro, c) - disc(ri, c))
}

/// ∫ y² dA over the part |y| < c of a disc of radius `r` \[m⁴\] (its elastic core).
fn core_second_moment(r: f64, c: f64) -> f64 {
    if c >= r {
        return PI * r.powi(4) / 4.0;
    }
    let root = (r * r - c * c).sqrt();
    2.0 * ((c / 4.0) * (2.0 * c * c - r * r) * root + r.powi(4) / 4.0 * (c / r).asin())
}

/// ∫ |y| dA over the part |y| > c of a disc of radius `r` \[m³\].
fn outer_first_moment(r: f64, c: f64) -> f64 {
    if c >= r {
        return 0.0;
    }
    4.0 / 3.0 * (r * r - c * c).powf(1.5)
}

/// Bending moment \[N·m\] of a tube with linear hardening H (uniaxial stress
/// σ_y + E_t (ε − ε_y) beyond yield, E_t = E H/(E + H)) bent monotonically to `kappa`:
/// the perfectly plastic moment plus E_t ∫(κ|y| − ε_y)|y| dA over the yielded part,
/// = E_t [κ (I − I_core) − ε_y S_outer] for each disc (module doc).
pub fn hardening_bending_moment(ri: f64, ro: f64, e: f64, sy: f64, h: f64, kappa: f64) -> f64 {
    let k = kappa.abs();
    let perfect = bending_moment(ri, ro, e, sy, kappa);
    if k == 0.0 {
        return perfect;
    }
    let c = sy / (e * k);
    let et = e * h / (e + h);
    let disc_extra = |r: f64| {
        if r <= 0.0 {
            return 0.0;
        }
        k * (PI * r.powi(4) / 4.0 - core_second_moment(r, c)) - sy / e * outer_first_moment(r, c)
    };
    perfect + kappa.signum() * et * (disc_extra(ro) - disc_extra(ri))
}

/// First-yield moment M_e = σ_y I/r_o \[N·m\].
pub fn first_yield_moment(ri: f64, ro: f64, sy: f64) -> f64 {
    sy * PI * (ro.powi(4) - ri.powi(4)) / (4.0 * ro)
}

/// Fully plastic moment M_p = (4/3) σ_y (r_o³ − r_i³) \[N·m\].
pub fn plastic_moment(ri: f64, ro: f64, sy: f64) -> f64 {
    4.0 / 3.0 * sy * (ro.powi(3) - ri.powi(3))
}

/// Torque \[N·m\] of an elastic–perfectly plastic (von Mises) tube twisted monotonically
/// at rate `twist` \[rad/m\], shear modulus `g` (module doc).
pub fn torque(ri: f64, ro: f64, g: f64, sy: f64, twist: f64) -> f64 {
    let t = twist.abs();
    if t == 0.0 {
        return 0.0;
    }
    let tau_y = sy / 3f64.sqrt();
    let rho = (tau_y / (g * t)).clamp(ri, ro);
    let elastic = g * t * (rho.powi(4) - ri.powi(4)) / 4.0;
    let plastic = tau_y * (ro.powi(3) - rho.powi(3)) / 3.0;
    twist.signum() * 2.0 * PI * (elastic + plastic)
}

/// Torque \[N·m\] of a tube with linear kinematic hardening `h` twisted monotonically at
/// rate `twist`: the perfectly plastic torque plus the yielded fibres' hardening
/// 2π G_t [θ' (r_o⁴ − ρ⁴)/4 − γ_y (r_o³ − ρ³)/3] (module doc).
pub fn hardening_torque(ri: f64, ro: f64, g: f64, sy: f64, h: f64, twist: f64) -> f64 {
    let perfect = torque(ri, ro, g, sy, twist);
    let t = twist.abs();
    if t == 0.0 {
        return perfect;
    }
    let tau_y = sy / 3f64.sqrt();
    let rho = (tau_y / (g * t)).clamp(ri, ro);
    let gt = g * h / (3.0 * g + h);
    let extra = t * (ro.powi(4) - rho.powi(4)) / 4.0 - tau_y / g * (ro.powi(3) - rho.powi(3)) / 3.0;
    perfect + twist.signum() * 2.0 * PI * gt * extra
}

/// Fully plastic torque T_p = (2π/3)(σ_y/√3)(r_o³ − r_i³) \[N·m\].
pub fn plastic_torque(ri: f64, ro: f64, sy: f64) -> f64 {
    2.0 * PI / 3.0 * sy / 3f64.sqrt() * (ro.powi(3) - ri.powi(3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_of_the_closed_forms() {
        let (ri, ro, e, g, sy) = (0.003, 0.004, 200e9, 77e9, 300e6);
        let ke = sy / (e * ro);
        let me = first_yield_moment(ri, ro, sy);
        assert!((bending_moment(ri, ro, e, sy, ke) - me).abs() < 1e-12 * me);
        assert!((bending_moment(ri, ro, e, sy, ke * (1.0 + 1e-9)) - me).abs() < 1e-6 * me);
        let mp = plastic_moment(ri, ro, sy);
        assert!((bending_moment(ri, ro, e, sy, 1e6 * ke) - mp).abs() < 1e-5 * mp);
        assert!(
            (bending_moment(0.0, ro, e, sy, 1e6 * ke) - 4.0 / 3.0 * sy * ro.powi(3)).abs()
                < 1e-5 * mp
        );
        let tp = plastic_torque(ri, ro, sy);
        assert!((torque(ri, ro, g, sy, 1e6) - tp).abs() < 1e-5 * tp);
        let small = 1e-3;
        assert!(
            (torque(ri, ro, g, sy, small) - g * PI / 2.0 * (ro.powi(4) - ri.powi(4)) * small).abs()
                < 1e-9
        );
    }

    /// The hardening torque against the fibre section (one return from the virgin state:
    /// exact for pure shear with linear hardening) on the simulator's grid: the 10/12 mm
    /// tube, elastic or wholly yielded at these twists, to rounding (measured 2.4e-15);
    /// the solid rod, whose elastic radius ρ cuts through its radial intervals (second
    /// order there), to the 0.5 % of the validation case `plastic_section` (measured
    /// 1.2e-3 at 1.5 θ'_e, 5e-6 at 20 θ'_e).
    #[test]
    fn hardening_torque_is_the_fibre_sections() {
        use crate::autodiff::V3;
        use crate::rod::fibre_law::FibreLaw;
        use crate::rod::fibre_section::FibreSection;
        let (e, g, sy, h) = (70e9, 70e9 / 2.6, 170e6, 580e6);
        for (di, da, tolerance) in [(0.010, 0.012, 1e-12), (0.0, 0.008, 5e-3)] {
            let law = FibreLaw {
                e,
                g,
                h,
                yield_stress: sy,
            };
            let s = FibreSection::tube(di, da, law);
            let zero = vec![0.0; s.history_len()];
            let twist_e = sy / 3f64.sqrt() / (g * 0.5 * da);
            for factor in [0.5, 1.5, 4.0, 20.0] {
                let t = factor * twist_e;
                let fibres = s.moments(V3::new(t, 0.0, 0.0), &zero).x;
                let exact = hardening_torque(0.5 * di, 0.5 * da, g, sy, h, t);
                assert!(
                    (fibres - exact).abs() < tolerance * exact,
                    "d {di}/{da} at {factor} θ'_e: fibres {fibres}, closed form {exact}"
                );
            }
        }
    }
}
