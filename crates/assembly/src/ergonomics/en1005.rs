//! EN 1005-3:2002+A1:2008 as an alternative to the dissertation's tables:
//! the recommended force limit of an action and the risk zone of a force against it.
//! The numbers live in `data/en1005_3.toml` (embedded at build time) with their sources
//! and how sure each is; this module reads, checks and applies them.
//!
//! Clause 4.2 of the standard, as Pliant applies it to a hand force judged as a push or a
//! pull (the rule of [`super::classify`]):
//!
//! ```text
//! Step A (4.2.1)  F_B     basic force capacity of the action's push or pull row (Table 1)
//! Step B (4.2.2)  F_Br =  F_B · exp((z_p − z_ref) · s)   population percentile p
//!                 F_R  =  F_Br · m_v · m_f · m_d           velocity, frequency, duration
//! Step C (4.2.3)  m_r  =  F / F_R:  ≤ 0.5 recommended, ≤ 0.7 not recommended, else to be avoided
//! ```
//!
//! with z_p the standard normal quantile, z_ref that of the percentile the table stands
//! for (15th, professional use) and s the standard deviation of ln F (an assumption of
//! the data file: the standard's Annex A distributions are not reproduced). In Pliant's
//! terms the guide range of a force is [0, 0.5 F_R] (recommended) and its limit value
//! 0.7 F_R: above it a force is "to be avoided" and makes the study infeasible.

use super::error::ErgonomicsError;
use super::names::{parse_named, Named};
use super::quantile::normal_quantile;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;

/// Why a frequency or duration range ends: the multiplier tables end there.
const TABLE_END: &str = " (EN 1005-3's table ends there)";

/// The data file, as shipped.
pub const EN1005_3_TOML: &str = include_str!("../../data/en1005_3.toml");

/// The action a worker performs (a pair of push and pull rows of Table 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum En1005Action {
    /// Whole body work, standing (push 200 N, pull 145 N).
    #[default]
    WholeBody,
    /// Arm work, sitting, one arm, with trunk support.
    ArmTrunkSupport,
    /// Arm work, sitting, one arm, without trunk support.
    Arm,
}
named_enum!(En1005Action, "EN 1005-3 action", [
    WholeBody => "whole_body",
    ArmTrunkSupport => "arm_trunk_support",
    Arm => "arm",
]);

/// How fast the limb moves while the force acts (multiplier m_v).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum En1005Velocity {
    /// Static or slow.
    #[default]
    Low,
    /// Noticeable velocity.
    High,
}
named_enum!(En1005Velocity, "EN 1005-3 velocity", [Low => "low", High => "high"]);

/// The risk zone of a force (EN 1005-3, 4.2.3 step C).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RiskZone {
    /// m_r ≤ 0.5 (green).
    Recommended,
    /// 0.5 < m_r ≤ 0.7 (yellow): the risk should be reduced.
    NotRecommended,
    /// m_r > 0.7 (red).
    ToBeAvoided,
}

impl RiskZone {
    /// The standard's words: "recommended", "not recommended", "to be avoided".
    pub fn words(self) -> &'static str {
        match self {
            RiskZone::Recommended => "recommended",
            RiskZone::NotRecommended => "not recommended",
            RiskZone::ToBeAvoided => "to be avoided",
        }
    }
}

/// The profile's EN 1005-3 parameters: which action, whose capacity, how it is done.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct En1005Params {
    /// The Table 1 rows a push and a pull are judged against.
    pub action: En1005Action,
    /// Percentile of the intended user population whose capacity counts (1–50);
    /// default 15 (professional use).
    pub percentile: f64,
    /// Velocity of the movement (m_v).
    pub velocity: En1005Velocity,
    /// Actions per minute (m_f); default 0.2 (at most one every five minutes).
    pub frequency_per_min: f64,
    /// How long one action lasts \[s\] (m_f: short up to 3 s); default 3.
    pub action_time_s: f64,
    /// Hours per day of this work (m_d); default 1.
    pub duration_h: f64,
}

impl Default for En1005Params {
    /// Professional use, one short, slow action now and then, up to an hour a day: every
    /// multiplier 1, F_R = F_B.
    fn default() -> Self {
        En1005Params {
            action: En1005Action::WholeBody,
            percentile: 15.0,
            velocity: En1005Velocity::Low,
            frequency_per_min: 0.2,
            action_time_s: 3.0,
            duration_h: 1.0,
        }
    }
}

impl En1005Params {
    /// The profile keys these parameters take (see [`Self::set`]).
    pub const KEYS: [&'static str; 7] = [
        "action",
        "use",
        "percentile",
        "velocity",
        "frequency_per_min",
        "action_time_s",
        "duration_h",
    ];

    /// Sets one parameter from text, checked against the built-in tables (the error
    /// names the key and the allowed values). `None` if `key` is not one of [`Self::KEYS`].
    pub fn set(&mut self, key: &str, value: &str) -> Option<Result<(), ErgonomicsError>> {
        let tables = match En1005Tables::builtin() {
            Ok(t) => t,
            Err(e) => return Some(Err(e)),
        };
        // `note`: why the range ends where it does
        let number = |lo: f64, hi: f64, unit: &str, note: &str| -> Result<f64, ErgonomicsError> {
            let refuse = |why: String| ErgonomicsError::Profile {
                given: value.to_string(),
                reason: format!("`{key}` {why}"),
            };
            let x: f64 = value
                .parse()
                .map_err(|_| refuse(format!("must be a number{unit}, not `{value}`")))?;
            if x.is_finite() && x >= lo && x <= hi {
                Ok(x)
            } else {
                Err(refuse(format!(
                    "must lie in [{lo}, {hi}]{unit}{note}, not {value}"
                )))
            }
        };
        let result = match key {
            "action" => parse_named(value).map(|a| self.action = a),
            "use" => match value.to_ascii_lowercase().as_str() {
                "professional" => {
                    self.percentile = tables.professional;
                    Ok(())
                }
                "domestic" => {
                    self.percentile = tables.domestic;
                    Ok(())
                }
                _ => Err(ErgonomicsError::Profile {
                    given: value.to_string(),
                    reason: "`use` must be professional or domestic".into(),
                }),
            },
            "percentile" => number(1.0, 50.0, "", " (the weaker half of the population)")
                .map(|x| self.percentile = x),
            "velocity" => parse_named(value).map(|v| self.velocity = v),
            "frequency_per_min" => number(0.0, tables.max_frequency(), " per minute", TABLE_END)
                .map(|x| self.frequency_per_min = x),
            "action_time_s" => {
                number(0.0, 86_400.0, " s", " (a day)").map(|x| self.action_time_s = x)
            }
            "duration_h" => {
                number(0.0, tables.max_duration(), " h", TABLE_END).map(|x| self.duration_h = x)
            }
            _ => return None,
        };
        Some(result)
    }

    /// Writes the parameters as `key=value` pairs [`Self::set`] reads back exactly.
    pub fn write(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "action={},percentile={},velocity={},frequency_per_min={},action_time_s={},duration_h={}",
            self.action,
            self.percentile,
            self.velocity,
            self.frequency_per_min,
            self.action_time_s,
            self.duration_h
        )
    }
}

/// The recommended force limit of one push or pull and how it was reached (clause 4.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct En1005Limit {
    /// Basic force capacity F_B of the Table 1 row \[N\].
    pub f_b: f64,
    /// F_B at the profile's percentile \[N\].
    pub f_br: f64,
    pub m_v: f64,
    pub m_f: f64,
    pub m_d: f64,
    /// F_R = F_Br · m_v · m_f · m_d \[N\].
    pub f_r: f64,
    /// Upper bounds of m_r of the recommended and not-recommended zones (0.5, 0.7).
    pub recommended_max: f64,
    pub not_recommended_max: f64,
}

impl En1005Limit {
    /// Upper end of the recommended zone, 0.5 F_R \[N\] (Pliant's guide value).
    pub fn recommended(&self) -> f64 {
        self.recommended_max * self.f_r
    }

    /// Upper end of the not-recommended zone, 0.7 F_R \[N\] (Pliant's limit value).
    pub fn limit(&self) -> f64 {
        self.not_recommended_max * self.f_r
    }

    /// The risk multiplier m_r = F / F_R and its zone for a force `force` \[N\].
    pub fn judge(&self, force: f64) -> En1005Judgement {
        let m_r = force / self.f_r;
        let zone = if m_r <= self.recommended_max {
            RiskZone::Recommended
        } else if m_r <= self.not_recommended_max {
            RiskZone::NotRecommended
        } else {
            RiskZone::ToBeAvoided
        };
        En1005Judgement {
            f_r: self.f_r,
            m_r,
            zone,
        }
    }
}

/// A force judged by EN 1005-3.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct En1005Judgement {
    /// Recommended force limit F_R \[N\].
    pub f_r: f64,
    /// Risk multiplier m_r = F / F_R.
    pub m_r: f64,
    pub zone: RiskZone,
}

/// One action's rows of Table 1.
#[derive(Clone, Debug, PartialEq)]
struct ActionRows {
    push: f64,
    pull: f64,
    describe: String,
}

/// The EN 1005-3 data, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct En1005Tables {
    /// Per [`En1005Action`], in `ALL` order.
    actions: Vec<ActionRows>,
    reference_percentile: f64,
    log_sd: f64,
    professional: f64,
    domestic: f64,
    velocity: [f64; 2],
    short_action_s: f64,
    /// (max actions per minute, m_f short, m_f long), increasing.
    frequency: Vec<(f64, f64, f64)>,
    /// (max hours, m_d), increasing.
    duration: Vec<(f64, f64)>,
    recommended_max: f64,
    not_recommended_max: f64,
    /// The `source` of every table, in file order.
    sources: Vec<(&'static str, String)>,
}

impl En1005Tables {
    /// The built-in data (parsed once).
    pub fn builtin() -> Result<&'static En1005Tables, ErgonomicsError> {
        static BUILTIN: std::sync::OnceLock<Result<En1005Tables, ErgonomicsError>> =
            std::sync::OnceLock::new();
        BUILTIN
            .get_or_init(|| En1005Tables::parse(EN1005_3_TOML))
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Reads a file in the format of `data/en1005_3.toml` and checks it: every action
    /// present with rows that exist, forces positive, multipliers in (0, 1], bands
    /// increasing, zone bounds 0 < recommended < not recommended.
    pub fn parse(text: &str) -> Result<En1005Tables, ErgonomicsError> {
        let bad = |what: String| ErgonomicsError::File(format!("en1005_3: {what}"));
        let raw: RawFile = toml::from_str(text).map_err(|e| bad(e.to_string()))?;
        let positive = |x: f64, at: &str| {
            if x.is_finite() && x > 0.0 {
                Ok(x)
            } else {
                Err(bad(format!("{at} = {x} must be finite and positive")))
            }
        };
        let multiplier = |x: f64, at: &str| {
            if x.is_finite() && x > 0.0 && x <= 1.0 {
                Ok(x)
            } else {
                Err(bad(format!("{at} = {x} must lie in (0, 1]")))
            }
        };
        if raw.basic_force.unit != "N" {
            return Err(bad(format!(
                "basic_force.unit must be \"N\", found \"{}\"",
                raw.basic_force.unit
            )));
        }
        let row = |name: &str| -> Result<f64, ErgonomicsError> {
            let v = raw
                .basic_force
                .rows
                .get(name)
                .ok_or_else(|| bad(format!("basic_force has no row `{name}`")))?;
            positive(*v, &format!("basic_force.{name}"))
        };
        let mut actions = Vec::new();
        for a in En1005Action::ALL {
            let r = raw
                .actions
                .get(a.name())
                .ok_or_else(|| bad(format!("actions.{} is missing", a.name())))?;
            actions.push(ActionRows {
                push: row(&r.push)?,
                pull: row(&r.pull)?,
                describe: r.describe.clone(),
            });
        }
        if let Some(extra) = raw
            .actions
            .keys()
            .find(|k| parse_named::<En1005Action>(k).is_err())
        {
            return Err(bad(format!(
                "actions.{extra} is not an action Pliant knows"
            )));
        }
        let pop = &raw.population;
        let percentile = |x: f64, at: &str| {
            if x.is_finite() && (1.0..=50.0).contains(&x) {
                Ok(x)
            } else {
                Err(bad(format!("population.{at} = {x} must lie in [1, 50]")))
            }
        };
        let increasing = |xs: &[f64], at: &str| {
            if xs.is_empty() || xs.windows(2).any(|w| w[1] <= w[0]) {
                Err(bad(format!("{at} bands must be given in increasing order")))
            } else {
                Ok(())
            }
        };
        let mut frequency = Vec::new();
        for (k, b) in raw.frequency.bands.iter().enumerate() {
            let at = format!("frequency.bands[{k}]");
            frequency.push((
                positive(b.max_per_min, &at)?,
                multiplier(b.short, &at)?,
                multiplier(b.long, &at)?,
            ));
        }
        increasing(
            &frequency.iter().map(|b| b.0).collect::<Vec<_>>(),
            "frequency",
        )?;
        let mut duration = Vec::new();
        for (k, b) in raw.duration.bands.iter().enumerate() {
            let at = format!("duration.bands[{k}]");
            duration.push((positive(b.max_h, &at)?, multiplier(b.m, &at)?));
        }
        increasing(
            &duration.iter().map(|b| b.0).collect::<Vec<_>>(),
            "duration",
        )?;
        let z = &raw.risk_zones;
        if !(z.recommended_max > 0.0 && z.recommended_max < z.not_recommended_max) {
            return Err(bad(format!(
                "risk_zones: need 0 < recommended_max ({}) < not_recommended_max ({})",
                z.recommended_max, z.not_recommended_max
            )));
        }
        let sources = vec![
            ("basic_force", raw.basic_force.source),
            ("population", raw.population.source.clone()),
            ("velocity", raw.velocity.source),
            ("frequency", raw.frequency.source),
            ("duration", raw.duration.source),
            ("risk_zones", raw.risk_zones.source.clone()),
        ];
        if let Some((key, _)) = sources.iter().find(|(_, s)| s.trim().is_empty()) {
            return Err(bad(format!("{key}: `source` must not be empty")));
        }
        Ok(En1005Tables {
            actions,
            reference_percentile: percentile(pop.reference_percentile, "reference_percentile")?,
            log_sd: positive(pop.log_sd, "population.log_sd")?,
            professional: percentile(pop.professional, "professional")?,
            domestic: percentile(pop.domestic, "domestic")?,
            velocity: [
                multiplier(raw.velocity.low, "velocity.low")?,
                multiplier(raw.velocity.high, "velocity.high")?,
            ],
            short_action_s: positive(raw.frequency.short_action_s, "frequency.short_action_s")?,
            frequency,
            duration,
            recommended_max: z.recommended_max,
            not_recommended_max: z.not_recommended_max,
            sources,
        })
    }

    /// The highest frequency the table covers [actions per minute].
    pub fn max_frequency(&self) -> f64 {
        self.frequency.last().map_or(0.0, |b| b.0)
    }

    /// The longest daily duration the table covers \[h\].
    pub fn max_duration(&self) -> f64 {
        self.duration.last().map_or(0.0, |b| b.0)
    }

    /// Where each table comes from: (key, source), in file order.
    pub fn sources(&self) -> impl Iterator<Item = (&'static str, &str)> {
        self.sources.iter().map(|(k, s)| (*k, s.as_str()))
    }

    /// The action's words, e.g. "whole body work, standing".
    pub fn describe(&self, action: En1005Action) -> &str {
        &self.actions[action.index()].describe
    }

    /// F_B of the action's push (`push = true`) or pull row \[N\].
    pub fn basic_force(&self, action: En1005Action, push: bool) -> f64 {
        let rows = &self.actions[action.index()];
        if push {
            rows.push
        } else {
            rows.pull
        }
    }

    /// The recommended force limit of a push or pull under `params` (module doc). The
    /// parameters are assumed checked ([`En1005Params::set`]); a frequency or duration
    /// beyond the tables takes their last band.
    pub fn limit(&self, params: &En1005Params, push: bool) -> En1005Limit {
        let f_b = self.basic_force(params.action, push);
        let z = |p: f64| normal_quantile(p / 100.0);
        let f_br =
            f_b * ((z(params.percentile) - z(self.reference_percentile)) * self.log_sd).exp();
        let m_v = self.velocity[params.velocity.index()];
        let short = params.action_time_s <= self.short_action_s;
        let band = self
            .frequency
            .iter()
            .find(|b| params.frequency_per_min <= b.0)
            .or(self.frequency.last());
        let m_f = band.map_or(1.0, |b| if short { b.1 } else { b.2 });
        let m_d = self
            .duration
            .iter()
            .find(|b| params.duration_h <= b.0)
            .or(self.duration.last())
            .map_or(1.0, |b| b.1);
        En1005Limit {
            f_b,
            f_br,
            m_v,
            m_f,
            m_d,
            f_r: f_br * m_v * m_f * m_d,
            recommended_max: self.recommended_max,
            not_recommended_max: self.not_recommended_max,
        }
    }
}

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    basic_force: RawBasic,
    actions: BTreeMap<String, RawAction>,
    population: RawPopulation,
    velocity: RawVelocity,
    frequency: RawFrequency,
    duration: RawDuration,
    risk_zones: RawZones,
}

#[derive(Deserialize)]
struct RawBasic {
    source: String,
    unit: String,
    #[serde(flatten)]
    rows: BTreeMap<String, f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAction {
    push: String,
    pull: String,
    describe: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPopulation {
    source: String,
    reference_percentile: f64,
    log_sd: f64,
    professional: f64,
    domestic: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawVelocity {
    source: String,
    low: f64,
    high: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFrequency {
    source: String,
    short_action_s: f64,
    bands: Vec<RawFrequencyBand>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFrequencyBand {
    max_per_min: f64,
    short: f64,
    long: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDuration {
    source: String,
    bands: Vec<RawDurationBand>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDurationBand {
    max_h: f64,
    m: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawZones {
    source: String,
    recommended_max: f64,
    not_recommended_max: f64,
}
