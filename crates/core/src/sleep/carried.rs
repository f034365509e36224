//! Sleeping carried by a moving part: a hose (or network) at rest *relative to* the one
//! moving part it lies on sleeps as a rigid load on that part. Its nodes keep their pose
//! in the part's reference frame and are placed by the part's pose each step (x = T(t) +
//! R(t) x_local, q = R(t) q_local, v and ω those of the rigid motion), so no element or
//! contact work is done for it.
//!
//! That is exact as long as the awake hose would stay at rest relative to the part. In the
//! part's frame a node at rest balances its contact force f_c, the internal force f_int of
//! its elements (frozen while it sleeps) and the effective gravity
//! m g_eff = m (g − a_p), a_p the acceleration of the part's material point under it (the
//! d'Alembert force, centripetal and Euler terms included; no Coriolis force at rest):
//! f_c + f_int + m g_eff = 0. So while it sleeps the contact force the node needs is
//!
//! > f_c(t) = f_c(0) − m (g_eff(t) − g_eff(0))      (both in the part's frame)
//!
//! and the hose wakes as soon as, at any node,
//! - a node in contact would need f_c(t) outside [`WAKE_CONE`] of the static Coulomb cone
//!   (f_n ≤ 0: it would lift off; |f_t| > WAKE_CONE μ_s f_n: it would slip), or
//! - a node without contact (a free span) sees its effective gravity change by more than
//!   [`WAKE_GRAVITY_CHANGE`] of |g| (its elements would deflect), or
//! - a still part comes within contact reach (the part carries it into something), or
//!   another moving part does ([`crate::contact`]'s `wake_near`), or
//! - anything that wakes a hose asleep in place happens (hands, load cases, another hose's
//!   contact force, a moving support whose pose is not the carried one).
//!
//! A hose falls asleep carried only if its network touches exactly one part, a moving
//! one, every node's velocity relative to the part is below [`super::SLEEP_SPEED`] for
//! [`super::SLEEP_AFTER_STEPS`] steps, every contact force lies within [`SLEEP_CONE`] of
//! the cone, no still part is within reach, and it has no stiffened section (those keep a
//! rigid-body state of their own). A hose fixed in the world, or to another part, on the
//! moving part slides relative to it and is never calm there.
//!
//! g_eff(t) uses the part's material acceleration by central differences of its velocity
//! field over ±Δt/2 (exact for uniformly accelerated motions).

use crate::kinematics::{Placement, Pose};
use crate::math::log_map;
use crate::{Model, State};
use glam::{DMat3, DQuat, DVec3};

/// A hose falls asleep on a moving part only if each node's contact force lies within
/// this fraction of the static friction cone: |f_t| ≤ SLEEP_CONE μ_s f_n.
pub const SLEEP_CONE: f64 = 0.8;
/// A carried node wakes its hose when the contact force it needs leaves this fraction of
/// the static friction cone (a margin below slipping; above [`SLEEP_CONE`], so that a
/// hose does not wake and fall asleep by turns).
pub const WAKE_CONE: f64 = 0.9;
/// A carried node without contact wakes its hose when its effective gravity (in the
/// part's frame) changes by more than this fraction of |g| (plus `WAKE_FORCE`/m).
pub const WAKE_GRAVITY_CHANGE: f64 = 0.01;
/// Force change \[N\] that always counts (the same floor as for sleeping in place).
const WAKE_FORCE: f64 = 1e-6;
/// How far around a carried hose the still parts are searched \[m\]; the part may carry it
/// this far (less the contact reach) before they are searched again.
const CLEARANCE_SEARCH: f64 = 0.05;

/// No part.
const NONE: usize = usize::MAX;
/// More than one part.
const MIXED: usize = usize::MAX - 1;

/// The carried-sleep state of a [`State`]'s hoses (part of [`crate::sleep::Sleep`], so of every
/// checkpoint).
#[derive(Clone, Debug, Default)]
pub struct Carriage {
    /// Per node: the moving part carrying it while its hose sleeps (`usize::MAX`: none).
    pub part_of_node: Vec<usize>,
    /// Per hose: the moving part carrying it (`usize::MAX`: none).
    part_of_hose: Vec<usize>,
    /// Per carried node: its position and orientation in the part's reference frame.
    local_x: Vec<DVec3>,
    local_q: Vec<DQuat>,
    /// Per carried node, in the part's frame at falling asleep: contact force, contact
    /// normal (zero: no contact), effective gravity g − a_p.
    force0: Vec<DVec3>,
    normal0: Vec<DVec3>,
    gravity0: Vec<DVec3>,
    /// Per carried hose: how far its part may still carry it before the still parts are
    /// searched again \[m\], and its nodes' largest distance from the part's origin.
    clearance: Vec<f64>,
    spread: Vec<f64>,
    /// Per part (while it carries a hose): its pose at the step's end, its angular
    /// velocity over the step, the effective gravity in its frame at the step's start
    /// ([`gravity_map`]), and the step's start time and length they are for.
    end_pose: Vec<Pose>,
    end_spin: Vec<DVec3>,
    gravity: Vec<(DVec3, DMat3)>,
    placed_for: Vec<(f64, f64)>,
    /// Per hose (scratch): the one part its contacts touched this step (or none, mixed).
    seen: Vec<usize>,
    /// Per hose (scratch): the part its network lies on.
    network_part: Vec<usize>,
    /// Per node (scratch): its contact normals this step, weighted and summed.
    normal_now: Vec<DVec3>,
}

impl Carriage {
    pub(super) fn new(model: &Model) -> Self {
        let (nodes, hoses) = (model.node_count(), model.hoses.len());
        Carriage {
            part_of_node: vec![NONE; nodes],
            part_of_hose: vec![NONE; hoses],
            local_x: vec![DVec3::ZERO; nodes],
            local_q: vec![DQuat::IDENTITY; nodes],
            force0: vec![DVec3::ZERO; nodes],
            normal0: vec![DVec3::ZERO; nodes],
            gravity0: vec![DVec3::ZERO; nodes],
            clearance: vec![0.0; hoses],
            spread: vec![0.0; hoses],
            end_pose: vec![Pose::IDENTITY; model.environment.parts.len()],
            end_spin: vec![DVec3::ZERO; model.environment.parts.len()],
            gravity: vec![(DVec3::ZERO, DMat3::ZERO); model.environment.parts.len()],
            placed_for: vec![(f64::NAN, f64::NAN); model.environment.parts.len()],
            seen: vec![NONE; hoses],
            network_part: vec![NONE; hoses],
            normal_now: vec![DVec3::ZERO; nodes],
        }
    }

    /// The moving part carrying hose `h` while it sleeps, if any.
    pub fn part_of_hose(&self, h: usize) -> Option<usize> {
        self.part_of_hose.get(h).copied().filter(|&k| k != NONE)
    }

    /// Whether any hose sleeps carried.
    pub fn any(&self) -> bool {
        self.part_of_hose.iter().any(|&k| k != NONE)
    }

    /// Hose `h` no longer carried (it wakes).
    pub(super) fn release(&mut self, model: &Model, h: usize) {
        if self.part_of_hose[h] == NONE {
            return;
        }
        self.part_of_hose[h] = NONE;
        for i in model.hoses[h].nodes() {
            self.part_of_node[i] = NONE;
        }
    }

    /// Where carried node `i` is at the step's end (after [`before_step`]).
    pub(crate) fn target(&self, i: usize) -> Option<(DVec3, DQuat)> {
        let k = *self.part_of_node.get(i)?;
        (k != NONE).then(|| {
            let pose = self.end_pose[k];
            let q = (pose.rotation * self.local_q[i]).normalize();
            (pose.apply(self.local_x[i]), q)
        })
    }
}

/// The hose node `i` belongs to (hoses own consecutive node ranges).
fn hose_of(model: &Model, i: usize) -> Option<usize> {
    let h = model
        .hoses
        .partition_point(|h| h.first_node <= i)
        .checked_sub(1)?;
    model.hoses[h].nodes().contains(&i).then_some(h)
}

/// Part `k`'s placements at `t` ∓ `h`, between which [`gravity_map`] differentiates
/// its velocity field.
fn placements_about(model: &Model, state: &State, k: usize, t: f64, h: f64) -> [Placement; 2] {
    let at = |t| model.kinematics.placement_at(k, t, &state.part_moves);
    [at(t - h), at(t + h)]
}

/// The effective gravity g − a_p in the frame `rotation` of the part (its rotation at the
/// time between `about`, [`placements_about`] ±`h`), a_p the acceleration of the
/// material point at l (reference placement) by central differences of its velocity
/// ω × (R l) + Ṫ: an affine map of l, returned as (G, N) with g_eff(l) = G + N l.
fn gravity_map(model: &Model, about: &[Placement; 2], h: f64, rotation: DQuat) -> (DVec3, DMat3) {
    let skew = |w: DVec3| {
        DMat3::from_cols(
            DVec3::new(0.0, w.z, -w.y),
            DVec3::new(-w.z, 0.0, w.x),
            DVec3::new(w.y, -w.x, 0.0),
        )
    };
    let field = |p: &Placement| skew(p.twist.angular) * DMat3::from_quat(p.pose.rotation);
    let a0 = (about[1].twist.linear - about[0].twist.linear) / (2.0 * h);
    let m = (field(&about[1]) - field(&about[0])) * (1.0 / (2.0 * h));
    let back = DMat3::from_quat(rotation.inverse());
    (back * (model.gravity - a0), -(back * m))
}

/// Whether contact force `f` with normal `n` lies within `fraction` of the static cone.
fn inside_cone(f: DVec3, n: DVec3, mu: f64, fraction: f64) -> bool {
    let f_n = f.dot(n);
    f_n > 0.0 && (f - f_n * n).length() <= fraction * mu * f_n
}

/// After a step: which part each hose's contacts touched and which part each network
/// lies on (one moving part, or none), and the nodes' contact normals.
pub(super) fn survey(model: &Model, state: &mut State) {
    let c = &mut state.sleep.carried;
    c.seen.fill(NONE);
    c.normal_now.fill(DVec3::ZERO);
    for p in &state.contact.points {
        let Some(h) = hose_of(model, p.node_a) else {
            continue;
        };
        c.seen[h] = match c.seen[h] {
            NONE => p.part,
            k if k == p.part => k,
            _ => MIXED,
        };
        if p.node_a == p.node_b {
            c.normal_now[p.node_a] += p.normal;
        } else {
            c.normal_now[p.node_a] += (1.0 - p.t) * p.normal;
            c.normal_now[p.node_b] += p.t * p.normal;
        }
    }
    for h in 0..model.hoses.len() {
        let network = model.hose_network[h];
        let mut part = NONE;
        for k in 0..model.hoses.len() {
            if model.hose_network[k] != network || c.seen[k] == NONE {
                continue;
            }
            part = if part == NONE || part == c.seen[k] {
                c.seen[k]
            } else {
                MIXED
            };
        }
        let moving = part < model.environment.parts.len() && model.environment.parts[part].moves;
        c.network_part[h] = if moving { part } else { NONE };
    }
}

/// Node `i`'s velocity and spin relative to the moving part its network lies on (its
/// absolute ones if none), after [`survey`].
pub(super) fn relative_motion(state: &State, h: usize, i: usize) -> (DVec3, DVec3) {
    let k = state.sleep.carried.network_part[h];
    if k == NONE {
        return (state.v[i], state.w[i]);
    }
    let place = state.contact.placements[k];
    (
        state.v[i] - place.velocity_at(state.x[i]),
        state.w[i] - place.twist.angular,
    )
}

/// Whether hose `h`, calm, may sleep, after [`survey`]: `Ok(Some(part))` carried by the
/// moving part its network lies on, `Ok(None)` in place (it lies on no moving part),
/// `Err(())` not yet (it lies on a moving part but may not sleep carried by it).
pub(super) fn carrier(model: &Model, state: &State, h: usize) -> Result<Option<usize>, ()> {
    let c = &state.sleep.carried;
    let k = c.network_part[h];
    if k == NONE {
        return Ok(None);
    }
    let mu = model.environment.parts[k].friction_static;
    let network = model.hose_network[h];
    for (g, info) in model.hoses.iter().enumerate() {
        if model.hose_network[g] != network {
            continue;
        }
        for i in info.nodes() {
            let n = c.normal_now[i];
            let loaded = n != DVec3::ZERO;
            if model.body_of[i].is_some()
                || (loaded && !inside_cone(state.contact_force[i], n.normalize(), mu, SLEEP_CONE))
            {
                return Err(());
            }
        }
    }
    if still_clearance(model, state, h, 0.0) <= 0.0 {
        return Err(());
    }
    Ok(Some(k))
}

/// The distance part `k` may carry hose `h` before one of its nodes comes within contact
/// reach of a still part, less `margin` (searched up to [`CLEARANCE_SEARCH`]).
fn still_clearance(model: &Model, state: &State, h: usize, margin: f64) -> f64 {
    let env = &model.environment;
    let mut clearance = CLEARANCE_SEARCH;
    if env.parts.len() == env.moving.len() {
        return clearance - margin; // no still part
    }
    for i in model.hoses[h].nodes() {
        let reach = model.radius[i] * (1.0 + crate::contact::CONTACT_SKIN);
        let d = env
            .closest_point(state.x[i], CLEARANCE_SEARCH + reach)
            .map_or(CLEARANCE_SEARCH + reach, |hit| hit.2);
        clearance = clearance.min(d - reach);
    }
    clearance - margin
}

/// Hose `h` falls asleep carried by part `k`: its nodes' poses in the part's frame and
/// their forces and effective gravity there are kept, and they take the part's velocity.
pub(super) fn begin(model: &Model, state: &mut State, h: usize, k: usize) {
    let now = model
        .kinematics
        .placement_at(k, state.time, &state.part_moves);
    let mid = state.contact.placements[k];
    let half = 0.5 * model.time_step;
    let about = placements_about(model, state, k, state.time, half);
    let (g0, n0) = gravity_map(model, &about, half, now.pose.rotation);
    let inverse = now.pose.rotation.inverse();
    let mut spread = 0.0_f64;
    for i in model.hoses[h].nodes() {
        let local = now.pose.inverse_apply(state.x[i]);
        let gravity = g0 + n0 * local;
        let c = &mut state.sleep.carried;
        c.part_of_node[i] = k;
        c.local_x[i] = local;
        c.local_q[i] = (inverse * state.q[i]).normalize();
        c.force0[i] = inverse * state.contact_force[i];
        c.normal0[i] = (inverse * c.normal_now[i]).normalize_or_zero();
        c.gravity0[i] = gravity;
        spread = spread.max(local.length());
        state.v[i] = mid.velocity_at(state.x[i]);
        state.w[i] = mid.twist.angular;
    }
    let clearance = still_clearance(model, state, h, 0.0);
    let c = &mut state.sleep.carried;
    c.part_of_hose[h] = k;
    c.spread[h] = spread;
    c.clearance[h] = clearance;
}

/// Before a step of `dt` from `state.time` (the parts placed for it): wakes the carried
/// hoses whose part would no longer carry them at rest (module doc), and places the
/// carrying parts at the step's end for [`carry`].
pub(crate) fn before_step(model: &Model, state: &mut State, dt: f64) {
    if !state.sleep.carried.any() {
        return;
    }
    let t = state.time;
    let g = model.gravity.length();
    for h in 0..model.hoses.len() {
        let k = state.sleep.carried.part_of_hose[h];
        if k == NONE {
            continue;
        }
        if state.sleep.carried.placed_for[k] != (t, dt) {
            let end = model.kinematics.placement_at(k, t + dt, &state.part_moves);
            let about = placements_about(model, state, k, t, 0.5 * dt);
            let start = state.contact.placements[k].pose.rotation;
            let map = gravity_map(model, &about, 0.5 * dt, start);
            let spin = log_map(end.pose.rotation * start.conjugate()) / dt;
            let c = &mut state.sleep.carried;
            (c.end_pose[k], c.end_spin[k], c.gravity[k]) = (end.pose, spin, map);
            c.placed_for[k] = (t, dt);
        }
        let place = state.contact.placements[k];
        let mu = model.environment.parts[k].friction_static;
        let c = &state.sleep.carried;
        let sweep = (place.twist.linear.length() + place.twist.angular.length() * c.spread[h]) * dt;
        let mut wake = false;
        let clearance = c.clearance[h] - sweep;
        let clearance = if clearance < 0.0 {
            still_clearance(model, state, h, sweep)
        } else {
            clearance
        };
        wake |= clearance <= 0.0;
        for i in model.hoses[h].nodes() {
            if wake {
                break;
            }
            let c = &state.sleep.carried;
            let gravity = c.gravity[k].0 + c.gravity[k].1 * c.local_x[i];
            let change = model.mass[i] * (gravity - c.gravity0[i]);
            wake = if c.normal0[i] == DVec3::ZERO {
                change.length() > WAKE_FORCE + WAKE_GRAVITY_CHANGE * model.mass[i] * g
            } else {
                !inside_cone(c.force0[i] - change, c.normal0[i], mu, WAKE_CONE)
            };
        }
        state.sleep.carried.clearance[h] = clearance;
        if wake {
            state.sleep.wake(model, h);
        }
    }
}

/// Places the carried nodes still asleep and not held otherwise at their part's pose at
/// the step's end, with the velocities of that motion over the step of `dt`; they count
/// as held.
pub(crate) fn carry(state: &mut State, dt: f64) {
    for i in 0..state.x.len() {
        if state.held[i] || !state.sleep.node_asleep[i] {
            continue;
        }
        let Some((x, q)) = state.sleep.carried.target(i) else {
            continue;
        };
        state.v[i] = (x - state.x[i]) / dt;
        state.w[i] = state.sleep.carried.end_spin[state.sleep.carried.part_of_node[i]];
        state.x[i] = x;
        state.q[i] = q;
        state.held[i] = true;
        state.force[i] = DVec3::ZERO;
        state.moment[i] = DVec3::ZERO;
    }
}
