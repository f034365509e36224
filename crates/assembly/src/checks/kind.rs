//! The installation checks (SPEC V3; cf. DIN 20066 for hose lines and the bend-radius
//! checks of CAD routing tools) and what one violation records.

use serde::Serialize;

/// One installation rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CheckKind {
    /// Bend radius 1/κ at least the material's minimum, everywhere and at all times.
    BendRadius,
    /// Twist rate relative to the routed, unloaded hose at most the limit [rad/m].
    Twist,
    /// No axial tension once assembled: the axial strain at the end of the study at most
    /// the limit (reported as the axial force against the force at that strain).
    TensionAtRest,
    /// A straight length behind each stub: over that length from the hose end on the
    /// stub the bend radius is at least the straightness radius.
    StraightBehindStub,
}

impl CheckKind {
    /// Every check, in report order.
    pub const ALL: [CheckKind; 4] = [
        CheckKind::BendRadius,
        CheckKind::Twist,
        CheckKind::TensionAtRest,
        CheckKind::StraightBehindStub,
    ];

    /// The name used in `[checks]`, `checks.csv` and the reports.
    pub fn name(self) -> &'static str {
        match self {
            CheckKind::BendRadius => "bend_radius",
            CheckKind::Twist => "twist",
            CheckKind::TensionAtRest => "tension_at_rest",
            CheckKind::StraightBehindStub => "straight_behind_stub",
        }
    }

    /// The unit of its values as reported (SI; the reports convert nothing).
    pub fn unit(self) -> &'static str {
        match self {
            CheckKind::BendRadius | CheckKind::StraightBehindStub => "m",
            CheckKind::Twist => "rad/m",
            CheckKind::TensionAtRest => "N",
        }
    }

    /// Whether a value below the limit is the violation (radii) rather than above it.
    pub fn lower_bound(self) -> bool {
        matches!(self, CheckKind::BendRadius | CheckKind::StraightBehindStub)
    }

    /// Whether the check judges the assembled state (end of the study) only.
    pub fn at_end_only(self) -> bool {
        matches!(
            self,
            CheckKind::TensionAtRest | CheckKind::StraightBehindStub
        )
    }
}

/// The worst violation of one check on one hose, and when it was violated.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Violation {
    pub check: CheckKind,
    pub hose: usize,
    pub hose_name: String,
    /// Arc length from the hose's first node (rest length) of the worst place \[m\].
    pub arc_length: f64,
    /// Time of the worst value \[s\].
    pub time: f64,
    /// The worst value and the limit it broke ([`CheckKind::unit`]).
    pub value: f64,
    pub limit: f64,
    /// First and last checked instant the check was violated anywhere on the hose \[s\].
    pub first_time: f64,
    pub last_time: f64,
    /// Checked instants at which it was violated.
    pub instants: u64,
    /// For stubs: the stub's name.
    pub at: Option<String>,
}

impl Violation {
    /// One line for the verdict.
    pub fn describe(&self) -> String {
        let place = match &self.at {
            Some(stub) => format!(" behind stub '{stub}'"),
            None => String::new(),
        };
        let (value, limit) = match self.check {
            CheckKind::BendRadius => (
                format!("bend radius {:.0} mm", 1e3 * self.value),
                format!("the minimum {:.0} mm", 1e3 * self.limit),
            ),
            CheckKind::StraightBehindStub => (
                format!("bend radius {:.0} mm", 1e3 * self.value),
                format!("the {:.0} mm that count as straight", 1e3 * self.limit),
            ),
            CheckKind::Twist => (
                format!("twist {:.1} °/m", self.value.to_degrees()),
                format!("the limit {:.1} °/m", self.limit.to_degrees()),
            ),
            CheckKind::TensionAtRest => (
                format!("axial tension {:.1} N", self.value),
                format!("the limit {:.1} N", self.limit),
            ),
        };
        let when = if self.check.at_end_only() {
            format!("at the end (t = {:.2} s)", self.time)
        } else {
            format!(
                "at t = {:.2} s (violated from {:.2} s to {:.2} s)",
                self.time, self.first_time, self.last_time
            )
        };
        format!(
            "hose '{}'{place}: {} check — {value} at s = {:.0} mm {when} breaks {limit}",
            self.hose_name,
            self.check.name(),
            1e3 * self.arc_length,
        )
    }
}
