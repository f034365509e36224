//! When a Newton solve has converged ("convergence is honest"): every free
//! node's out-of-balance force and moment, each against the size of the loads in the
//! problem — so the same setting works for a 1 mm silicone tube carrying millinewtons and
//! a steel pipe carrying kilonewtons — with optional absolute floors.
//!
//! The load scale F is the largest force any element end, weight, dead load or contact
//! puts on a node; the moment scale M the largest such moment, and at least F times the
//! mean element length (so that a hose carrying only axial force still has a moment
//! scale). A node is balanced when |r_f| ≤ max(f_abs, ε F) and |r_m| ≤ max(m_abs, ε M).

/// The size of the loads of an assembly ([`super::NewtonSystem::assemble`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LoadScale {
    /// Largest force on a node from one element end, its weight, a dead load or contact \[N\].
    pub force: f64,
    /// Largest such moment, at least `force` × mean element length \[N·m\].
    pub moment: f64,
}

impl LoadScale {
    /// Takes in one force and one moment.
    pub fn include(&mut self, force: f64, moment: f64) {
        self.force = self.force.max(force);
        self.moment = self.moment.max(moment);
    }
}

/// How close to balance a Newton solve must come.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// ε: the allowed residual as a fraction of the load scale.
    pub relative: f64,
    /// Absolute floors \[N\] and \[N·m\] (0: the relative test alone).
    pub force: f64,
    pub moment: f64,
}

impl Default for Tolerance {
    fn default() -> Self {
        Self {
            relative: 1e-8,
            force: 0.0,
            moment: 0.0,
        }
    }
}

impl Tolerance {
    /// Absolute tolerances only, as a caller who knows the problem's loads gives them.
    pub fn absolute(force: f64, moment: f64) -> Self {
        Self {
            relative: 0.0,
            force,
            moment,
        }
    }

    /// The largest residual force and moment allowed under loads of `scale`.
    pub fn limits(&self, scale: LoadScale) -> (f64, f64) {
        (
            self.force.max(self.relative * scale.force),
            self.moment.max(self.relative * scale.moment),
        )
    }

    /// Whether residuals (largest over the free nodes) are within the limits.
    pub fn met(&self, scale: LoadScale, residual_force: f64, residual_moment: f64) -> bool {
        let (f, m) = self.limits(scale);
        residual_force <= f && residual_moment <= m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same relative setting accepts the same relative error at any load level.
    #[test]
    fn relative_test_is_scale_free() {
        let tol = Tolerance::default();
        for size in [1e-3, 1.0, 1e5] {
            let scale = LoadScale {
                force: size,
                moment: 0.1 * size,
            };
            assert!(tol.met(scale, 0.5e-8 * size, 0.5e-9 * size));
            assert!(!tol.met(scale, 2e-8 * size, 0.0));
            assert!(!tol.met(scale, 0.0, 2e-9 * size));
        }
    }

    #[test]
    fn absolute_floor_applies_when_loads_vanish() {
        let tol = Tolerance::absolute(1e-7, 1e-8);
        assert!(tol.met(LoadScale::default(), 1e-7, 1e-8));
        assert!(!tol.met(LoadScale::default(), 2e-7, 0.0));
    }
}
