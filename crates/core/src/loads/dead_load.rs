//! Dead load: a force and moment at a node, fixed in global axes (it does not turn with
//! the hose), as used by the tip-load and roll-up validation cases. It acts at once, or
//! grows linearly from zero over a ramp (a load a worker builds up, or a load step a
//! static study takes gradually), or fades smoothly to zero (a hand letting go: the force
//! it held the hose with, [`LoadRamp::smooth_fall`]).

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct DeadLoad {
    pub node: usize,
    /// Force \[N\], global axes (the full value, reached at the end of the ramp).
    pub force: DVec3,
    /// Moment \[N·m\], global axes.
    pub moment: DVec3,
    /// Grows linearly from zero over this ramp; `None` acts in full at once.
    pub ramp: Option<LoadRamp>,
}

/// A linear rise from zero at `start` \[s\] to the full load at `start + duration`, or
/// (`falls`) a smooth fall from the full load to zero over that time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadRamp {
    pub start: f64,
    pub duration: f64,
    /// Falls to zero instead of rising from it.
    pub falls: bool,
}

impl LoadRamp {
    /// Rises linearly from zero at `start` to the full load at `start + duration`.
    pub fn rise(start: f64, duration: f64) -> Self {
        LoadRamp {
            start,
            duration,
            falls: false,
        }
    }

    /// Falls from the full load at `start` to zero at `start + duration` along
    /// 1 − (3s² − 2s³), s = (t − start)/duration: no jump in the load or in its rate, so
    /// the fall excites the hose's fast modes little once it lasts several of their
    /// periods (a hand letting go, [`DeadLoad::is_release`]).
    pub fn smooth_fall(start: f64, duration: f64) -> Self {
        LoadRamp {
            start,
            duration,
            falls: true,
        }
    }
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

    /// Whether this is what a hand left behind on letting go (a fall to zero): gone once a
    /// hand or a fix takes the node again.
    pub fn is_release(&self) -> bool {
        self.ramp.is_some_and(|r| r.falls)
    }

    /// The share of the full load acting at time `t`: rising, min(1, max(0, (t − t₀)/T));
    /// falling, 1 − (3s² − 2s³) with that s.
    pub fn factor(&self, t: f64) -> f64 {
        match self.ramp {
            Some(r) if r.falls && r.duration > 0.0 => {
                let s = ((t - r.start) / r.duration).clamp(0.0, 1.0);
                1.0 - s * s * (3.0 - 2.0 * s)
            }
            Some(r) if r.falls => {
                if t < r.start {
                    1.0
                } else {
                    0.0
                }
            }
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

    /// Force \[N\] and moment \[N·m\] acting at time `t`.
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
        load.ramp = Some(LoadRamp::rise(1.0, 0.5));
        assert_eq!(load.factor(0.5), 0.0);
        assert_eq!(load.factor(1.0), 0.0);
        assert_eq!(load.factor(1.25), 0.5);
        assert_eq!(load.factor(1.5), 1.0);
        assert_eq!(load.factor(9.0), 1.0);
        assert_eq!(load.at(1.25).0, DVec3::new(0.0, 0.0, -5.0));
        assert!(!load.is_release());
    }

    #[test]
    fn a_fall_goes_smoothly_from_the_full_load_to_zero() {
        let mut load = DeadLoad::constant(3, DVec3::new(0.0, 0.0, -10.0), DVec3::X);
        load.ramp = Some(LoadRamp::smooth_fall(1.0, 0.5));
        assert!(load.is_release());
        assert_eq!(load.factor(0.5), 1.0);
        assert_eq!(load.factor(1.0), 1.0);
        assert_eq!(load.factor(1.25), 0.5);
        assert_eq!(load.factor(1.5), 0.0);
        assert_eq!(load.factor(9.0), 0.0);
        // 1 − (3s² − 2s³) at s = 0.1: 0.972, flat at both ends
        assert!((load.factor(1.05) - 0.972).abs() < 1e-12);
        let rate = |t: f64| (load.factor(t + 1e-7) - load.factor(t - 1e-7)) / 2e-7;
        assert!(rate(1.0 + 1e-6).abs() < 1e-3 && rate(1.5 - 1e-6).abs() < 1e-3);
        assert!((rate(1.25) + 3.0).abs() < 1e-6, "steepest mid-way: −1.5/T");
    }
}
