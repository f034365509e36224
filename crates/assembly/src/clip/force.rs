//! The clip's force on a hose along the opening axis (SPEC L7, replacing the
//! dissertation's eq. 4.110).
//!
//! With s = (m − p)·n the hose centre's coordinate along the opening, |n| the opening
//! distance, h the touch height (see [`ClipSpec`]), r the hose's outer radius, k the snap
//! force, and the force counted positive along +n (out of the clip):
//!
//! ```text
//! s ≥ |n| + h            f = 0                                 no touch
//! |n| ≤ s < |n| + h      f = +k · (√(r² − (s − |n|)²) − d₁/2) / (r − d₁/2)   resists
//! 0 ≤ s < |n|            f = −k · s / |n|                      pulls in (eq. 4.110, 3rd branch)
//! s < 0                  f = +k · min(−s / |n|, 1)             centres on the seat
//! r ≤ d₁/2               f = 0                                 hose thinner than the opening
//! ```
//!
//! The rise is the spread of the opening: a hose whose centre is at s spans a chord of
//! half-width √(r² − (s − |n|)²) in the opening's plane, which forces the jaws apart by
//! that minus d₁/2 on each side; the force is taken proportional to that spread, from 0 at
//! first touch to its full value r − d₁/2 (force k) when the hose's widest part passes
//! the opening. SPEC L7 calls the dissertation's middle branch, k·(h − |m − p − n|)/|p − m|,
//! dimensionally inconsistent; as printed it is k times a ratio of lengths, but it is not
//! normalised: at the opening it gives k·h/|n| instead of the k that section 5.3.1 defines
//! as the snap force, so the peak would depend on the geometry. It is replaced by the
//! shape above, as SPEC L7 asks.
//! Past the opening the jaws close behind the hose and pull it into the seat; the
//! dissertation's third branch, −k·|p − m|/|n| (dimensionally sound), is kept: k at the
//! opening, falling linearly to 0 at the seat. The jump from +k to −k at s = |n| is the
//! snap. Behind the seat (s < 0) the same linear law, continued, pushes the hose back,
//! making the seat a stable rest position (the clip's rigid body itself is contact, L4).
//! Each branch is smooth; the force is continuous everywhere except at the snap.

use super::spec::ClipSpec;
use glam::DVec3;

impl ClipSpec {
    /// Force on the hose along +n \[N\] for a hose of outer radius `radius` whose centre is
    /// at coordinate `s` along the opening (see the module's table). Non-finite input
    /// gives 0.
    pub fn force_along_opening(&self, s: f64, radius: f64) -> f64 {
        let Some(h) = self.touch_height(radius) else {
            return 0.0;
        };
        if !s.is_finite() {
            return 0.0;
        }
        let (n, k, half) = (
            self.opening_distance(),
            self.snap_force(),
            0.5 * self.opening_width(),
        );
        if s >= n + h {
            0.0
        } else if s >= n {
            let x = s - n;
            let spread = ((radius * radius - x * x).max(0.0).sqrt() - half) / (radius - half);
            k * spread.clamp(0.0, 1.0)
        } else if s >= 0.0 {
            -k * s / n
        } else {
            k * (-s / n).min(1.0)
        }
    }

    /// Force vector on a hose of outer radius `radius` centred at `centre` \[N\]: the law of
    /// [`ClipSpec::force_along_opening`] along n. Whether it applies at all (the hose is
    /// in front of the opening, not beside the clip) is decided by
    /// [`crate::clip::ClipState`].
    pub fn force_on_hose(&self, centre: DVec3, radius: f64) -> DVec3 {
        self.force_along_opening(self.opening_coordinate(centre), radius) * self.opening()
    }
}
