//! What the worker could not do, as typed verdict reasons (SPEC E1): a hand target out
//! of reach, a body segment inside a part. Each says who, how far, where and when.

use serde::Serialize;

/// One thing the worker could not do, at its worst.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum WorkerFinding {
    /// A hand target the arm could not reach: the grip centre stayed `distance` \[m\]
    /// short of it at its worst, at `time` \[s\].
    OutOfReach {
        /// "the 5th-percentile woman".
        who: String,
        /// "right" or "left".
        arm: &'static str,
        /// The workcell hand whose target it was.
        hand: usize,
        distance: f64,
        time: f64,
        /// The first and last posed instants it was out of reach \[s\].
        first_time: f64,
        last_time: f64,
    },
    /// A body segment inside a part or a hose, `depth` \[m\] at its deepest, at `time`
    /// \[s\].
    Collision {
        who: String,
        segment: String,
        /// The part's or hose's name.
        part: String,
        /// "part" or "hose".
        obstacle: &'static str,
        depth: f64,
        time: f64,
        first_time: f64,
        last_time: f64,
    },
}

impl WorkerFinding {
    /// The finding in words, e.g. "out of reach for the 5th-percentile woman by 120 mm
    /// at t = 3.20 s (hand 0, right arm; from t = 3.00 s to 3.40 s)".
    pub fn describe(&self) -> String {
        let span = |a: f64, b: f64| {
            if a == b {
                String::new()
            } else {
                format!("; from t = {a:.2} s to {b:.2} s")
            }
        };
        match self {
            WorkerFinding::OutOfReach {
                who,
                arm,
                hand,
                distance,
                time,
                first_time,
                last_time,
            } => format!(
                "out of reach for {who} by {:.0} mm at t = {time:.2} s (hand {hand}, {arm} arm{})",
                distance * 1e3,
                span(*first_time, *last_time)
            ),
            WorkerFinding::Collision {
                who,
                segment,
                part,
                obstacle,
                depth,
                time,
                first_time,
                last_time,
            } => {
                format!(
                "body collision: {who}'s {segment} is {:.0} mm {} '{part}' at t = {time:.2} s{}",
                depth * 1e3,
                if *obstacle == "hose" { "into hose" } else { "inside" },
                span(*first_time, *last_time)
            )
            }
        }
    }
}
