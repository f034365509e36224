//! Recording a range-of-motion study: at each checked instant one row of the motion
//! coordinate, per hose its smallest bend radius, its bend furthest past its beam's
//! minimum radius, its largest twist and largest axial force,
//! per hose and watched part their clearance ([`pliant_core::contact::part_gap`]), and
//! the largest force with which a fix, mount, support or hand holds a node (the fixing
//! forces: `State::reaction_force` of the held nodes); and every hose's centre-line
//! samples for its swept envelope ([`super::envelope`]).

use super::coordinate::Coordinate;
use super::envelope::SweptHoses;
use super::settings::SweepSettings;
use super::summary::SweepSummary;
use crate::checks::axial_force;
use crate::series_cap::{retain_flat, SeriesCap};
use pliant_core::contact::part_gap::hose_part_gap;
use pliant_core::loads::LoadCase;
use pliant_core::{Model, State};

/// Values per hose in a row: smallest bend radius \[m\]; the largest ratio κ·r_min of a
/// beam's curvature to its allowed one (above 1 it breaks its minimum radius) and that
/// beam's minimum radius \[m\] (0 when the hose is not checked); largest twist relative to
/// the routed hose [rad/m]; largest axial force \[N\].
pub(super) const PER_HOSE: usize = 5;

/// Values in one row of a sweep of `hoses` hoses and `pairs` watched (hose, part)
/// pairs: time, coordinate, five per hose, one per pair, the fixing force.
pub fn row_len(hoses: usize, pairs: usize) -> usize {
    2 + PER_HOSE * hoses + pairs + 1
}

/// The rows recorded so far, with the names and limits a report needs.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionSweep {
    coordinate: Coordinate,
    found: SweepSummary,
    /// Keeps the rows within [`crate::series_cap::MAX_SERIES_BYTES`] in a session of any
    /// length, the worst rows kept.
    cap: SeriesCap,
}

impl MotionSweep {
    /// A sweep of `model` with `settings`; `allowed_radius` per hose and beam \[m\] (empty:
    /// not checked) and `twist_limit` [rad/m] are the checks' limits.
    pub fn new(
        model: &Model,
        settings: &SweepSettings,
        allowed_radius: Vec<Vec<f64>>,
        twist_limit: f64,
    ) -> MotionSweep {
        let parts: Vec<usize> = if settings.clearance_parts.is_empty() {
            (0..model.environment.parts.len()).collect()
        } else {
            settings.clearance_parts.clone()
        };
        let pairs: Vec<(usize, usize)> = (0..model.hoses.len())
            .flat_map(|h| parts.iter().map(move |&p| (h, p)))
            .collect();
        let mut coordinate = Coordinate::of(model, settings.part);
        if model.kinematics.motion(settings.part).is_none() {
            if let Some(kind) = settings.moved_by_inputs {
                coordinate.kind = kind;
            }
        }
        let stride = row_len(model.hoses.len(), pairs.len());
        MotionSweep {
            cap: SeriesCap::of_rows(stride * std::mem::size_of::<f64>()),
            found: SweepSummary {
                coordinate: Some(coordinate.clone()),
                hose_names: model.hoses.iter().map(|h| h.name.clone()).collect(),
                allowed_radius,
                twist_limit,
                stride,
                pairs,
                part_names: model
                    .environment
                    .parts
                    .iter()
                    .map(|p| p.name.clone())
                    .collect(),
                min_clearance: settings.min_clearance,
                rows: Vec::new(),
                swept: Some(std::sync::Arc::new(SweptHoses::new(
                    model,
                    settings.envelope_voxel,
                ))),
                worst_bend_poses: None,
            },
            coordinate,
        }
    }

    /// Records a row for `state`, with the beams' curvature `kappa` [1/m] and twist
    /// relative to the routed hose `twist` [rad/m] (the checks' values at this instant).
    pub fn record(&mut self, model: &Model, state: &State, kappa: &[f64], twist: &[f64]) {
        if !self.cap.take() {
            return;
        }
        let t = state.time;
        let rows = &mut self.found.rows;
        rows.push(t);
        rows.push(self.coordinate.at(model, state, t));
        // the worst bend of this instant over every hose: κ·r_min where a minimum is
        // checked, else κ
        let checked = self
            .found
            .allowed_radius
            .iter()
            .any(|a| a.iter().any(|&r| r > 0.0));
        let mut severity = 0.0_f64;
        for (info, allowed) in model.hoses.iter().zip(&self.found.allowed_radius) {
            let (mut k, mut tw, mut force) = (0.0_f64, 0.0_f64, 0.0_f64);
            let (mut ratio, mut limit) = (0.0_f64, allowed.first().copied().unwrap_or(0.0));
            for (b, e) in (info.first_element..info.first_element + info.element_count).enumerate()
            {
                k = k.max(kappa[e]);
                let r_min = allowed.get(b).copied().unwrap_or(0.0);
                if kappa[e] * r_min > ratio {
                    (ratio, limit) = (kappa[e] * r_min, r_min);
                }
                tw = tw.max(twist[e].abs());
                force = force.max(axial_force(model, state, e).abs());
            }
            rows.extend([1.0 / k, ratio, limit, tw, force]);
            severity = severity.max(if checked { ratio } else { k });
        }
        let worse = self
            .found
            .worst_bend_poses
            .as_ref()
            .is_none_or(|w| severity > w.severity);
        if worse {
            let w = self
                .found
                .worst_bend_poses
                .get_or_insert_with(Default::default);
            w.time = t;
            w.severity = severity;
            w.poses.clear();
            w.poses.extend(
                (0..model.environment.parts.len())
                    .map(|k| model.kinematics.placement_at(k, t, &state.part_moves).pose),
            );
        }
        let rows = &mut self.found.rows;
        for &(h, p) in &self.found.pairs {
            let nodes = model.hoses[h].nodes();
            let pose = model
                .kinematics
                .moves(p)
                .then(|| model.kinematics.placement_at(p, t, &state.part_moves).pose);
            let (gap, _) = hose_part_gap(
                &model.environment,
                p,
                pose.as_ref(),
                &state.x[nodes.clone()],
                &model.radius[nodes],
            );
            rows.push(gap);
        }
        let fixing = state
            .loads
            .iter()
            .filter(|(_, c)| c.is_kinematic() || matches!(c, LoadCase::Support(_)))
            .map(|(_, c)| state.reaction_force[c.node()].length())
            .fold(0.0, f64::max);
        rows.push(fixing);
        if let Some(swept) = &mut self.found.swept {
            std::sync::Arc::make_mut(swept).add(model, state);
        }
        let count = rows.len() / self.found.stride;
        if count >= self.cap.max_rows() {
            let worst = self.found.worst_rows();
            if let Some(keep) = self.cap.thin(count, |i| worst.binary_search(&i).is_ok()) {
                retain_flat(&mut self.found.rows, self.found.stride, &keep);
            }
        }
    }

    /// How many checked instants make one row (1 until the rows first reach their cap).
    pub fn stride(&self) -> u64 {
        self.cap.stride()
    }

    /// What was recorded.
    pub fn summary(&self) -> &SweepSummary {
        &self.found
    }
}
