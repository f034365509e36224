//! One line of a verdict as a typed value (SPEC I5): why a study is feasible or not, what
//! it warns of, what is still to do. [`super::Verdict::judge`] decides by building these;
//! `Display` words them — the text `pliant run` prints, `report.json`, the live
//! protocol and Python carry beside the values.

use super::solver_doubt::{InstabilityNote, SolverDoubt};
use super::tally::ZoneNote;
use super::verdict::Stage;
use crate::checks::Violation;
use crate::ergonomics::{table_posture, LoadKind, RiskZone, Standard};
use crate::fastener_state::{FastenerKind, FastenerState};
use crate::sweep::{ClearanceViolation, MotionExtremes};
use crate::worker::{PostureNote, StepNote, WorkerFinding};
use pliant_worker::PostureClass;
use serde::Serialize;
use std::fmt;

/// The fastener a hand worked at its worst moment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkedFastener {
    pub fastener: FastenerKind,
    pub name: String,
}

/// A hand's load against its limit value \[N or N·m\]: `ratio` = `value` / `limit`, at
/// `time` \[s\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LoadAgainstLimit {
    pub hand: usize,
    pub load: LoadKind,
    pub value: f64,
    pub limit: f64,
    pub ratio: f64,
    pub time: f64,
    /// The worker's posture class whose rows gave the limit (SPEC E2), if a worker was
    /// posed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub posture_class: Option<PostureClass>,
}

/// One line of a verdict: a reason, a warning, a fastener still to fit, a hand's EN 1005-3
/// zone or a line on the worker. Serialised with its `kind` ("hand_load_over_limit", …);
/// an optional member that is empty is left out.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Reason {
    /// The solver's doubt about the numbers: they are uncertain (first among the
    /// reasons).
    Solver(SolverDoubt),
    /// The simulation stopped early (a divergence, or a replay that refused an input).
    StoppedEarly { message: String },
    /// A hand's peak push or pull judged by EN 1005-3: its risk zone and how its
    /// recommended limit came about (a reason beyond the limit, a warning in the
    /// not-recommended zone, and the verdict's `zones`).
    HandForceZone {
        hand: usize,
        zone: ZoneNote,
        #[serde(skip_serializing_if = "Option::is_none")]
        working: Option<WorkedFastener>,
    },
    /// A hand's push, pull (or, when moments decide, twist or bending) over its limit
    /// value (dissertation tables 3.7, 3.9, 3.11).
    HandLoadOverLimit {
        #[serde(flatten)]
        load: LoadAgainstLimit,
        #[serde(skip_serializing_if = "Option::is_none")]
        working: Option<WorkedFastener>,
    },
    /// A hand's twist or bending moment above the upper end of its guide range
    /// (`guide_hi`) or its limit \[N·m\]; guidance only unless `moments_decide`.
    MomentAboveGuide {
        hand: usize,
        load: LoadKind,
        value: f64,
        time: f64,
        guide_hi: f64,
        limit: f64,
        moments_decide: bool,
    },
    /// At the end of the study a fastener was not in its assembled state.
    FastenerNotFitted {
        fastener: FastenerKind,
        name: String,
        final_state: FastenerState,
    },
    /// While the study runs: a fastener not yet in its assembled state.
    FastenerPending {
        fastener: FastenerKind,
        name: String,
        state: FastenerState,
    },
    /// An installation check violated (SPEC V3), with the motion's position then in a
    /// range-of-motion study.
    CheckViolated {
        violation: Violation,
        #[serde(skip_serializing_if = "Option::is_none")]
        position: Option<String>,
    },
    /// A hose came nearer to a part than the smallest clearance allowed (range of motion).
    ClearanceViolated(ClearanceViolation),
    /// What the worker could not do: out of reach, a body collision (SPEC E1).
    Worker { finding: WorkerFinding },
    /// The worker's worst posture scores (SPEC E2).
    Posture(PostureNote),
    /// A worker in the scene never posed: no hand acted.
    NotPosed { who: String },
    /// A step the worker took (to reach, or with a VR user).
    Step(StepNote),
    /// How many more steps the worker took than are listed.
    MoreSteps { count: u64 },
    /// Over a range of motion: each hose's smallest bend radius and the smallest
    /// clearance with where they were.
    MotionExtremes(MotionExtremes),
    /// The hoses touched a part over this time span \[s\].
    Contact {
        part: String,
        first_time: f64,
        last_time: f64,
    },
    /// An instability met, or implicit steps taken explicitly: information.
    Instability(InstabilityNote),
    /// Feasible: every hand load within its limit value under `standard`, every
    /// fastener fitted, the installation checks that ran (`checks`) passed, and the
    /// worker (`reached`: who) reached every target without a body collision.
    WithinLimits {
        standard: Standard,
        checks: Vec<&'static str>,
        #[serde(skip_serializing_if = "Option::is_none")]
        reached: Option<String>,
    },
    /// Feasible so far: every hand load within its limit value; the worst of them.
    WithinLimitsSoFar {
        #[serde(skip_serializing_if = "Option::is_none")]
        worst: Option<LoadAgainstLimit>,
    },
    /// A range-of-motion study with no hand: every check passed (and, at the end, every
    /// fastener was fitted).
    ChecksPassed { stage: Stage },
    /// Nothing to judge: no hand acted.
    NoHandActed { stage: Stage },
}

/// The name of a load in the verdict's words.
fn load_name(kind: LoadKind) -> &'static str {
    match kind {
        LoadKind::Bending => "bending moment",
        k => k.name(),
    }
}

/// The row of the tables a load is judged against.
/// The table row a posture class judges a push or pull by: ", crouching row".
fn row_of(class: PostureClass, kind: LoadKind) -> String {
    let posture = table_posture(class);
    let row = match kind {
        LoadKind::Pull => posture.pull().to_string(),
        _ => posture.push().to_string(),
    };
    format!(", {} row", row.replace('_', " "))
}

fn table(kind: LoadKind) -> &'static str {
    match kind {
        LoadKind::Push => "table 3.7",
        LoadKind::Pull => "table 3.9",
        LoadKind::Twist => "screwdriver, table 3.11",
        LoadKind::Bending => "T-handle, table 3.11",
    }
}

impl fmt::Display for WorkedFastener {
    /// What the hand was doing: " — pressing the hose end onto stub 'a'".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = &self.name;
        match self.fastener {
            FastenerKind::Stub => write!(f, " — pressing the hose end onto stub '{name}'"),
            FastenerKind::Connector => write!(f, " — plugging connector '{name}'"),
            kind => write!(f, " — pressing the hose into {kind} '{name}'"),
        }
    }
}

/// " — pressing …" or nothing.
struct Working<'a>(&'a Option<WorkedFastener>);

impl fmt::Display for Working<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(w) => w.fmt(f),
            None => Ok(()),
        }
    }
}

/// A peak push or pull against EN 1005-3: value, zone, m_r and how F_R came about.
fn write_zone(f: &mut fmt::Formatter<'_>, hand: usize, z: &ZoneNote) -> fmt::Result {
    let (l, j) = (&z.limit, &z.judgement);
    write!(
        f,
        "hand {hand}: {} of {:.1} N at t = {:.2} s is {} (",
        load_name(z.kind),
        z.magnitude,
        z.time,
        j.zone.words().to_uppercase(),
    )?;
    match j.zone {
        RiskZone::Recommended => write!(f, "m_r = F/F_R = {:.2} ≤ {}", j.m_r, l.recommended_max),
        RiskZone::NotRecommended => write!(
            f,
            "{} < m_r = F/F_R = {:.2} ≤ {}",
            l.recommended_max, j.m_r, l.not_recommended_max
        ),
        RiskZone::ToBeAvoided => {
            write!(f, "m_r = F/F_R = {:.2} > {}", j.m_r, l.not_recommended_max)
        }
    }?;
    write!(
        f,
        "; EN 1005-3, {}: F_R = {:.1} N = F_Br {:.1} N · m_v {} · m_f {} · m_d {}, F_B = {:.0} N)",
        z.action, l.f_r, l.f_br, l.m_v, l.m_f, l.m_d, l.f_b,
    )
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Reason::Solver(doubt) => doubt.fmt(f),
            Reason::StoppedEarly { message } => {
                write!(f, "the simulation stopped early: {message}")
            }
            Reason::HandForceZone {
                hand,
                zone,
                working,
            } => {
                write_zone(f, *hand, zone)?;
                Working(working).fmt(f)
            }
            Reason::HandLoadOverLimit { load: l, working } => {
                let (allowed, row) = match l.posture_class {
                    Some(class) => (format!(" allowed for {class}"), row_of(class, l.load)),
                    None => (String::new(), String::new()),
                };
                write!(
                    f,
                    "hand {}: {} of {:.1} {u} at t = {:.2} s exceeds the limit {:.1} {u}{allowed} ({}{row}; {:.0} % of it){}",
                    l.hand,
                    load_name(l.load),
                    l.value,
                    l.time,
                    l.limit,
                    table(l.load),
                    100.0 * l.ratio,
                    Working(working),
                    u = l.load.unit(),
                )
            }
            Reason::MomentAboveGuide {
                hand,
                load,
                value,
                time,
                guide_hi,
                limit,
                moments_decide,
            } => {
                write!(
                    f,
                    "hand {hand}: {} of {value:.2} N·m at t = {time:.2} s is ",
                    load_name(*load)
                )?;
                if value > limit {
                    write!(f, "above the limit {limit:.2} N·m")?;
                } else {
                    write!(
                        f,
                        "above the guide range (up to {guide_hi:.2} N·m; limit {limit:.2} N·m)"
                    )?;
                }
                write!(f, " ({})", table(*load))?;
                if value > limit && !moments_decide {
                    f.write_str(" — guidance only: the dissertation (3.3.3) never fails an installation for twist or bending")?;
                }
                Ok(())
            }
            Reason::FastenerNotFitted {
                fastener,
                name,
                final_state,
            } => {
                let wanted = match fastener {
                    FastenerKind::Stub => "fixed on it",
                    FastenerKind::Connector => "plugged and latched",
                    FastenerKind::Clip => "seated in it",
                };
                write!(
                    f,
                    "{fastener} '{name}': the hose did not end {wanted} (final state: {final_state})"
                )
            }
            Reason::FastenerPending {
                fastener,
                name,
                state,
            } => write!(f, "{fastener} '{name}' not yet fitted (state: {state})"),
            Reason::CheckViolated {
                violation,
                position,
            } => {
                f.write_str(&violation.describe())?;
                match position {
                    Some(at) => write!(f, ", at {at}"),
                    None => Ok(()),
                }
            }
            Reason::ClearanceViolated(c) => c.fmt(f),
            Reason::Worker { finding } => f.write_str(&finding.describe()),
            Reason::Posture(note) => note.fmt(f),
            Reason::NotPosed { who } => write!(f, "{who}: not posed (no hand acted)"),
            Reason::Step(note) => note.fmt(f),
            Reason::MoreSteps { count } => write!(f, "and {count} more steps"),
            Reason::MotionExtremes(extremes) => extremes.fmt(f),
            Reason::Contact {
                part,
                first_time,
                last_time,
            } => write!(
                f,
                "contact with '{part}' from t = {first_time:.2} s to {last_time:.2} s"
            ),
            Reason::Instability(note) => note.fmt(f),
            Reason::WithinLimits {
                standard,
                checks,
                reached,
            } => {
                write!(
                    f,
                    "every hand load stayed within its ergonomic limit value ({}), every stub, connector and clip was fitted",
                    standard.title()
                )?;
                if !checks.is_empty() {
                    write!(
                        f,
                        ", and the installation checks ({}) passed",
                        checks.join(", ")
                    )?;
                }
                match reached {
                    Some(who) => write!(
                        f,
                        ", and {who} reached every hand target without a body collision"
                    ),
                    None => Ok(()),
                }
            }
            Reason::WithinLimitsSoFar { worst } => {
                f.write_str("every hand load so far is within its ergonomic limit value")?;
                match worst {
                    Some(w) => write!(
                        f,
                        "; the worst is hand {}'s {} of {:.1} {u}, {:.0} % of the limit {:.1} {u}",
                        w.hand,
                        load_name(w.load),
                        w.value,
                        100.0 * w.ratio,
                        w.limit,
                        u = w.load.unit()
                    ),
                    None => Ok(()),
                }
            }
            Reason::ChecksPassed { stage: Stage::Final } => f.write_str(
                "every stub, connector and clip was fitted, and every installation check passed at every position of the motion",
            ),
            Reason::ChecksPassed {
                stage: Stage::Running,
            } => f.write_str("every installation check has passed so far"),
            Reason::NoHandActed { stage: Stage::Final } => {
                f.write_str("no hand acted in this scene: there is no hand load to judge")
            }
            Reason::NoHandActed {
                stage: Stage::Running,
            } => f.write_str("no hand has acted yet: nothing to judge"),
        }
    }
}
