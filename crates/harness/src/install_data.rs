//! The data of the installation `install.toml` describes (`data/installation.toml`): the
//! force–travel curve a plugged connector gets and the bundle's assembly slack. KBL carries
//! neither; the connectors' peak force comes from a manufacturer's product specification by
//! the housing's number of positions, the curve's shape and the slack are assumptions (see
//! the data file: every value with its source).

use serde::Deserialize;

/// A value with the source it comes from (or "assumption: …").
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Sourced<T> {
    pub value: T,
    pub source: String,
}

/// One row of the peak table: connectors of up to `max_positions` positions.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct PeakRow {
    pub max_positions: usize,
    pub force_n: Sourced<f64>,
}

/// The latch's hold.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Retention {
    pub force_n: Sourced<f64>,
}

/// The curve's shape.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Shape {
    pub travel_mm: Sourced<f64>,
    pub latch_at_mm: Sourced<f64>,
    /// (travel mm, share of the peak).
    pub points: Sourced<Vec<[f64; 2]>>,
}

/// The assembly slack.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct Slack {
    /// Share of a segment's length it is made longer than its route.
    pub share: Sourced<f64>,
}

/// The data of `data/installation.toml`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct InstallData {
    pub slack: Slack,
    pub peak: Vec<PeakRow>,
    pub retention: Retention,
    pub shape: Shape,
}

/// The built-in data file.
pub const INSTALLATION_TOML: &str = include_str!("../data/installation.toml");

/// One connector's mating law as `install.toml` writes it.
#[derive(Clone, Debug, PartialEq)]
pub struct MatingLaw {
    /// (travel \[mm\], force \[N\]).
    pub curve: Vec<(f64, f64)>,
    pub peak_n: f64,
    pub travel_mm: f64,
    pub latch_at_mm: f64,
    pub retention_n: f64,
    /// Where the peak comes from.
    pub source: String,
}

impl InstallData {
    /// The built-in data (checked by a unit test, so this cannot fail at run time).
    pub fn builtin() -> Self {
        Self::from_toml(INSTALLATION_TOML)
            .unwrap_or_else(|e| panic!("data/installation.toml is invalid: {e}"))
    }

    /// Data from TOML text, checked: a slack within [0, 10 %], peak rows in increasing `max_positions` with positive
    /// forces, a travel and latch with 0 < latch ≤ travel, shape points in strictly
    /// increasing travel within [0, travel] with shares ≥ 0, a positive retention.
    pub fn from_toml(text: &str) -> Result<Self, String> {
        let d: InstallData = toml::from_str(text).map_err(|e| e.to_string())?;
        let slack = d.slack.share.value;
        if !(slack.is_finite() && (0.0..=0.1).contains(&slack)) {
            return Err("slack.share must lie within [0, 0.1]".into());
        }
        if d.peak.is_empty() {
            return Err("`peak` needs at least one row".into());
        }
        for (k, row) in d.peak.iter().enumerate() {
            if !(row.force_n.value.is_finite() && row.force_n.value > 0.0) {
                return Err(format!("peak[{k}].force_n must be a positive number"));
            }
            if k > 0 && row.max_positions <= d.peak[k - 1].max_positions {
                return Err(format!(
                    "peak[{k}].max_positions must be larger than the row before"
                ));
            }
        }
        let (travel, latch) = (d.shape.travel_mm.value, d.shape.latch_at_mm.value);
        if !(travel.is_finite() && travel > 0.0 && latch > 0.0 && latch <= travel) {
            return Err("shape: needs 0 < latch_at_mm <= travel_mm".into());
        }
        let pts = &d.shape.points.value;
        if pts.is_empty() || pts.len() > 16 {
            return Err("shape.points needs 1 to 16 points".into());
        }
        for (k, p) in pts.iter().enumerate() {
            if !(p[0].is_finite() && (0.0..=travel).contains(&p[0])) {
                return Err(format!(
                    "shape.points[{k}]: travel must lie within [0, travel_mm]"
                ));
            }
            if k > 0 && p[0] <= pts[k - 1][0] {
                return Err(format!("shape.points[{k}]: travel must increase strictly"));
            }
            if !(p[1].is_finite() && p[1] >= 0.0) {
                return Err(format!("shape.points[{k}]: the share must be >= 0"));
            }
        }
        let r = d.retention.force_n.value;
        if !(r.is_finite() && r > 0.0) {
            return Err("retention.force_n must be a positive number".into());
        }
        Ok(d)
    }

    /// The law of a connector with `positions` positions (0: not known — the table's
    /// largest peak, the worst case).
    pub fn law(&self, positions: usize) -> MatingLaw {
        let row = if positions == 0 {
            self.peak
                .iter()
                .max_by(|a, b| a.force_n.value.total_cmp(&b.force_n.value))
        } else {
            self.peak
                .iter()
                .find(|r| r.max_positions >= positions)
                .or(self.peak.last())
        }
        .expect("checked: at least one row");
        let peak = row.force_n.value;
        MatingLaw {
            curve: self
                .shape
                .points
                .value
                .iter()
                .map(|p| (p[0], p[1] * peak))
                .collect(),
            peak_n: peak,
            travel_mm: self.shape.travel_mm.value,
            latch_at_mm: self.shape.latch_at_mm.value,
            retention_n: self.retention.force_n.value,
            source: row.force_n.source.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_data_loads_with_sources() {
        let d = InstallData::builtin();
        assert_eq!(d.peak.len(), 3);
        assert!(d.peak[0].force_n.source.contains("108-15299"));
        assert!(d.retention.force_n.source.contains("160 N"));
        assert!(d.shape.points.source.starts_with("assumption"));
        assert_eq!(d.slack.share.value, 0.01);
        assert!(d.slack.share.source.contains("IPC/WHMA-A-620C"));
    }

    #[test]
    fn the_peak_follows_the_positions() {
        let d = InstallData::builtin();
        let peak = |n| d.law(n).curve.iter().map(|p| p.1).fold(0.0, f64::max);
        assert_eq!(peak(4), 60.0);
        assert_eq!(peak(24), 60.0);
        assert_eq!(peak(25), 70.0);
        assert_eq!(peak(90), 70.0);
        assert_eq!(peak(0), 70.0);
        let law = d.law(3);
        assert_eq!(law.curve.len(), 5);
        assert_eq!(law.latch_at_mm, 6.5);
        assert_eq!(law.retention_n, 160.0);
    }

    #[test]
    fn bad_data_is_refused_with_the_field() {
        let bad =
            INSTALLATION_TOML.replace("latch_at_mm = { value = 6.5", "latch_at_mm = { value = 9.5");
        assert!(InstallData::from_toml(&bad)
            .unwrap_err()
            .contains("latch_at_mm"));
        let bad = INSTALLATION_TOML.replace("max_positions = 40", "max_positions = 20");
        assert!(InstallData::from_toml(&bad)
            .unwrap_err()
            .contains("peak[1]"));
        let bad = INSTALLATION_TOML.replace("share = { value = 0.01", "share = { value = 0.5");
        assert!(InstallData::from_toml(&bad).unwrap_err().contains("slack"));
    }
}
