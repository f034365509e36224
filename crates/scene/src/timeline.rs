//! Building the timeline: hose names and node indices resolved, waypoints converted to
//! metres, angles to radians, defaults filled in (SPEC L1–L3).

use crate::error::FieldError;
use crate::format::{
    ActionEntry, AimHandEntry, AlignHandEntry, FixEntry, GrabEntry, GripName, HandEntry, LoadEntry,
    MountEntry, MoveEntry, MoveHandEntry, MovePartEntry, NodeEntry, Points, RotateEntry,
    RotatePartEntry, RunEntry, SettleEntry, SettleFinishName, TieEntry, UnloadEntry,
};
use crate::ranges::{at_most, vec_at_most, MAX_LOAD_FORCE, MAX_LOAD_MOMENT, MAX_ROTATION_DEG};
use crate::units::LengthUnit;
use crate::validate::{finite, finite_vec, node_index, non_negative, non_zero_vec, positive};
use glam::DVec3;
use pliant_assembly::{Action, Grip, MovePath, NodeRef, Rotation, SettleFinish, Timeline};

/// Default residual force tolerance of `settle` (N), as Python's `Simulation.settle`.
pub const DEFAULT_SETTLE_FORCE_TOLERANCE: f64 = 1e-3;
/// Default residual moment tolerance of `settle` (N·m), as Python's `Simulation.settle`.
pub const DEFAULT_SETTLE_MOMENT_TOLERANCE: f64 = 1e-4;
/// Default rest threshold of `settle` (J).
pub const DEFAULT_SETTLE_KINETIC_ENERGY: f64 = 1e-6;
/// Default time limit of `settle` (s).
pub const DEFAULT_SETTLE_MAX_DURATION: f64 = 30.0;
/// Number of hands a timeline may use (indices 0 … `MAX_HANDS` − 1).
pub const MAX_HANDS: usize = 8;
/// Farthest a `move_part` may shift a part \[m\] (the workcell's limit).
const MAX_PART_SHIFT: f64 = pliant_assembly::workcell::part_inputs::MAX_PART_SHIFT;
/// Largest turn of a `rotate_part` \[°\] (the workcell's limit).
const MAX_PART_TURN_DEG: f64 = 3600.0;

/// Makes the parts the timeline moves (`move_part`, `rotate_part`) movable, after
/// checking that each names a part without a `motion` of its own; errors name the
/// action's `part` field and list the parts.
pub fn make_moved_parts_movable(
    timeline: &Timeline,
    parts: &mut [pliant_core::RigidPartSpec],
) -> Result<(), FieldError> {
    for (i, a) in timeline.actions.iter().enumerate() {
        let (Action::MovePart { part, .. } | Action::RotatePart { part, .. }) = a else {
            continue;
        };
        let field = format!("timeline[{i}].part");
        let Some(k) = parts.iter().position(|p| &p.name == part) else {
            let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
            return Err(FieldError::new(
                field,
                format!("\"{part}\""),
                format!(
                    "names no part; parts are: {}",
                    if names.is_empty() {
                        "none".into()
                    } else {
                        names.join(", ")
                    }
                ),
            ));
        };
        if parts[k].motion.is_some() {
            return Err(FieldError::new(
                field,
                format!("\"{part}\""),
                "has a `motion`; a timeline cannot move it as well (script the motion, or move a part it carries)",
            ));
        }
        parts[k].movable = true;
    }
    Ok(())
}

/// A hose as the timeline sees it: its name and node count.
pub struct HoseNodes<'a> {
    /// Hose name.
    pub name: &'a str,
    /// Number of nodes.
    pub nodes: usize,
}

/// Checks and builds the timeline.
pub fn build_timeline(
    raw: &[ActionEntry],
    hoses: &[HoseNodes],
    unit: LengthUnit,
) -> Result<Timeline, FieldError> {
    let actions = raw
        .iter()
        .enumerate()
        .map(|(i, a)| build_action(&format!("timeline[{i}]"), a, hoses, unit))
        .collect::<Result<Vec<_>, _>>()?;
    check_hands(&actions)?;
    check_load_names(&actions)?;
    Ok(Timeline { actions })
}

/// Checks that a named load is not named again while it acts, and that an `unload` by
/// name names a load acting on that node.
fn check_load_names(actions: &[Action]) -> Result<(), FieldError> {
    let mut acting: Vec<(&str, NodeRef)> = Vec::new();
    for (i, a) in actions.iter().enumerate() {
        match a {
            Action::Load {
                name: Some(name),
                node,
                ..
            } => {
                if acting.iter().any(|(n, _)| n == name) {
                    return Err(FieldError::new(
                        format!("timeline[{i}].name"),
                        format!("\"{name}\""),
                        "a load of this name is still acting; unload it first or choose another name",
                    ));
                }
                acting.push((name, *node));
            }
            Action::Unload { node, name: None } => acting.retain(|(_, n)| n != node),
            Action::Unload {
                node,
                name: Some(name),
            } => match acting.iter().position(|(n, _)| n == name) {
                Some(k) if acting[k].1 == *node => {
                    acting.remove(k);
                }
                Some(_) => {
                    return Err(FieldError::new(
                        format!("timeline[{i}].name"),
                        format!("\"{name}\""),
                        "that load acts on another node",
                    ))
                }
                None => {
                    return Err(FieldError::new(
                        format!("timeline[{i}].name"),
                        format!("\"{name}\""),
                        "no earlier `load` of this name is acting",
                    ))
                }
            },
            _ => {}
        }
    }
    Ok(())
}

/// Checks a hand index: 0 … [`MAX_HANDS`] − 1.
fn hand_index(field: &str, hand: i64) -> Result<usize, FieldError> {
    if (0..MAX_HANDS as i64).contains(&hand) {
        Ok(hand as usize)
    } else {
        Err(FieldError::new(
            field,
            hand.to_string(),
            format!("out of range: hands are numbered 0 … {}", MAX_HANDS - 1),
        ))
    }
}

/// Follows which hands hold a beam through the timeline: `move_hand` and `release_hand`
/// need a hand that grabbed earlier and has not let go since. (A `grab` by a hand that
/// already holds a beam lets go of it first, as the runner does.)
fn check_hands(actions: &[Action]) -> Result<(), FieldError> {
    // For each hand: the index of the action where it last grabbed or released.
    let mut holding = [None::<usize>; MAX_HANDS];
    let mut released = [None::<usize>; MAX_HANDS];
    for (i, a) in actions.iter().enumerate() {
        let (hand, verb) = match a {
            Action::Grab { hand, .. } | Action::GrabNode { hand, .. } => {
                holding[*hand] = Some(i);
                released[*hand] = None;
                continue;
            }
            Action::MoveHand { hand, .. } | Action::AlignHand { hand, .. } => (*hand, "move"),
            Action::ReleaseHand { hand } => (*hand, "release"),
            Action::AimHand { hand, .. } => (*hand, "aim"),
            _ => continue,
        };
        if holding[hand].is_none() {
            let why = match released[hand] {
                Some(r) => format!("it let go at timeline[{r}] and has not grabbed since"),
                None => format!("no earlier `grab` with hand = {hand}"),
            };
            return Err(FieldError::new(
                format!("timeline[{i}].hand"),
                hand.to_string(),
                format!("cannot {verb} a hand that holds nothing: {why}"),
            ));
        }
        if verb == "release" {
            holding[hand] = None;
            released[hand] = Some(i);
        }
    }
    Ok(())
}

/// Resolves `hose` and `node` of an action.
fn node_ref(
    field: &str,
    hose: &str,
    node: i64,
    hoses: &[HoseNodes],
) -> Result<NodeRef, FieldError> {
    let index = hoses.iter().position(|h| h.name == hose).ok_or_else(|| {
        let names: Vec<&str> = hoses.iter().map(|h| h.name).collect();
        FieldError::new(
            format!("{field}.hose"),
            format!("\"{hose}\""),
            format!("unknown hose; hoses: {}", names.join(", ")),
        )
    })?;
    let node = node_index(&format!("{field}.node"), node, hoses[index].nodes, hose)?;
    Ok(NodeRef { hose: index, node })
}

/// Checks waypoints and converts them to metres.
fn waypoints(field: &str, points: &Points, unit: LengthUnit) -> Result<Vec<DVec3>, FieldError> {
    let (u, scale) = (unit.symbol(), unit.to_metres());
    match points {
        Points::One(p) => Ok(vec![finite_vec(field, *p, u)? * scale]),
        Points::Many(ps) if ps.is_empty() => {
            Err(FieldError::new(field, "[]", "needs at least one waypoint"))
        }
        Points::Many(ps) => ps
            .iter()
            .enumerate()
            .map(|(k, p)| finite_vec(&format!("{field}[{k}]"), *p, u).map(|v| v * scale))
            .collect(),
    }
}

/// Checks a rotation and converts it to a unit axis and radians.
fn rotation(field: &str, r: &RotateEntry) -> Result<Rotation, FieldError> {
    let axis = non_zero_vec(&format!("{field}.axis"), r.axis, "")?.normalize();
    let angle_field = format!("{field}.angle_deg");
    let angle = finite(&angle_field, r.angle_deg, "°")?;
    let angle = at_most(&angle_field, angle, MAX_ROTATION_DEG, "°", "a rotation")?.to_radians();
    Ok(Rotation { axis, angle })
}

/// Checks the `to` / `by` / `rotate` of a `move` or `move_hand`: at most one of `to`
/// and `by`, at least one of the three. `what` names the action in messages.
/// The path of a move: `to` or `by` (not both), or none.
fn move_path(
    field: &str,
    what: &str,
    to: &Option<Points>,
    by: &Option<Points>,
    unit: LengthUnit,
) -> Result<Option<MovePath>, FieldError> {
    let sub = |name: &str| format!("{field}.{name}");
    Ok(match (to, by) {
        (Some(_), Some(_)) => {
            return Err(FieldError::about(
                field,
                format!("{what} takes either `to` (absolute) or `by` (relative), not both"),
            ))
        }
        (Some(p), None) => Some(MovePath::To(waypoints(&sub("to"), p, unit)?)),
        (None, Some(p)) => Some(MovePath::By(waypoints(&sub("by"), p, unit)?)),
        (None, None) => None,
    })
}

fn path_and_rotation(
    field: &str,
    what: &str,
    to: &Option<Points>,
    by: &Option<Points>,
    rotate: &Option<RotateEntry>,
    unit: LengthUnit,
) -> Result<(Option<MovePath>, Option<Rotation>), FieldError> {
    let sub = |name: &str| format!("{field}.{name}");
    let path = move_path(field, what, to, by, unit)?;
    let rotation = match rotate {
        Some(r) => Some(rotation(&sub("rotate"), r)?),
        None => None,
    };
    if path.is_none() && rotation.is_none() {
        return Err(FieldError::about(
            field,
            format!("{what} needs `to`, `by` or `rotate`"),
        ));
    }
    Ok((path, rotation))
}

/// Checks and builds one action.
fn build_action(
    field: &str,
    a: &ActionEntry,
    hoses: &[HoseNodes],
    unit: LengthUnit,
) -> Result<Action, FieldError> {
    let sub = |name: &str| format!("{field}.{name}");
    Ok(match a {
        ActionEntry::Fix(FixEntry { hose, node, part }) => match part {
            None => Action::Fix {
                node: node_ref(field, hose, *node, hoses)?,
            },
            Some(part) => Action::Mount {
                node: node_ref(field, hose, *node, hoses)?,
                part: part.clone(),
            },
        },
        ActionEntry::Mount(MountEntry { hose, node, part }) => Action::Mount {
            node: node_ref(field, hose, *node, hoses)?,
            part: part.clone(),
        },
        ActionEntry::Unload(UnloadEntry { hose, node, name }) => Action::Unload {
            node: node_ref(field, hose, *node, hoses)?,
            name: name.clone(),
        },
        ActionEntry::Release(NodeEntry { hose, node }) => Action::Release {
            node: node_ref(field, hose, *node, hoses)?,
        },
        ActionEntry::Tie(TieEntry { hose, node, to }) => {
            let (a, b) = (
                node_ref(field, hose, *node, hoses)?,
                node_ref(&sub("to"), &to.hose, to.node, hoses)?,
            );
            if a == b {
                return Err(FieldError::new(
                    sub("to"),
                    format!("{{ hose = \"{}\", node = {} }}", to.hose, to.node),
                    "is the tied node itself; a tie joins two nodes",
                ));
            }
            Action::Tie { node: a, to: b }
        }
        ActionEntry::Move(MoveEntry {
            hose,
            node,
            to,
            by,
            rotate,
            duration_s,
            wait,
        }) => {
            let node = node_ref(field, hose, *node, hoses)?;
            let (path, rotation) = path_and_rotation(field, "a move", to, by, rotate, unit)?;
            let duration = positive(&sub("duration_s"), *duration_s, "s")?;
            Action::Move {
                node,
                path,
                rotation,
                duration,
                wait: wait.unwrap_or(true),
            }
        }
        ActionEntry::Load(LoadEntry {
            hose,
            node,
            force_n,
            moment_nm,
            ramp_s,
            name,
        }) => {
            let node = node_ref(field, hose, *node, hoses)?;
            if force_n.is_none() && moment_nm.is_none() {
                return Err(FieldError::about(
                    field,
                    "a load needs `force_n` and/or `moment_nm`",
                ));
            }
            let force = finite_vec(&sub("force_n"), force_n.unwrap_or([0.0; 3]), "N")?;
            let force = vec_at_most(&sub("force_n"), force, MAX_LOAD_FORCE, "N", "a load")?;
            let moment = finite_vec(&sub("moment_nm"), moment_nm.unwrap_or([0.0; 3]), "N·m")?;
            let moment = vec_at_most(
                &sub("moment_nm"),
                moment,
                MAX_LOAD_MOMENT,
                "N·m",
                "a load's moment",
            )?;
            let ramp = non_negative(&sub("ramp_s"), ramp_s.unwrap_or(0.0), "s")?;
            if name.as_deref() == Some("") {
                return Err(FieldError::new(sub("name"), "\"\"", "must not be empty"));
            }
            Action::Load {
                node,
                force,
                moment,
                ramp,
                name: name.clone(),
            }
        }
        ActionEntry::Grab(GrabEntry {
            hand,
            at,
            hose,
            node,
            grip,
        }) => {
            let grip = match grip {
                GripName::Firm => Grip::Firm,
                GripName::Axial => Grip::Axial,
                GripName::Ball => Grip::Ball,
            };
            let hand = hand_index(&sub("hand"), *hand)?;
            match (at, hose, node) {
                (Some(at), None, None) => Action::Grab {
                    grip,
                    hand,
                    at: finite_vec(&sub("at"), *at, unit.symbol())? * unit.to_metres(),
                },
                (None, Some(hose), Some(node)) => Action::GrabNode {
                    grip,
                    hand,
                    node: node_ref(field, hose, *node, hoses)?,
                },
                (Some(_), _, _) => {
                    return Err(FieldError::about(
                        sub("at"),
                        "give either `at` or `hose` and `node`, not both",
                    ))
                }
                (None, Some(_), None) => {
                    return Err(FieldError::about(
                        field.to_string(),
                        "a grab by `hose` needs `node` too",
                    ))
                }
                (None, None, Some(_)) => {
                    return Err(FieldError::about(
                        field.to_string(),
                        "a grab by `node` needs `hose` too",
                    ))
                }
                (None, None, None) => {
                    return Err(FieldError::about(
                        sub("at"),
                        "missing field `at`: a grab needs `at`, or `hose` and `node`",
                    ))
                }
            }
        }
        ActionEntry::AlignHand(AlignHandEntry {
            hand,
            direction,
            to,
            by,
            duration_s,
        }) => {
            let d = non_zero_vec(&sub("direction"), *direction, "")?;
            let path = move_path(field, "a hand turn", to, by, unit)?;
            Action::AlignHand {
                hand: hand_index(&sub("hand"), *hand)?,
                direction: d.normalize(),
                path,
                duration: positive(&sub("duration_s"), *duration_s, "s")?,
            }
        }
        ActionEntry::MoveHand(MoveHandEntry {
            hand,
            to,
            by,
            rotate,
            duration_s,
            speed_m_s,
            spline,
            wait,
        }) => {
            let hand = hand_index(&sub("hand"), *hand)?;
            let (path, rotation) = path_and_rotation(field, "a hand move", to, by, rotate, unit)?;
            let (duration, speed) = match (duration_s, speed_m_s) {
                (Some(d), None) => (positive(&sub("duration_s"), *d, "s")?, None),
                (None, Some(v)) => {
                    if path.is_none() {
                        return Err(FieldError::about(
                            sub("speed_m_s"),
                            "a speed needs a path (`to` or `by`); give `duration_s` for a pure rotation",
                        ));
                    }
                    (0.0, Some(positive(&sub("speed_m_s"), *v, "m/s")?))
                }
                (Some(_), Some(_)) => {
                    return Err(FieldError::about(
                        sub("speed_m_s"),
                        "give either `duration_s` or `speed_m_s`, not both",
                    ))
                }
                (None, None) => {
                    return Err(FieldError::about(
                        field.to_string(),
                        "a hand move needs `duration_s` or `speed_m_s`",
                    ))
                }
            };
            Action::MoveHand {
                hand,
                path,
                rotation,
                duration,
                speed,
                spline: spline.unwrap_or(false),
                wait: wait.unwrap_or(true),
            }
        }
        ActionEntry::AimHand(AimHandEntry {
            hand,
            position,
            orientation_wxyz,
        }) => {
            let orientation = match orientation_wxyz {
                None => None,
                Some([w, x, y, z]) => {
                    let q = glam::DQuat::from_xyzw(*x, *y, *z, *w);
                    if !q.is_finite() || (q.length() - 1.0).abs() > 1e-6 {
                        return Err(FieldError::new(
                            sub("orientation_wxyz"),
                            format!("{:?}", [w, x, y, z]),
                            "must be a finite unit quaternion [w, x, y, z]",
                        ));
                    }
                    Some(q.normalize())
                }
            };
            Action::AimHand {
                hand: hand_index(&sub("hand"), *hand)?,
                position: finite_vec(&sub("position"), *position, unit.symbol())?
                    * unit.to_metres(),
                orientation,
            }
        }
        ActionEntry::ReleaseHand(HandEntry { hand }) => Action::ReleaseHand {
            hand: hand_index(&sub("hand"), *hand)?,
        },
        ActionEntry::MovePart(MovePartEntry {
            part,
            by,
            to,
            duration_s,
            wait,
        }) => {
            let offset = |name: &str, v: &Option<[f64; 3]>| -> Result<_, FieldError> {
                v.map(|v| {
                    let m = finite_vec(&sub(name), v, unit.symbol())? * unit.to_metres();
                    vec_at_most(&sub(name), m, MAX_PART_SHIFT, "m", "a part's move")
                })
                .transpose()
            };
            let (by, to) = (offset("by", by)?, offset("to", to)?);
            if by.is_some() == to.is_some() {
                return Err(FieldError::about(
                    field,
                    "move_part takes either `by` (from where the part is) or `to` (from where the scene placed it)",
                ));
            }
            Action::MovePart {
                part: part.clone(),
                by,
                to,
                duration: positive(&sub("duration_s"), *duration_s, "s")?,
                wait: wait.unwrap_or(true),
            }
        }
        ActionEntry::RotatePart(RotatePartEntry {
            part,
            axis,
            point,
            by_deg,
            to_deg,
            duration_s,
            wait,
        }) => {
            let axis = non_zero_vec(&sub("axis"), *axis, "")?.normalize();
            let point = point
                .map(|p| finite_vec(&sub("point"), p, unit.symbol()))
                .transpose()?
                .map(|p| p * unit.to_metres());
            let angle = |name: &str, a: &Option<f64>| -> Result<_, FieldError> {
                a.map(|a| {
                    let a = finite(&sub(name), a, "°")?;
                    at_most(&sub(name), a, MAX_PART_TURN_DEG, "°", "a part's turn")
                        .map(f64::to_radians)
                })
                .transpose()
            };
            let (by, to) = (angle("by_deg", by_deg)?, angle("to_deg", to_deg)?);
            if by.is_some() == to.is_some() {
                return Err(FieldError::about(
                    field,
                    "rotate_part takes either `by_deg` (from where the part is) or `to_deg` (from where the scene placed it)",
                ));
            }
            Action::RotatePart {
                part: part.clone(),
                axis,
                point,
                by,
                to,
                duration: positive(&sub("duration_s"), *duration_s, "s")?,
                wait: wait.unwrap_or(true),
            }
        }
        ActionEntry::Run(RunEntry { duration_s }) => Action::Run {
            duration: positive(&sub("duration_s"), *duration_s, "s")?,
        },
        ActionEntry::Settle(SettleEntry {
            force_tolerance_n,
            moment_tolerance_nm,
            kinetic_energy_j,
            max_duration_s,
            finish,
        }) => Action::Settle {
            force_tolerance: positive(
                &sub("force_tolerance_n"),
                force_tolerance_n.unwrap_or(DEFAULT_SETTLE_FORCE_TOLERANCE),
                "N",
            )?,
            moment_tolerance: positive(
                &sub("moment_tolerance_nm"),
                moment_tolerance_nm.unwrap_or(DEFAULT_SETTLE_MOMENT_TOLERANCE),
                "N·m",
            )?,
            kinetic_energy_threshold: positive(
                &sub("kinetic_energy_j"),
                kinetic_energy_j.unwrap_or(DEFAULT_SETTLE_KINETIC_ENERGY),
                "J",
            )?,
            max_duration: positive(
                &sub("max_duration_s"),
                max_duration_s.unwrap_or(DEFAULT_SETTLE_MAX_DURATION),
                "s",
            )?,
            finish: match finish.unwrap_or_default() {
                SettleFinishName::Dynamic => SettleFinish::Dynamic,
                SettleFinishName::Static => SettleFinish::Static,
                SettleFinishName::StaticEquilibrium => SettleFinish::StaticEquilibrium,
            },
        },
    })
}
