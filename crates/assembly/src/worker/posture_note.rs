//! The worker's worst posture scores (SPEC E2): RULA (McAtamney & Corlett 1993) and REBA
//! (Hignett & McAtamney 2000), when they were reached, and what their levels call for.

use super::track::ScoreAt;
use pliant_worker::reba::RebaScore;
use pliant_worker::rula::RulaScore;
use serde::Serialize;
use std::fmt;

/// The worst RULA and REBA scores of a study and when.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PostureNote {
    /// "the 50th-percentile man".
    pub who: String,
    pub rula: ScoreAt<RulaScore>,
    pub reba: ScoreAt<RebaScore>,
}

impl PostureNote {
    /// Whether the posture calls for change soon (RULA action level 3 or more, or REBA
    /// high risk or more).
    pub fn alarming(&self) -> bool {
        self.rula.score.action_level >= 3 || self.reba.score.risk_level >= 3
    }
}

impl fmt::Display for PostureNote {
    /// E.g. "posture of the 50th-percentile man: RULA 6 at t = 2.00 s (action level 3:
    /// investigate further and change soon), REBA 8 at t = 2.00 s (high risk)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (r, e) = (&self.rula, &self.reba);
        write!(
            f,
            "posture of {}: RULA {} at t = {:.2} s (action level {}: {}), REBA {} at t = {:.2} s ({} risk)",
            self.who,
            r.score.grand,
            r.time,
            r.score.action_level,
            rula_words(r.score.action_level),
            e.score.reba,
            e.time,
            reba_words(e.score.risk_level),
        )
    }
}

/// RULA's action levels in words (McAtamney & Corlett 1993).
pub fn rula_words(level: u8) -> &'static str {
    match level {
        1 => "acceptable",
        2 => "investigate further",
        3 => "investigate further and change soon",
        _ => "investigate and change immediately",
    }
}

/// REBA's risk levels in words (Hignett & McAtamney 2000).
pub fn reba_words(level: u8) -> &'static str {
    match level {
        0 => "negligible",
        1 => "low",
        2 => "medium",
        3 => "high",
        _ => "very high",
    }
}
