//! Anthropometry: a worker's body dimensions from the cited table
//! `data/anthropometry.toml` — ANSUR II stature per sex and percentile (Gordon et al.
//! 2014), segment proportions of stature after Winter (2009, fig. 4.1) / Drillis &
//! Contini (1966), capsule radii (the author's estimates) and joint limits (AAOS 1965).
//! The file's header says where every number comes from; everything here is SI (metres,
//! radians).

use crate::error::WorkerError;
use crate::quantile::normal_quantile;
use serde::Deserialize;
use std::sync::OnceLock;

/// The built-in table's text.
pub const DATA: &str = include_str!("../data/anthropometry.toml");

/// Which sex's statistics size the worker.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sex {
    Female,
    Male,
}

impl Sex {
    /// Reads `female`/`woman`/`women` or `male`/`man`/`men` (case-insensitive).
    pub fn parse(field: &str, text: &str) -> Result<Sex, WorkerError> {
        match text.trim().to_ascii_lowercase().as_str() {
            "female" | "woman" | "women" | "f" => Ok(Sex::Female),
            "male" | "man" | "men" | "m" => Ok(Sex::Male),
            _ => Err(WorkerError::field(
                field,
                format!("\"{text}\""),
                "expected \"female\" or \"male\"",
            )),
        }
    }

    /// "woman" or "man", for the verdict's words.
    pub fn noun(self) -> &'static str {
        match self {
            Sex::Female => "woman",
            Sex::Male => "man",
        }
    }
}

/// Who the worker is: a sex and a percentile of its stature.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Population {
    pub sex: Sex,
    /// Percentile of stature, in [1, 99].
    pub percentile: f64,
}

impl Population {
    /// Checks the percentile (in [1, 99]; the normal model is not trusted further out).
    pub fn new(sex: Sex, percentile: f64) -> Result<Population, WorkerError> {
        if !(1.0..=99.0).contains(&percentile) {
            return Err(WorkerError::field(
                "percentile",
                percentile,
                "must be a percentile in [1, 99]",
            ));
        }
        Ok(Population { sex, percentile })
    }

    /// Reads "female 5", "male 95", "woman 50" (sex, then percentile).
    pub fn parse(field: &str, text: &str) -> Result<Population, WorkerError> {
        let mut words = text.split_whitespace();
        let (Some(sex), Some(p), None) = (words.next(), words.next(), words.next()) else {
            return Err(WorkerError::field(
                field,
                format!("\"{text}\""),
                "expected a sex and a percentile, e.g. \"female 5\" or \"male 95\"",
            ));
        };
        let sex = Sex::parse(field, sex)?;
        let percentile: f64 = p.trim_end_matches("th").parse().map_err(|_| {
            WorkerError::field(
                field,
                format!("\"{text}\""),
                "the percentile is not a number",
            )
        })?;
        Population::new(sex, percentile).map_err(|e| match e {
            WorkerError::Field { reason, .. } => {
                WorkerError::field(field, format!("\"{text}\""), reason)
            }
            e => e,
        })
    }

    /// "the 5th-percentile woman".
    pub fn describe(&self) -> String {
        let p = self.percentile;
        let n = if p.fract() == 0.0 {
            format!("{p:.0}")
        } else {
            format!("{p}")
        };
        let suffix = match (p.fract() == 0.0, p as u64 % 100) {
            (true, 11..=13) => "th",
            (true, x) if x % 10 == 1 => "st",
            (true, x) if x % 10 == 2 => "nd",
            (true, x) if x % 10 == 3 => "rd",
            _ => "th",
        };
        format!("the {n}{suffix}-percentile {}", self.sex.noun())
    }
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    stature: MeasureTable,
    popliteal_height: MeasureTable,
    proportions: Dimensions,
    radii: SegmentRadii,
    joint_limits: JointLimits,
}

/// A measure's mean and standard deviation per sex \[m\] (stature, popliteal height).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MeasureTable {
    female_mean: f64,
    female_sd: f64,
    male_mean: f64,
    male_sd: f64,
}

/// A body's heights, widths and segment lengths \[m\] (in the data table: fractions of
/// stature after Winter 2009, fig. 4.1; [`Dimensions::scaled`]).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Dimensions {
    /// Heights above the floor: shoulder joint, hip joint, knee, ankle, chin, eyes.
    pub shoulder_height: f64,
    pub hip_height: f64,
    pub knee_height: f64,
    pub ankle_height: f64,
    pub chin_height: f64,
    pub eye_height: f64,
    /// Between the shoulder joints and between the hip joints.
    pub shoulder_width: f64,
    pub hip_width: f64,
    /// Shoulder–elbow, elbow–wrist, wrist–fingertip.
    pub upper_arm: f64,
    pub forearm: f64,
    pub hand: f64,
}

/// Joint limits \[rad\] (AAOS 1965 average ranges of motion), each a positive range from
/// the neutral standing posture. The data table gives them in degrees
/// ([`JointLimits::to_radians`]).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct JointLimits {
    pub trunk_flexion: f64,
    pub trunk_extension: f64,
    pub trunk_lateral: f64,
    pub trunk_twist: f64,
    pub neck_flexion: f64,
    pub neck_extension: f64,
    pub neck_lateral: f64,
    pub neck_twist: f64,
    pub shoulder_flexion: f64,
    pub shoulder_extension: f64,
    pub shoulder_abduction: f64,
    pub shoulder_adduction: f64,
    pub elbow_flexion: f64,
}

/// A worker's body: stature, segment lengths and radii \[m\], joint limits \[rad\].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Body {
    pub population: Population,
    /// Stature H \[m\].
    pub stature: f64,
    /// Popliteal height \[m\]: floor to the underside of the thigh behind the knee,
    /// seated with the knees at 90° (ANSUR II, the same percentile; the default seat
    /// height, [`crate::seat::Seat`]).
    pub popliteal_height: f64,
    /// Heights, widths and segment lengths \[m\].
    #[serde(flatten)]
    pub dims: Dimensions,
    /// Capsule radii \[m\].
    pub radii: SegmentRadii,
    pub limits: JointLimits,
}

/// Capsule radii \[m\] of a body (in the data table: fractions of stature, the author's
/// estimates, not data; [`SegmentRadii::scaled`]).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentRadii {
    pub head: f64,
    pub neck: f64,
    pub trunk: f64,
    pub pelvis: f64,
    pub upper_arm: f64,
    pub forearm: f64,
    pub hand: f64,
    pub thigh: f64,
    pub shank: f64,
}

impl JointLimits {
    /// Every limit converted from degrees to radians.
    pub fn to_radians(self) -> JointLimits {
        let r = f64::to_radians;
        JointLimits {
            trunk_flexion: r(self.trunk_flexion),
            trunk_extension: r(self.trunk_extension),
            trunk_lateral: r(self.trunk_lateral),
            trunk_twist: r(self.trunk_twist),
            neck_flexion: r(self.neck_flexion),
            neck_extension: r(self.neck_extension),
            neck_lateral: r(self.neck_lateral),
            neck_twist: r(self.neck_twist),
            shoulder_flexion: r(self.shoulder_flexion),
            shoulder_extension: r(self.shoulder_extension),
            shoulder_abduction: r(self.shoulder_abduction),
            shoulder_adduction: r(self.shoulder_adduction),
            elbow_flexion: r(self.elbow_flexion),
        }
    }
}

impl Dimensions {
    /// Every dimension times `h` (fractions of stature to metres).
    pub fn scaled(self, h: f64) -> Dimensions {
        Dimensions {
            shoulder_height: self.shoulder_height * h,
            hip_height: self.hip_height * h,
            knee_height: self.knee_height * h,
            ankle_height: self.ankle_height * h,
            chin_height: self.chin_height * h,
            eye_height: self.eye_height * h,
            shoulder_width: self.shoulder_width * h,
            hip_width: self.hip_width * h,
            upper_arm: self.upper_arm * h,
            forearm: self.forearm * h,
            hand: self.hand * h,
        }
    }
}

impl SegmentRadii {
    /// Every radius times `h` (fractions of stature to metres).
    pub fn scaled(self, h: f64) -> SegmentRadii {
        SegmentRadii {
            head: self.head * h,
            neck: self.neck * h,
            trunk: self.trunk * h,
            pelvis: self.pelvis * h,
            upper_arm: self.upper_arm * h,
            forearm: self.forearm * h,
            hand: self.hand * h,
            thigh: self.thigh * h,
            shank: self.shank * h,
        }
    }
}

impl Body {
    /// The grip centre's distance from the wrist \[m\]: half the hand length (a power
    /// grip closes the fingers round a hose at about mid-hand).
    pub fn grip_offset(&self) -> f64 {
        0.5 * self.dims.hand
    }

    /// Shoulder to grip centre with the arm straight \[m\].
    pub fn arm_reach(&self) -> f64 {
        self.dims.upper_arm + self.dims.forearm + self.grip_offset()
    }
}

fn table() -> Result<&'static Table, WorkerError> {
    static TABLE: OnceLock<Result<Table, String>> = OnceLock::new();
    TABLE
        .get_or_init(|| toml::from_str::<Table>(DATA).map_err(|e| e.to_string()))
        .as_ref()
        .map_err(|e| WorkerError::Data(e.clone()))
}

/// Stature \[m\] of `population`: ANSUR II mean + z(p) · sd of its sex.
pub fn stature(population: Population) -> Result<f64, WorkerError> {
    Ok(percentile_of(&table()?.stature, population))
}

/// Popliteal height \[m\] of `population`: ANSUR II mean + z(p) · sd of its sex.
pub fn popliteal_height(population: Population) -> Result<f64, WorkerError> {
    Ok(percentile_of(&table()?.popliteal_height, population))
}

/// The percentile of `population` of measure `t`: mean + z(p) · sd of its sex.
fn percentile_of(t: &MeasureTable, population: Population) -> f64 {
    let (mean, sd) = match population.sex {
        Sex::Female => (t.female_mean, t.female_sd),
        Sex::Male => (t.male_mean, t.male_sd),
    };
    mean + normal_quantile(population.percentile / 100.0) * sd
}

/// The body of `population`: the table's proportions and radii scaled to its stature.
pub fn body(population: Population) -> Result<Body, WorkerError> {
    let t = table()?;
    let h = stature(population)?;
    Ok(Body {
        population,
        stature: h,
        popliteal_height: popliteal_height(population)?,
        dims: t.proportions.scaled(h),
        radii: t.radii.scaled(h),
        limits: t.joint_limits.to_radians(),
    })
}
