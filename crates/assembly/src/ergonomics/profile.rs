//! Which rows and columns of the ergonomic tables (SPEC I3) apply to a study: the user
//! picks them once, and every hand load is judged against them.

use super::error::ErgonomicsError;
use super::names::{parse_named, Duty, Population, Posture, PullPosture, PushPosture, TorqueGrip};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// The table rows and columns that judge a hand load.
///
/// Default: push standing (table 3.7 row 1), pull standing lever (table 3.9 row 1),
/// torque T-handle (table 3.11 row 2), women, occasional duty. Reasons:
/// - standing is the posture of the dissertation's own push-on trials (section 3.3.3);
/// - a hand holding a hose mostly bends it, which the dissertation equates with the
///   T-handle (the screwdriver stands for torsion about the hose's own axis; pick it for a
///   torsion study);
/// - every limit for women is below the one for men, so women is the conservative column;
/// - the critical actions (pushing onto and pulling off a stub) are short, which the
///   dissertation puts under occasional duty.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ErgonomicProfile {
    /// Row of the push tables (3.6 / 3.7).
    pub push_posture: PushPosture,
    /// Row of the pull tables (3.8 / 3.9).
    pub pull_posture: PullPosture,
    /// Row of the torque tables (3.10 / 3.11).
    pub torque_grip: TorqueGrip,
    /// Column: women or men.
    pub population: Population,
    /// Column group: continuous or occasional.
    pub duty: Duty,
}

impl ErgonomicProfile {
    /// The profile for one posture word ([`Posture::push`], [`Posture::pull`]) with the
    /// default torque grip.
    pub fn for_posture(posture: Posture, population: Population, duty: Duty) -> Self {
        ErgonomicProfile {
            push_posture: posture.push(),
            pull_posture: posture.pull(),
            torque_grip: TorqueGrip::default(),
            population,
            duty,
        }
    }
}

/// Parses `key=value` pairs separated by commas, applied in order on top of the default,
/// e.g. `posture=crouching, population=men, duty=continuous` or
/// `push=sitting,pull=handle,torque=screwdriver`. Keys: `posture` (sets push and pull),
/// `push`, `pull`, `torque`, `population`, `duty`. An empty string is the default.
impl ErgonomicProfile {
    /// The keys [`Self::set`] takes, in the order a profile is best written.
    pub const KEYS: [&'static str; 6] = ["posture", "push", "pull", "torque", "population", "duty"];

    /// Sets one named part of the profile — `posture` (both the push and the pull row),
    /// `push`, `pull`, `torque`, `population` or `duty` — from its name as the tables
    /// spell it. The one parser behind `--ergonomics`, a scene's `[ergonomics]` and the
    /// protocol's `set_ergonomics`.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ErgonomicsError> {
        let value = value.trim();
        match key.trim().to_ascii_lowercase().as_str() {
            "posture" => {
                let posture: Posture = parse_named(value)?;
                self.push_posture = posture.push();
                self.pull_posture = posture.pull();
            }
            "push" => self.push_posture = parse_named(value)?,
            "pull" => self.pull_posture = parse_named(value)?,
            "torque" => self.torque_grip = parse_named(value)?,
            "population" => self.population = parse_named(value)?,
            "duty" => self.duty = parse_named(value)?,
            other => {
                return Err(ErgonomicsError::Profile {
                    given: other.to_string(),
                    reason: format!("unknown key `{other}`; allowed: {}", Self::KEYS.join(", ")),
                })
            }
        }
        Ok(())
    }
}

impl FromStr for ErgonomicProfile {
    type Err = ErgonomicsError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let refuse = |reason: String| ErgonomicsError::Profile {
            given: text.to_string(),
            reason,
        };
        let mut profile = ErgonomicProfile::default();
        for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (key, value) = item
                .split_once('=')
                .ok_or_else(|| refuse(format!("`{item}` is not of the form key=value")))?;
            profile.set(key, value).map_err(|e| match e {
                ErgonomicsError::Profile { reason, .. } => refuse(reason),
                other => refuse(other.to_string()),
            })?;
        }
        Ok(profile)
    }
}

/// Writes the profile in the form [`FromStr`] reads.
impl fmt::Display for ErgonomicProfile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "push={},pull={},torque={},population={},duty={}",
            self.push_posture, self.pull_posture, self.torque_grip, self.population, self.duty
        )
    }
}
