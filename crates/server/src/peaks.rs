//! The peak loads of one hand over a session (SPEC I2): the largest push, pull and torque
//! magnitudes and when they occurred. Kept as magnitudes, not ratios, so that the running
//! verdict can be re-judged when the user picks another ergonomic profile.

use pliant_assembly::ergonomics::{HandAssessment, LoadKind};

/// One peak: the largest magnitude [N or N·m] and its time [s].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Peak {
    pub magnitude: f64,
    pub time: f64,
}

impl Peak {
    fn record(&mut self, magnitude: f64, time: f64) {
        if magnitude.is_finite() && magnitude > self.magnitude {
            self.magnitude = magnitude;
            self.time = time;
        }
    }
}

/// A hand's peak push, pull and torque.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HandPeaks {
    pub push: Peak,
    pub pull: Peak,
    pub torque: Peak,
}

impl HandPeaks {
    /// Takes in one step's assessment at time `time`.
    pub fn record(&mut self, a: &HandAssessment, time: f64) {
        match a.force.kind {
            LoadKind::Pull => self.pull.record(a.force.magnitude, time),
            _ => self.push.record(a.force.magnitude, time),
        }
        self.torque.record(a.torque.magnitude, time);
    }

    /// The peaks with their kinds.
    pub fn each(&self) -> [(LoadKind, Peak); 3] {
        [
            (LoadKind::Push, self.push),
            (LoadKind::Pull, self.pull),
            (LoadKind::Torque, self.torque),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use pliant_assembly::ergonomics::{ErgonomicLimits, ErgonomicProfile};

    #[test]
    fn keeps_the_largest_of_each_kind() {
        let limits = ErgonomicLimits::builtin().unwrap();
        let p = ErgonomicProfile::default();
        let d = DVec3::X;
        let mut peaks = HandPeaks::default();
        let a = |f: DVec3, t: DVec3| limits.assess(&p, f, t, d).unwrap();
        peaks.record(&a(DVec3::new(5.0, 0.0, 0.0), DVec3::ZERO), 1.0);
        peaks.record(&a(DVec3::new(-8.0, 0.0, 0.0), DVec3::Z * 0.5), 2.0);
        peaks.record(&a(DVec3::new(3.0, 0.0, 0.0), DVec3::ZERO), 3.0);
        assert_eq!(
            peaks.push,
            Peak {
                magnitude: 5.0,
                time: 1.0
            }
        );
        assert_eq!(
            peaks.pull,
            Peak {
                magnitude: 8.0,
                time: 2.0
            }
        );
        assert_eq!(
            peaks.torque,
            Peak {
                magnitude: 0.5,
                time: 2.0
            }
        );
    }
}
