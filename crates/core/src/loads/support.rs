//! A fixing's support: a node held to a pose by stiff springs in the
//! directions the fixing fixes and by none in those it leaves free, with Coulomb friction
//! along its free translations (a sliding guide).
//!
//! In the fixing's frame R = [X Y Z] (columns in global axes), with d = x − x₀ the node's
//! offset from the held position and θ = log(q q₀⁻¹) its turn from the held orientation,
//! P_f / P_r the projectors onto the fixed translations / rotations:
//!
//! ```text
//! f = −k P_f d − c P_f v          m = −k_r P_r θ − c_r P_r ω
//! ```
//!
//! (a zero-length spring and damper per fixed direction). A fixing on a moving part is
//! carried with it: x₀, q₀ and the frame follow the part's pose, and the dampers act on
//! the velocity relative to the held point's, v − v₀ and ω − ω₀ (v₀, ω₀ from the part's
//! twist; zero for a fixing that stands still). Along the free translations a
//! stick spring of the same k pulls towards a slip anchor s; its force is capped at μ N with
//! N = |−k P_f d − c P_f v| the support's force across the free directions (Coulomb):
//!
//! ```text
//! t = −k P_free (x − s);   |t| ≤ μ N: stick, force t;   else slip, force μ N t/|t|
//! ```
//!
//! and the anchor is dragged along at each accepted step ([`Support::commit`]). With
//! μ = 0 the free directions carry nothing. At rest (static equilibrium) the spring
//! force in each fixed direction is the support's reaction, equal and opposite to the
//! load there whatever k is; k only sets how far the node gives (F/k).
//!
//! Stiffness: k = [`SUPPORT_FACTOR`] · m / Δt², k_r = [`SUPPORT_FACTOR`] · I / Δt² with
//! m, I the node's lumped mass and inertia and Δt the explicit step — the stiffest spring
//! the explicit solver carries stably (ω Δt = √0.5 on top of the hose's own frequencies,
//! which the default safety factor 0.5 keeps at ω Δt ≤ 1: together ≤ 1.23 < 2); the
//! damper c = 2 ζ √(k m) with ζ = [`SUPPORT_DAMPING`].

use crate::math::log_map;
use glam::{DMat3, DQuat, DVec3};

/// k = SUPPORT_FACTOR · m / Δt² (see the module doc).
pub const SUPPORT_FACTOR: f64 = 0.5;
/// Damping ratio ζ of the support's dampers.
pub const SUPPORT_DAMPING: f64 = 0.5;

/// The largest explicit time-step safety factor with which supports stay stable: the hose's
/// own frequencies reach ω Δt = 2 · safety, a support adds √SUPPORT_FACTOR, and together
/// they must stay below 2 (the module doc's bound): 1 − √SUPPORT_FACTOR / 2 ≈ 0.65.
pub fn largest_safety_with_supports() -> f64 {
    1.0 - 0.5 * SUPPORT_FACTOR.sqrt()
}

/// A node held in some directions of a frame and free in the others.
#[derive(Clone, Debug, PartialEq)]
pub struct Support {
    pub node: usize,
    /// Held position x₀ \[m\].
    pub position: DVec3,
    /// Held orientation q₀.
    pub orientation: DQuat,
    /// The fixing's frame: its X, Y, Z axes in global axes.
    pub frame: DQuat,
    /// Which of the frame's translations (X, Y, Z) are free.
    pub free_translation: [bool; 3],
    /// Which of the frame's rotations (about X, Y, Z) are free.
    pub free_rotation: [bool; 3],
    /// Coulomb coefficient μ along the free translations [-].
    pub friction: f64,
    /// Slip anchor s of the friction spring \[m\] (moved by [`Support::commit`]).
    pub anchor: DVec3,
    /// Set by whoever moves `position` (a hand): the explicit step then wakes a sleeping
    /// hose, as a moving fix does, and clears it.
    pub moved: bool,
    /// Velocity v₀ of the held point \[m/s\] (a fixing on a moving part; else zero).
    pub velocity: DVec3,
    /// Angular velocity ω₀ of the fixing's frame \[rad/s\] (a fixing on a moving part).
    pub spin: DVec3,
}

/// The support's load on its node and its tangent −∂(f, m)/∂(δx, δθ) (diagonal blocks;
/// the damper's part is c · `rate_factor`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SupportLoad {
    pub force: DVec3,
    pub moment: DVec3,
    pub tangent_translation: DMat3,
    pub tangent_rotation: DMat3,
    /// The friction force along the free translations (part of `force`) \[N\].
    pub friction: DVec3,
    /// Whether the friction slips (the anchor follows on commit).
    pub slipping: bool,
    /// Energy of the springs (½ k |P_f d|² + ½ k_r |P_r θ|², the friction spring's
    /// elastic part or μN|u| − (μN)²/2k when slipping) \[J\], for the static line search.
    pub energy: f64,
}

/// Projector Σ eₖ eₖᵀ over the frame's axes k selected by `pick`.
fn projector(r: DMat3, pick: [bool; 3]) -> DMat3 {
    let mut p = DMat3::ZERO;
    for (k, on) in pick.into_iter().enumerate() {
        if on {
            let e = r.col(k);
            p += DMat3::from_cols(e * e.x, e * e.y, e * e.z);
        }
    }
    p
}

impl Support {
    /// A support holding `node` at its pose (`position`, `orientation`) in `frame`.
    pub fn new(
        node: usize,
        position: DVec3,
        orientation: DQuat,
        frame: DQuat,
        free_translation: [bool; 3],
        free_rotation: [bool; 3],
        friction: f64,
    ) -> Support {
        Support {
            node,
            position,
            orientation,
            frame,
            free_translation,
            free_rotation,
            friction,
            anchor: position,
            moved: false,
            velocity: DVec3::ZERO,
            spin: DVec3::ZERO,
        }
    }

    /// Spring stiffnesses (k, k_r) and damper constants (c, c_r) for a node of lumped mass
    /// `mass` and inertia `inertia` in a model stepping by `dt` (module doc).
    pub fn constants(mass: f64, inertia: f64, dt: f64) -> (f64, f64, f64, f64) {
        let (k, kr) = (
            SUPPORT_FACTOR * mass / (dt * dt),
            SUPPORT_FACTOR * inertia / (dt * dt),
        );
        let c = 2.0 * SUPPORT_DAMPING * (k * mass).sqrt();
        let cr = 2.0 * SUPPORT_DAMPING * (kr * inertia).sqrt();
        (k, kr, c, cr)
    }

    /// The load on the node at pose (x, q) moving with (v, ω), for a node of mass `mass`,
    /// inertia `inertia`, explicit step `dt`; `rate_factor` = ∂v/∂δx (0 in statics).
    #[allow(clippy::too_many_arguments)]
    pub fn load(
        &self,
        x: DVec3,
        q: DQuat,
        v: DVec3,
        w: DVec3,
        (mass, inertia, dt): (f64, f64, f64),
        rate_factor: f64,
    ) -> SupportLoad {
        let (k, kr, c, cr) = Self::constants(mass, inertia, dt);
        let r = DMat3::from_quat(self.frame);
        let fixed_t = projector(r, self.free_translation.map(|f| !f));
        let free = projector(r, self.free_translation);
        let fixed_r = projector(r, self.free_rotation.map(|f| !f));
        let spring = -(fixed_t * (x - self.position)) * k;
        let theta = fixed_r * log_map(q * self.orientation.conjugate());
        let held = spring - fixed_t * (v - self.velocity) * c;
        let mut out = SupportLoad {
            energy: 0.5
                * (spring.length_squared() / k.max(f64::MIN_POSITIVE)
                    + kr * theta.length_squared()),
            force: held,
            moment: -theta * kr - fixed_r * (w - self.spin) * cr,
            tangent_translation: fixed_t * (k + c * rate_factor),
            tangent_rotation: fixed_r * (kr + cr * rate_factor),
            ..Default::default()
        };
        if self.friction > 0.0 {
            let trial = -(free * (x - self.anchor)) * k;
            let cap = self.friction * held.length();
            let u = trial.length() / k;
            if trial.length() <= cap {
                out.friction = trial;
                out.tangent_translation += free * k;
                out.energy += 0.5 * k * u * u;
            } else {
                out.friction = trial.normalize_or_zero() * cap;
                out.slipping = true;
                out.energy += cap * u - 0.5 * cap * cap / k;
            }
            out.force += out.friction;
        }
        out
    }

    /// Accepts the node's position `x` at the end of a step with the friction `load` found
    /// there: a slipping anchor is dragged so that the spring holds exactly μ N.
    pub fn commit(&mut self, x: DVec3, load: &SupportLoad, k: f64) {
        if load.slipping && k > 0.0 {
            let r = DMat3::from_quat(self.frame);
            let free = projector(r, self.free_translation);
            // P_free (x − s') = −friction / k
            self.anchor += free * (x - self.anchor) + load.friction / k;
        }
    }
}

/// Each support's load at the state's pose, written as its reaction (what the support
/// applies to the node, added to `reaction_force` / `reaction_moment`); with `commit`
/// the slip anchors are then dragged along (the step is accepted). Each tie's load
/// ([`super::Tie`]) is added the same way, +f on its first node and −f on its second.
pub fn support_reactions(model: &crate::Model, state: &mut crate::State, commit: bool) {
    let dt = model.time_step;
    let crate::State {
        loads,
        x,
        q,
        v,
        w,
        reaction_force,
        reaction_moment,
        ..
    } = state;
    for (_, case) in loads.iter_mut() {
        let s = match case {
            super::LoadCase::Support(s) => s,
            super::LoadCase::Tie(t) => {
                let [a, b] = t.nodes;
                let l = t.load(
                    [x[a], x[b]],
                    [v[a], v[b]],
                    [model.mass[a], model.mass[b]],
                    dt,
                    0.0,
                );
                reaction_force[a] += l.force;
                reaction_force[b] -= l.force;
                continue;
            }
            _ => continue,
        };
        let i = s.node;
        let (m, inertia) = (model.mass[i], model.inertia[i]);
        let load = s.load(x[i], q[i], v[i], w[i], (m, inertia, dt), 0.0);
        reaction_force[i] += load.force;
        reaction_moment[i] += load.moment;
        if commit {
            s.commit(x[i], &load, Support::constants(m, inertia, dt).0);
        }
    }
}
