//! The ergonomic guide and limit values (SPEC I3; dissertation tables 3.6–3.11, quoting
//! Schmidtke's "Handbuch der Ergonomie"). The data lives in `data/ergonomics.toml`
//! (embedded at build time) with the source of every table; this module only reads and
//! checks it. Forces are in newtons, torques in newton-metres.

use super::en1005::{En1005Limit, En1005Tables};
use super::error::ErgonomicsError;
use super::names::{parse_named, Duty, Named, Population, PullPosture, PushPosture, TorqueGrip};
use super::profile::{ErgonomicProfile, Standard};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::marker::PhantomData;
use std::sync::OnceLock;

/// The limits file, as shipped.
pub const ERGONOMICS_TOML: &str = include_str!("../../data/ergonomics.toml");

/// A guide value: the recommended range [lo, hi] (N or N·m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GuideRange {
    pub lo: f64,
    pub hi: f64,
}

/// One table: a value per row (posture or grip `P`), duty and population, with its
/// provenance and unit.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Table<P, V> {
    source: String,
    unit: String,
    /// Indexed `[posture][duty][population]`; one row per value of `P::ALL`.
    rows: Vec<[[V; 2]; 2]>,
    posture: PhantomData<P>,
}

impl<P: Named, V: Copy> Table<P, V> {
    /// The value for this posture, population and duty.
    pub fn get(&self, posture: P, population: Population, duty: Duty) -> V {
        self.rows[posture.index()][duty.index()][population.index()]
    }

    /// Where the table comes from, e.g. "dissertation table 3.7: …".
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Unit of the values: "N" or "N m".
    pub fn unit(&self) -> &str {
        &self.unit
    }
}

/// Provenance of one table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableInfo<'a> {
    /// Key in the limits file, e.g. `push_limit`.
    pub key: &'static str,
    /// Where the table comes from, e.g. "dissertation table 3.7: …".
    pub source: &'a str,
    /// Unit of its values: "N" or "N m".
    pub unit: &'a str,
}

/// All six tables of SPEC I3; look values up with the methods.
#[derive(Clone, Debug, PartialEq)]
pub struct ErgonomicLimits {
    /// Push against a plane, guide values (table 3.6) \[N\].
    push_guide: Table<PushPosture, GuideRange>,
    /// Push against a plane, limit values (table 3.7) \[N\].
    push_limit: Table<PushPosture, f64>,
    /// Pull, guide values (table 3.8) \[N\].
    pull_guide: Table<PullPosture, GuideRange>,
    /// Pull, limit values (table 3.9) \[N\].
    pull_limit: Table<PullPosture, f64>,
    /// Turning, guide values (table 3.10) \[N·m\].
    torque_guide: Table<TorqueGrip, GuideRange>,
    /// Turning, limit values (table 3.11) \[N·m\].
    torque_limit: Table<TorqueGrip, f64>,
    /// EN 1005-3, the alternative standard for push and pull (`data/en1005_3.toml`).
    en1005: En1005Tables,
}

impl ErgonomicLimits {
    /// The built-in limits (parsed once).
    pub fn builtin() -> Result<&'static ErgonomicLimits, ErgonomicsError> {
        static BUILTIN: OnceLock<Result<ErgonomicLimits, ErgonomicsError>> = OnceLock::new();
        BUILTIN
            .get_or_init(|| ErgonomicLimits::parse(ERGONOMICS_TOML))
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Reads a limits file in the format of `data/ergonomics.toml` and checks it: every
    /// row present once, every value finite and positive, lo ≤ hi for guide ranges, and
    /// each guide range's upper end at most the matching limit value.
    pub fn parse(text: &str) -> Result<ErgonomicLimits, ErgonomicsError> {
        let raw: RawFile =
            toml::from_str(text).map_err(|e| ErgonomicsError::File(e.to_string()))?;
        let limits = ErgonomicLimits {
            push_guide: raw.push_guide.build("push_guide", "N")?,
            push_limit: raw.push_limit.build("push_limit", "N")?,
            pull_guide: raw.pull_guide.build("pull_guide", "N")?,
            pull_limit: raw.pull_limit.build("pull_limit", "N")?,
            torque_guide: raw.torque_guide.build("torque_guide", "N m")?,
            torque_limit: raw.torque_limit.build("torque_limit", "N m")?,
            en1005: En1005Tables::builtin()?.clone(),
        };
        check_guides_below_limits("push", &limits.push_guide, &limits.push_limit)?;
        check_guides_below_limits("pull", &limits.pull_guide, &limits.pull_limit)?;
        check_guides_below_limits("torque", &limits.torque_guide, &limits.torque_limit)?;
        Ok(limits)
    }

    /// The EN 1005-3 data.
    pub fn en1005(&self) -> &En1005Tables {
        &self.en1005
    }

    /// The guide range and limit value \[N\] a push (`push = true`) or a pull is judged
    /// against under `profile`: the dissertation's tables 3.6–3.9, or under EN 1005-3
    /// [0, 0.5 F_R] and 0.7 F_R with the F_R they come from (see `super::en1005`).
    pub fn force_limits(
        &self,
        profile: &ErgonomicProfile,
        push: bool,
    ) -> (GuideRange, f64, Option<En1005Limit>) {
        let (pop, duty) = (profile.population, profile.duty);
        match profile.standard {
            Standard::En1005_3 => {
                let l = self.en1005.limit(&profile.en1005, push);
                let guide = GuideRange {
                    lo: 0.0,
                    hi: l.recommended(),
                };
                (guide, l.limit(), Some(l))
            }
            Standard::Dissertation if push => (
                self.push_guide(profile.push_posture, pop, duty),
                self.push_limit(profile.push_posture, pop, duty),
                None,
            ),
            Standard::Dissertation => (
                self.pull_guide(profile.pull_posture, pop, duty),
                self.pull_limit(profile.pull_posture, pop, duty),
                None,
            ),
        }
    }

    /// Push guide range (table 3.6) \[N\].
    pub fn push_guide(
        &self,
        posture: PushPosture,
        population: Population,
        duty: Duty,
    ) -> GuideRange {
        self.push_guide.get(posture, population, duty)
    }

    /// Push limit (table 3.7) \[N\].
    pub fn push_limit(&self, posture: PushPosture, population: Population, duty: Duty) -> f64 {
        self.push_limit.get(posture, population, duty)
    }

    /// Pull guide range (table 3.8) \[N\].
    pub fn pull_guide(
        &self,
        posture: PullPosture,
        population: Population,
        duty: Duty,
    ) -> GuideRange {
        self.pull_guide.get(posture, population, duty)
    }

    /// Pull limit (table 3.9) \[N\].
    pub fn pull_limit(&self, posture: PullPosture, population: Population, duty: Duty) -> f64 {
        self.pull_limit.get(posture, population, duty)
    }

    /// Torque guide range (table 3.10) \[N·m\].
    pub fn torque_guide(&self, grip: TorqueGrip, population: Population, duty: Duty) -> GuideRange {
        self.torque_guide.get(grip, population, duty)
    }

    /// Torque limit (table 3.11) \[N·m\].
    pub fn torque_limit(&self, grip: TorqueGrip, population: Population, duty: Duty) -> f64 {
        self.torque_limit.get(grip, population, duty)
    }

    /// Key, source and unit of every table, in file order.
    pub fn tables(&self) -> [TableInfo<'_>; 6] {
        let info = |key, source, unit| TableInfo { key, source, unit };
        [
            info(
                "push_guide",
                self.push_guide.source(),
                self.push_guide.unit(),
            ),
            info(
                "push_limit",
                self.push_limit.source(),
                self.push_limit.unit(),
            ),
            info(
                "pull_guide",
                self.pull_guide.source(),
                self.pull_guide.unit(),
            ),
            info(
                "pull_limit",
                self.pull_limit.source(),
                self.pull_limit.unit(),
            ),
            info(
                "torque_guide",
                self.torque_guide.source(),
                self.torque_guide.unit(),
            ),
            info(
                "torque_limit",
                self.torque_limit.source(),
                self.torque_limit.unit(),
            ),
        ]
    }
}

/// Every guide range's upper end must not exceed the limit of the same cell.
fn check_guides_below_limits<P: Named>(
    kind: &str,
    guide: &Table<P, GuideRange>,
    limit: &Table<P, f64>,
) -> Result<(), ErgonomicsError> {
    for &posture in P::ALL {
        for &duty in Duty::ALL {
            for &population in Population::ALL {
                let g = guide.get(posture, population, duty);
                let l = limit.get(posture, population, duty);
                if g.hi > l {
                    return Err(ErgonomicsError::File(format!(
                        "{kind} {posture_name} {duty_name} {population_name}: guide value {hi} exceeds the limit value {l}",
                        posture_name = posture.name(),
                        duty_name = duty.name(),
                        population_name = population.name(),
                        hi = g.hi,
                    )));
                }
            }
        }
    }
    Ok(())
}

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    push_guide: RawTable<[f64; 2]>,
    push_limit: RawTable<f64>,
    pull_guide: RawTable<[f64; 2]>,
    pull_limit: RawTable<f64>,
    torque_guide: RawTable<[f64; 2]>,
    torque_limit: RawTable<f64>,
}

/// A table as written: provenance, unit and one entry per row name.
#[derive(Deserialize)]
struct RawTable<V> {
    source: String,
    unit: String,
    #[serde(flatten)]
    rows: BTreeMap<String, RawRow<V>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRow<V> {
    continuous: RawPair<V>,
    occasional: RawPair<V>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPair<V> {
    women: V,
    men: V,
}

/// A value as written, checked and converted.
trait RawValue: Copy {
    type Value: Copy;
    fn build(self, at: &str) -> Result<Self::Value, ErgonomicsError>;
}

fn positive(value: f64, at: &str) -> Result<f64, ErgonomicsError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ErgonomicsError::File(format!(
            "{at}: {value} must be finite and positive"
        )))
    }
}

impl RawValue for f64 {
    type Value = f64;
    fn build(self, at: &str) -> Result<f64, ErgonomicsError> {
        positive(self, at)
    }
}

impl RawValue for [f64; 2] {
    type Value = GuideRange;
    fn build(self, at: &str) -> Result<GuideRange, ErgonomicsError> {
        let [lo, hi] = [positive(self[0], at)?, positive(self[1], at)?];
        if lo > hi {
            return Err(ErgonomicsError::File(format!(
                "{at}: guide range [{lo}, {hi}] must have lo <= hi"
            )));
        }
        Ok(GuideRange { lo, hi })
    }
}

impl<V: RawValue> RawTable<V> {
    /// Checks provenance and unit, maps row names onto `P` and requires every row once.
    fn build<P: Named>(self, key: &str, unit: &str) -> Result<Table<P, V::Value>, ErgonomicsError> {
        if self.source.trim().is_empty() {
            return Err(ErgonomicsError::File(format!(
                "{key}: `source` must not be empty"
            )));
        }
        if self.unit != unit {
            return Err(ErgonomicsError::File(format!(
                "{key}: unit must be \"{unit}\", found \"{}\"",
                self.unit
            )));
        }
        let mut rows: Vec<Option<[[V::Value; 2]; 2]>> = vec![None; P::ALL.len()];
        for (name, row) in self.rows {
            let posture: P =
                parse_named(&name).map_err(|e| ErgonomicsError::File(format!("{key}: {e}")))?;
            let at = |duty: &str, population: &str| format!("{key}.{name}.{duty}.{population}");
            // [duty][population], in the order of `Duty::ALL` and `Population::ALL`.
            let values = [
                [
                    row.continuous.women.build(&at("continuous", "women"))?,
                    row.continuous.men.build(&at("continuous", "men"))?,
                ],
                [
                    row.occasional.women.build(&at("occasional", "women"))?,
                    row.occasional.men.build(&at("occasional", "men"))?,
                ],
            ];
            if rows[posture.index()].replace(values).is_some() {
                return Err(ErgonomicsError::File(format!(
                    "{key}: row `{}` is given twice",
                    posture.name()
                )));
            }
        }
        let rows = P::ALL
            .iter()
            .zip(rows)
            .map(|(p, row)| {
                row.ok_or_else(|| {
                    ErgonomicsError::File(format!("{key}: row `{}` is missing", p.name()))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Table {
            source: self.source,
            unit: self.unit,
            rows,
            posture: PhantomData,
        })
    }
}
