//! Which rows and columns of the ergonomic tables (SPEC I3) apply to a study — or, with
//! `standard = en1005-3`, which EN 1005-3 action and conditions: the user picks them once,
//! and every hand load is judged against them.

use super::en1005::En1005Params;
use super::error::ErgonomicsError;
use super::names::{parse_named, Duty, Named, Population, Posture, PullPosture, PushPosture};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Which standard judges the hand force (push and pull).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Standard {
    /// The dissertation's tables 3.6–3.9 (Schmidtke's guide and limit values).
    #[default]
    Dissertation,
    /// EN 1005-3:2002+A1:2008 (recommended force limits, risk zones).
    En1005_3,
}
named_enum!(Standard, "standard", [
    Dissertation => "dissertation",
    En1005_3 => "en1005_3",
]);

impl Standard {
    /// How reports name it.
    pub fn title(self) -> &'static str {
        match self {
            Standard::Dissertation => "dissertation tables 3.6–3.11 (Schmidtke)",
            Standard::En1005_3 => "EN 1005-3:2002+A1:2008",
        }
    }
}

/// The table rows and columns that judge a hand load.
///
/// Default: push standing (table 3.7 row 1), pull standing lever (table 3.9 row 1),
/// women, occasional duty, moments as guidance only. Reasons:
/// - standing is the posture of the dissertation's own push-on trials (section 3.3.3);
/// - twist and bending are "never reasons for an installation to fail" (section 3.3.3,
///   after table 3.11), so by default they are warnings; twist is always judged against
///   the screwdriver row, bending against the T-handle row (no choice to make);
/// - every limit for women is below the one for men, so women is the conservative column;
/// - the critical actions (pushing onto and pulling off a stub) are short, which the
///   dissertation puts under occasional duty.
/// - the dissertation's tables judge; EN 1005-3 is chosen with `standard = en1005-3`
///   (its parameters default to F_R = F_B, see [`En1005Params`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ErgonomicProfile {
    /// Row of the push tables (3.6 / 3.7).
    pub push_posture: PushPosture,
    /// Row of the pull tables (3.8 / 3.9).
    pub pull_posture: PullPosture,
    /// Whether twist (screwdriver row) and bending (T-handle row) of tables 3.10 / 3.11
    /// count towards feasibility. Default `false`: the dissertation uses them as a rough
    /// guide only (section 3.3.3); they are reported as warnings.
    pub moments_decide: bool,
    /// Column: women or men.
    pub population: Population,
    /// Column group: continuous or occasional.
    pub duty: Duty,
    /// Which standard judges push and pull. Under EN 1005-3 the push and pull rows above
    /// are not used; twist and bending are still judged against tables 3.10 / 3.11 in
    /// the columns `population` and `duty` (EN 1005-3 gives no turning limits).
    pub standard: Standard,
    /// The EN 1005-3 action and conditions (used when `standard` is EN 1005-3).
    pub en1005: En1005Params,
}

impl ErgonomicProfile {
    /// The profile for one posture word ([`Posture::push`], [`Posture::pull`]), moments
    /// as guidance only.
    pub fn for_posture(posture: Posture, population: Population, duty: Duty) -> Self {
        ErgonomicProfile {
            push_posture: posture.push(),
            pull_posture: posture.pull(),
            moments_decide: false,
            population,
            duty,
            ..Default::default()
        }
    }
}

/// Parses `key=value` pairs separated by commas, applied in order on top of the default,
/// e.g. `posture=crouching, population=men, duty=continuous` or
/// `push=sitting,pull=handle,moments_decide=true`, or
/// `standard=en1005-3, action=whole_body, frequency_per_min=1`. Keys: `posture` (sets push
/// and pull), `push`, `pull`, `population`, `duty`, `moments_decide`, `standard`, and the
/// EN 1005-3 parameters ([`En1005Params::KEYS`], only after `standard=en1005-3`). An
/// empty string is the default.
impl ErgonomicProfile {
    /// The keys [`Self::set`] takes, in the order a profile is best written: the
    /// dissertation's, `standard`, then EN 1005-3's ([`En1005Params::KEYS`]).
    pub const KEYS: [&'static str; 14] = {
        let own = [
            "posture",
            "push",
            "pull",
            "population",
            "duty",
            "moments_decide",
            "standard",
        ];
        let mut keys = [""; 14];
        let mut i = 0;
        while i < 7 {
            keys[i] = own[i];
            keys[i + 7] = En1005Params::KEYS[i];
            i += 1;
        }
        keys
    };

    /// Sets one named part of the profile — `posture` (both the push and the pull row),
    /// `push`, `pull`, `population`, `duty` (names as the tables spell them) or
    /// `moments_decide` (`true` / `false`). The one parser behind `--ergonomics`, a scene's `[ergonomics]` and the
    /// protocol's `set_ergonomics`.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ErgonomicsError> {
        let value = value.trim();
        let key = key.trim().to_ascii_lowercase();
        if En1005Params::KEYS.contains(&key.as_str()) {
            if self.standard != Standard::En1005_3 {
                return Err(ErgonomicsError::Profile {
                    given: format!("{key}={value}"),
                    reason: format!(
                        "`{key}` is an EN 1005-3 parameter: give `standard=en1005-3` first"
                    ),
                });
            }
            return self.en1005.set(&key, value).unwrap_or(Ok(()));
        }
        match key.as_str() {
            "standard" => {
                let standard: Standard = parse_named(value)?;
                if standard != self.standard {
                    self.en1005 = En1005Params::default();
                }
                self.standard = standard;
            }
            "posture" => {
                let posture: Posture = parse_named(value)?;
                self.push_posture = posture.push();
                self.pull_posture = posture.pull();
            }
            "push" => self.push_posture = parse_named(value)?,
            "pull" => self.pull_posture = parse_named(value)?,
            "moments_decide" => {
                self.moments_decide = match value.to_ascii_lowercase().as_str() {
                    "true" | "yes" => true,
                    "false" | "no" => false,
                    _ => {
                        return Err(ErgonomicsError::Profile {
                            given: value.to_string(),
                            reason: "`moments_decide` must be true or false".into(),
                        })
                    }
                }
            }
            "torque" => {
                return Err(ErgonomicsError::Profile {
                    given: value.to_string(),
                    reason: "`torque` is no longer chosen: twist is judged against the \
                             screwdriver row and bending against the T-handle row of tables \
                             3.10/3.11; use `moments_decide = true` to make them decide \
                             feasibility"
                        .into(),
                })
            }
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
            "push={},pull={},population={},duty={},moments_decide={}",
            self.push_posture, self.pull_posture, self.population, self.duty, self.moments_decide
        )?;
        if self.standard != Standard::default() {
            write!(f, ",standard={},", self.standard.name())?;
            self.en1005.write(f)?;
        }
        Ok(())
    }
}
