//! Plugging a connector: a plug on a hose end pushed into its counterpart along an axis,
//! against a measured mating force, until its latch clicks (connector test practice as in
//! SAE/USCAR-2 §5.4.2 and USCAR-25: engage force over travel, latch, retention).
//!
//! The counterpart is described as a stub ([`StubSpec`]): its `origin` is the mouth where
//! the plug starts to engage, its `axis` the mating direction, its `length` the mating
//! travel (the plug stops there, fully home), its `diameter` the plug's size (the reach
//! tolerance). The force law, with s the travel from the mouth:
//!
//! - pushing in at travel s needs F(s), the measured force–travel curve interpolated
//!   linearly between its points (held at its first and last values outside them);
//! - pulling out needs F(s) too while the latch is open (the terminals' contact springs
//!   rub both ways), and the retention force F_r once s ≥ s_latch (the latch holds until it
//!   breaks);
//! - a plug released short of the latch is half-mated: not assembled.

use super::bead::Sense;
use super::error::StubError;
use super::spec::StubSpec;

/// Most points of a mating force curve.
pub const MAX_MATING_POINTS: usize = 16;

/// A connector's mating force law on its counterpart's geometry. All SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mating {
    counterpart: StubSpec,
    /// (travel \[m\], force \[N\]) in increasing travel; the first `len` slots are used (a
    /// fixed array keeps the law `Copy`).
    points: [(f64, f64); MAX_MATING_POINTS],
    len: usize,
    latch_at: f64,
    retention: f64,
}

fn refuse(field: &'static str, reason: &'static str) -> StubError {
    StubError::Spec { field, reason }
}

impl Mating {
    /// Checks and builds the law. `curve`: 1 to [`MAX_MATING_POINTS`] points (travel \[m\],
    /// force \[N\]) with travel strictly increasing within [0, travel of the counterpart]
    /// and forces finite and ≥ 0; `latch_at` \[m\] in (0, travel]; `retention` \[N\] finite
    /// and ≥ 0.
    pub fn new(
        counterpart: StubSpec,
        curve: &[(f64, f64)],
        latch_at: f64,
        retention: f64,
    ) -> Result<Self, StubError> {
        if curve.is_empty() || curve.len() > MAX_MATING_POINTS {
            return Err(refuse("mating_force", "needs 1 to 16 points"));
        }
        let travel = counterpart.length();
        let mut points = [(0.0, 0.0); MAX_MATING_POINTS];
        for (k, &(s, f)) in curve.iter().enumerate() {
            if !(s.is_finite() && (0.0..=travel).contains(&s)) {
                return Err(refuse(
                    "mating_force",
                    "each point's travel must lie within [0, travel]",
                ));
            }
            if k > 0 && s <= curve[k - 1].0 {
                return Err(refuse(
                    "mating_force",
                    "the points' travel must increase strictly",
                ));
            }
            if !(f.is_finite() && f >= 0.0) {
                return Err(refuse(
                    "mating_force",
                    "each point's force must be finite and >= 0",
                ));
            }
            points[k] = (s, f);
        }
        if !(latch_at.is_finite() && latch_at > 0.0 && latch_at <= travel) {
            return Err(refuse("latch_at", "must lie within (0, travel]"));
        }
        if !(retention.is_finite() && retention >= 0.0) {
            return Err(refuse("retention_force", "must be finite and >= 0"));
        }
        Ok(Mating {
            counterpart,
            points,
            len: curve.len(),
            latch_at,
            retention,
        })
    }

    /// The counterpart's geometry: mouth, mating axis, travel, plug size.
    pub fn counterpart(&self) -> &StubSpec {
        &self.counterpart
    }

    /// The measured curve's points (travel \[m\], force \[N\]).
    pub fn curve(&self) -> &[(f64, f64)] {
        &self.points[..self.len]
    }

    /// Travel at which the latch clicks \[m\].
    pub fn latch_at(&self) -> f64 {
        self.latch_at
    }

    /// Force a latched connector holds against pulling \[N\].
    pub fn retention(&self) -> f64 {
        self.retention
    }

    /// Whether the latch holds at travel `s` \[m\].
    pub fn latched(&self, s: f64) -> bool {
        s >= self.latch_at
    }

    /// F(s): the curve at travel `s` \[m\], linear between its points, held at its first
    /// and last values outside them \[N\]; NaN counts as the mouth.
    pub fn mating_force(&self, s: f64) -> f64 {
        let s = if s.is_nan() { 0.0 } else { s };
        let curve = self.curve();
        let after = curve.partition_point(|&(t, _)| t <= s);
        match (after.checked_sub(1).map(|k| curve[k]), curve.get(after)) {
            (Some((s0, f0)), Some(&(s1, f1))) => f0 + (f1 - f0) * (s - s0) / (s1 - s0),
            (Some((_, f)), None) | (None, Some(&(_, f))) => f,
            (None, None) => 0.0,
        }
    }

    /// The largest force of the curve \[N\]: what the hand must overcome to plug it.
    pub fn peak_force(&self) -> f64 {
        self.curve().iter().map(|&(_, f)| f).fold(0.0, f64::max)
    }

    /// Force \[N\] to move the plug in `sense` at travel `s`: F(s) pushing in; pulling out,
    /// the retention force once latched, F(s) before (see the module's law).
    pub fn force_moving(&self, s: f64, sense: Sense) -> f64 {
        match sense {
            Sense::Off if self.latched(s) => self.retention,
            _ => self.mating_force(s),
        }
    }
}
