//! The static Kirchhoff rod equations, their linearisation, and fixed-step RK4
//! integration over the polyline (restarted at every rest kink).
//!
//! # Equations
//!
//! Unknown fields of the reference arc length `s ∈ [0, L]`: centre line `r`,
//! material frame `R = [d1 d2 d3]`, internal force `n` and internal moment `m`
//! (both global; `n(s), m(s)` are exerted by the part `(s, L]` on the part
//! `[0, s]`). Antman, *Nonlinear Problems of Elasticity* (2nd ed.), ch. 8, with
//! an unshearable, linearly elastic, bimodular constitutive law:
//!
//! ```text
//! r' = ν d1,              ν = 1 + N / EA(N),  N = n·d1
//! R' = R [κ]×,            κ = (m_b1/GJ, m_b2/EI, m_b3/EI),  m_b = Rᵀ m
//! n' = −q                 (q: distributed dead load per reference length)
//! m' = −r' × n
//! ```
//!
//! On straight rest segments the intrinsic curvature is zero; at interior rest node
//! k the frame jumps by the concentrated material rotation `R ← R K_k`,
//! `K_k = R_rest,k−1ᵀ R_rest,k` (see [`crate::rod`]), so the unloaded rest state
//! (`n = m = 0`) reproduces the rest polyline exactly.
//!
//! # Linearisation (variational equations)
//!
//! For a variation `(δr, δR, δn, δm)`:
//!
//! ```text
//! δκ  = C⁻¹ (δRᵀ m + Rᵀ δm)
//! δν  = (δd1·n + d1·δn) / EA
//! δr' = δν d1 + ν δd1
//! δR' = δR [κ]× + R [δκ]×
//! δn' = 0
//! δm' = −(δr' × n + r' × δn)
//! ```
//!
//! RK4 applied to the state together with its variations yields exactly the
//! derivative of the discrete RK4 shooting map, so Newton sees the true Jacobian
//! even where finite differences would drown in round-off (`EA ≫ EI/L²`).
//!
//! # Discretisation
//!
//! Classical RK4 with a fixed step on each segment: `n_k = max(4, ⌈l_k · N / L⌉)`
//! steps on a segment of length `l_k`, `N` = [`crate::SolverOptions::steps_per_length`]
//! (default 4000, i.e. `h ≤ L/4000`). The global error is `O((h κ)⁴)`; for a rod
//! rolled into a full circle (`κL = 2π`) it is ~1e-11 L. The frame is integrated as
//! a 3×3 matrix; RK4's departure from orthogonality is `O((hκ)⁵)` per step, below
//! 1e-13 over the rod.

use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::error::{ReferenceError, Result};
use crate::rod::Rod;
use crate::so3::skew;

/// Minimum number of RK4 steps on any segment.
const MIN_STEPS_PER_SEGMENT: usize = 4;

/// Cross-section state `(r, R, n, m)`, or a variation of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RodState {
    pub r: Vector3<f64>,
    pub frame: Matrix3<f64>,
    pub n: Vector3<f64>,
    pub m: Vector3<f64>,
}

impl RodState {
    pub fn zero() -> Self {
        Self {
            r: Vector3::zeros(),
            frame: Matrix3::zeros(),
            n: Vector3::zeros(),
            m: Vector3::zeros(),
        }
    }

    /// `self + h · k`.
    fn axpy(&self, h: f64, k: &Self) -> Self {
        Self {
            r: self.r + k.r * h,
            frame: self.frame + k.frame * h,
            n: self.n + k.n * h,
            m: self.m + k.m * h,
        }
    }

    fn is_finite(&self) -> bool {
        self.r
            .iter()
            .chain(self.frame.iter())
            .chain(self.n.iter())
            .chain(self.m.iter())
            .all(|v| v.is_finite())
    }
}

/// A state together with `T` variations (`T = 6` for shooting, `0` for sampling).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Augmented<const T: usize> {
    pub state: RodState,
    pub variations: [RodState; T],
}

impl<const T: usize> Augmented<T> {
    fn axpy(&self, h: f64, k: &Self) -> Self {
        Self {
            state: self.state.axpy(h, &k.state),
            variations: std::array::from_fn(|j| self.variations[j].axpy(h, &k.variations[j])),
        }
    }

    /// Applies the concentrated material rotation of a rest kink: `R ← R K`.
    fn apply_kink(&mut self, kink: &Rotation3<f64>) {
        let k = kink.matrix();
        self.state.frame *= k;
        for v in &mut self.variations {
            v.frame *= k;
        }
    }
}

/// Constant data of the right-hand side.
struct Coefficients {
    ea_tension: f64,
    ea_compression: f64,
    inverse_stiffness: Vector3<f64>,
    load: Vector3<f64>,
}

impl Coefficients {
    fn new(rod: &Rod, load_scale: f64) -> Self {
        let st = rod.stiffness();
        Self {
            ea_tension: st.axial_tension(),
            ea_compression: st.axial_compression(),
            inverse_stiffness: Vector3::new(
                1.0 / st.torsion(),
                1.0 / st.bending(),
                1.0 / st.bending_d3(),
            ),
            load: rod.distributed_load() * load_scale,
        }
    }

    /// Right-hand side and its linearisation applied to every variation.
    fn derivative<const T: usize>(
        &self,
        a: &Augmented<T>,
    ) -> std::result::Result<Augmented<T>, f64> {
        let y = &a.state;
        let d1: Vector3<f64> = y.frame.column(0).into();
        let axial = d1.dot(&y.n);
        let ea = if axial >= 0.0 {
            self.ea_tension
        } else {
            self.ea_compression
        };
        let stretch = 1.0 + axial / ea;
        if stretch.is_nan() || stretch <= 0.0 {
            return Err(stretch);
        }
        let kappa = (y.frame.transpose() * y.m).component_mul(&self.inverse_stiffness);
        let kappa_hat = skew(&kappa);
        let r_prime = d1 * stretch;
        let state = RodState {
            r: r_prime,
            frame: y.frame * kappa_hat,
            n: -self.load,
            m: -r_prime.cross(&y.n),
        };
        let variations = std::array::from_fn(|j| {
            let dy = &a.variations[j];
            let dd1: Vector3<f64> = dy.frame.column(0).into();
            let dkappa = (dy.frame.transpose() * y.m + y.frame.transpose() * dy.m)
                .component_mul(&self.inverse_stiffness);
            let dstretch = (dd1.dot(&y.n) + d1.dot(&dy.n)) / ea;
            let dr_prime = d1 * dstretch + dd1 * stretch;
            RodState {
                r: dr_prime,
                frame: dy.frame * kappa_hat + y.frame * skew(&dkappa),
                n: Vector3::zeros(),
                m: -(dr_prime.cross(&y.n) + r_prime.cross(&dy.n)),
            }
        });
        Ok(Augmented { state, variations })
    }

    /// One classical RK4 step of size `h`.
    fn rk4<const T: usize>(
        &self,
        a: &Augmented<T>,
        h: f64,
    ) -> std::result::Result<Augmented<T>, f64> {
        if h == 0.0 {
            return Ok(*a);
        }
        let k1 = self.derivative(a)?;
        let k2 = self.derivative(&a.axpy(0.5 * h, &k1))?;
        let k3 = self.derivative(&a.axpy(0.5 * h, &k2))?;
        let k4 = self.derivative(&a.axpy(h, &k3))?;
        Ok(a.axpy(h / 6.0, &k1)
            .axpy(h / 3.0, &k2)
            .axpy(h / 3.0, &k3)
            .axpy(h / 6.0, &k4))
    }
}

/// Integrates from `s = 0` to `s = L`, starting from `start`.
///
/// `load_scale` multiplies the rod's distributed load (continuation ramps it).
/// `stops` must be sorted ascending in `[0, L]`; `on_stop(i, state)` is called with
/// the state at `stops[i]`, obtained by a partial RK4 step from the last grid
/// point (the grid itself, and thus the end state, does not depend on `stops`). A
/// stop exactly at an interior node gets the frame after the kink.
pub(crate) fn integrate<const T: usize>(
    rod: &Rod,
    load_scale: f64,
    steps_per_length: usize,
    start: Augmented<T>,
    stops: &[f64],
    mut on_stop: impl FnMut(usize, &Augmented<T>),
) -> Result<Augmented<T>> {
    let coefficients = Coefficients::new(rod, load_scale);
    let arc = rod.node_arc_lengths();
    let length = rod.length();
    let failure = |s: f64, stretch: f64| ReferenceError::Integration {
        arc_length: s,
        reason: format!("non-physical stretch ν = {stretch:.3e} (axial compression ≥ EA)"),
    };
    let mut a = start;
    let mut next_stop = 0;
    for k in 0..rod.segment_count() {
        if let Some(kink) = rod.kink(k) {
            a.apply_kink(&kink);
        }
        let (s0, s1) = (arc[k], arc[k + 1]);
        let segment_length = s1 - s0;
        let steps = ((segment_length / length * steps_per_length as f64).ceil() as usize)
            .max(MIN_STEPS_PER_SEGMENT);
        let h = segment_length / steps as f64;
        for j in 0..steps {
            let s = s0 + j as f64 * h;
            let step_end = if j + 1 == steps { s1 } else { s + h };
            while next_stop < stops.len() && stops[next_stop] < step_end {
                let partial = (stops[next_stop] - s).max(0.0);
                let sample = coefficients.rk4(&a, partial).map_err(|nu| failure(s, nu))?;
                on_stop(next_stop, &sample);
                next_stop += 1;
            }
            a = coefficients.rk4(&a, h).map_err(|nu| failure(s, nu))?;
        }
        if !a.state.is_finite() || !a.variations.iter().all(RodState::is_finite) {
            return Err(ReferenceError::Integration {
                arc_length: s1,
                reason: "non-finite state".to_string(),
            });
        }
    }
    while next_stop < stops.len() {
        on_stop(next_stop, &a);
        next_stop += 1;
    }
    Ok(a)
}
