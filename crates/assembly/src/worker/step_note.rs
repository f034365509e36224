//! A step the worker took (SPEC E1: "the feet kept, or allowed to step, reported as a
//! step"): when, how far, which way and why — to reach a hand target out of reach with
//! the feet kept (`[worker] steps = true`), back once every target is within reach from
//! where the worker was placed, or to stay under a VR user who walked.

use glam::DVec3;
use serde::Serialize;
use std::fmt;

/// Why the worker stepped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StepCause {
    /// A hand target out of reach with the feet kept; the workcell hand whose it was.
    Reach { hand: usize },
    /// The VR user's headset moved away from the stance.
    Walk,
    /// Back to where the worker was placed, every hand target within reach from there
    /// again.
    Return,
}

/// One step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepNote {
    /// "the 50th-percentile man".
    pub who: String,
    /// When \[s\].
    pub time: f64,
    /// Its length \[m\], the turn of the facing \[rad, positive to the left\] and, in words,
    /// which way from the stance it left: "0.32 m forward", "0.30 m to the left, turning
    /// 90° to the left".
    pub length: f64,
    pub turn: f64,
    pub words: String,
    /// The floor point between the feet before and after \[m\].
    pub from: DVec3,
    pub to: DVec3,
    pub cause: StepCause,
}

impl fmt::Display for StepNote {
    /// E.g. "the 50th-percentile man steps 0.32 m forward at t = 3.20 s (to reach hand 0)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} steps {} at t = {:.2} s ",
            self.who, self.words, self.time
        )?;
        match self.cause {
            StepCause::Reach { hand } => write!(f, "(to reach hand {hand})"),
            StepCause::Walk => f.write_str("(with the VR user)"),
            StepCause::Return => f.write_str("(back to where he was placed)"),
        }
    }
}
