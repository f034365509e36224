//! Dead load: a force and moment at a node, fixed in global axes (it does not turn with
//! the hose), as used by the tip-load and roll-up validation cases. It acts at once, or
//! grows linearly from zero over a ramp (a load a worker builds up, or a load step a
//! static study takes gradually).

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct DeadLoad {
    pub node: usize,
    /// Force [N], global axes (the full value, reached at the end of the ramp).
    pub force: DVec3,
    /// Moment [N·m], global axes.
    pub moment: DVec3,
    /// Grows linearly from zero over this ramp; `None` acts in full at once.
    pub ramp: Option<LoadRamp>,
}

/// A linear rise from zero at `start` [s] to the full load at `start + duration`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadRamp {
    pub start: f64,
    pub duration: f64,
}

impl DeadLoad {
    /// A load acting in full at once.
    pub fn constant(node: usize, force: DVec3, moment: DVec3) -> Self {
        DeadLoad {
            node,
            force,
            moment,
            ramp: None,
        }
    }

    /// The share of the full load acting at time `t`: min(1, max(0, (t − t₀)/T)).
    pub fn factor(&self, t: f64) -> f64 {
        match self.ramp {
            Some(r) if r.duration > 0.0 => ((t - r.start) / r.duration).clamp(0.0, 1.0),
            Some(r) => {
                if t >= r.start {
                    1.0
                } else {
                    0.0
                }
            }
            None => 1.0,
        }
    }

    /// Force [N] and moment [N·m] acting at time `t`.
    pub fn at(&self, t: f64) -> (DVec3, DVec3) {
        let s = self.factor(t);
        (self.force * s, self.moment * s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_rises_linearly_from_zero_to_the_full_load() {
        let mut load = DeadLoad::constant(3, DVec3::new(0.0, 0.0, -10.0), DVec3::X);
        assert_eq!(load.at(-5.0), (load.force, load.moment));
        load.ramp = Some(LoadRamp {
            start: 1.0,
            duration: 0.5,
        });
        assert_eq!(load.factor(0.5), 0.0);
        assert_eq!(load.factor(1.0), 0.0);
        assert_eq!(load.factor(1.25), 0.5);
        assert_eq!(load.factor(1.5), 1.0);
        assert_eq!(load.factor(9.0), 1.0);
        assert_eq!(load.at(1.25).0, DVec3::new(0.0, 0.0, -5.0));
    }
}
