//! The worker's account of a study (SPEC E1–E2): at every posed instant (the scene's
//! record interval) the manikin reaches for the hands' positions by inverse kinematics,
//! its capsules are checked against the parts and the hoses, and its posture is scored by RULA and
//! REBA with the hands' forces, and classed (upright, bent trunk, arms above shoulder,
//! sitting, sitting with bent trunk) for
//! the hand-force limits until the next posed instant. Kept: each arm's worst reach residual, each segment's
//! deepest collision per part, the worst scores and when, and a time series for
//! `worker.csv`. Nothing is allocated per instant except the series' amortised growth
//! and the first collision of a segment with a part.

use super::body_pose::BodyPose;
use super::collisions::{checked, deepest, Obstacle, Penetration};
use super::finding::WorkerFinding;
use super::posture_note::PostureNote;
use super::settings::WorkerSettings;
use super::step_note::{StepCause, StepNote};
use crate::series_cap::SeriesCap;
use crate::workcell::HandRecord;
use glam::DVec3;
use pliant_core::kinematics::Pose;
use pliant_core::{Model, State};
use pliant_worker::reba::RebaScore;
use pliant_worker::rula::RulaScore;
use pliant_worker::scores::PostureScores;
use pliant_worker::{
    body, capsules, describe_step, reach_step, reach_turn, score_posture, walk_step, Body, Manikin,
    Placement, Posture, PostureClass, ScoreOptions, Seat, Segment, Side, TrunkAngles, WorkerError,
    CAPSULE_COUNT,
};
use serde::Serialize;

/// A hand target farther than this from the grip centre is out of reach \[m\] (1 mm: the
/// inverse kinematics reaches targets within reach to well under 0.1 mm).
pub const REACH_TOLERANCE: f64 = 1e-3;

/// The steps kept for the verdict and the summary (the first ones; all are counted).
pub const MAX_STEP_NOTES: usize = 100;

/// How many times a step that would put the legs into a part or hose is halved before
/// the worker keeps the feet instead.
const STEP_HALVINGS: usize = 3;

/// One posed instant, a row of `worker.csv`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct WorkerSample {
    pub time: f64,
    /// Per arm (right, left): the workcell hand it follows and its reach residual \[m\].
    pub hand: [Option<usize>; 2],
    pub residual: [Option<f64>; 2],
    pub rula: u8,
    pub reba: u8,
    /// Trunk flexion, lateral bending, twist; neck flexion \[rad\].
    pub trunk_flexion: f64,
    pub trunk_lateral: f64,
    pub trunk_twist: f64,
    pub neck_flexion: f64,
    /// Per arm: upper arm flexion and elbow flexion \[rad\].
    pub upper_arm: [f64; 2],
    pub elbow: [f64; 2],
    /// The deepest body collision at this instant \[m\] (0: none).
    pub collision_depth: f64,
    /// The posture class, whose rows judge the hand forces until the next instant.
    pub posture_class: PostureClass,
}

/// An arm's worst reach.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ReachRecord {
    /// Largest residual met \[m\], when, and the hand whose target it was.
    pub worst: f64,
    pub time: f64,
    pub hand: Option<usize>,
    /// First and last posed instants out of reach \[s\].
    pub first_out: Option<f64>,
    pub last_out: Option<f64>,
}

/// A body segment inside a part or a hose.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BodyCollision {
    pub segment: String,
    /// The part's or hose's name.
    pub part: String,
    /// "part" or "hose".
    pub obstacle: &'static str,
    #[serde(skip)]
    with: Obstacle,
    /// Deepest penetration \[m\] and when; first and last posed instants inside \[s\].
    pub depth: f64,
    pub time: f64,
    pub first_time: f64,
    pub last_time: f64,
}

/// A score at its worst and when.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ScoreAt<S> {
    pub score: S,
    pub time: f64,
}

/// What the worker did over a study, for the verdict, `summary.json` and the report
/// (the time series stays with the track: [`WorkerTrack::series`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkerSummary {
    /// "the 5th-percentile woman".
    pub who: String,
    pub body: Body,
    /// The seat of a seated worker (`None`: standing).
    pub seat: Option<Seat>,
    /// Where the worker stood (`None`: never placed — no hand acted under an automatic
    /// placement).
    pub placement: Option<Placement>,
    pub instants: u64,
    /// Right arm, then left.
    pub reach: [ReachRecord; 2],
    pub collisions: Vec<BodyCollision>,
    pub worst_rula: Option<ScoreAt<RulaScore>>,
    pub worst_reba: Option<ScoreAt<RebaScore>>,
    /// The posture at the worst RULA score (the report's picture).
    pub worst_posture: Option<Posture>,
    /// Every part's pose at that instant (the identity for a part that stands still), so
    /// that the picture draws a moving part where it was.
    #[serde(skip)]
    pub worst_part_poses: Vec<Pose>,
    /// Posed instants per posture class: upright, bent trunk, arms above shoulder,
    /// sitting, sitting with bent trunk.
    pub class_instants: ClassInstants,
    /// The first [`MAX_STEP_NOTES`] steps the worker took, and how many in all.
    pub steps: Vec<StepNote>,
    pub step_count: u64,
    pub decide: bool,
}

/// How many posed instants the worker spent in each posture class.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ClassInstants {
    pub upright: u64,
    pub bent_trunk: u64,
    pub arms_above_shoulder: u64,
    pub sitting: u64,
    pub sitting_bent_trunk: u64,
}

/// The manikin at its last posed instant (what the live viewer draws).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkerNow {
    /// When it was posed \[s\].
    pub time: f64,
    /// Where it stands, and how many steps it took up to now.
    pub placement: Placement,
    pub steps: u64,
    pub posture: Posture,
    /// Per arm (right, left): the workcell hand it follows.
    pub hand: [Option<usize>; 2],
    pub scores: PostureScores,
    pub class: PostureClass,
    /// Per capsule, in [`capsules()`]' order: the deepest penetration at this instant.
    pub contacts: [Option<Penetration>; CAPSULE_COUNT],
}

/// The worker's running account.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkerTrack {
    settings: WorkerSettings,
    body: Body,
    manikin: Option<Manikin>,
    /// Where the worker was first placed: a step to reach goes at most one step from it.
    home: Option<Placement>,
    steps: Vec<StepNote>,
    step_count: u64,
    next_time: f64,
    instants: u64,
    reach: [ReachRecord; 2],
    collisions: Vec<BodyCollision>,
    worst_rula: Option<ScoreAt<RulaScore>>,
    worst_reba: Option<ScoreAt<RebaScore>>,
    worst_posture: Option<Posture>,
    worst_part_poses: Vec<Pose>,
    /// The last posed instant; its class chooses the force limits' rows (SPEC E2).
    now: Option<WorkerNow>,
    /// A VR user's body posing the worker (the last [`crate::Input::WorkerPose`]).
    body_pose: Option<BodyPose>,
    /// Posed instants per class, in the order of [`PostureClass::ALL`].
    class_instants: [u64; PostureClass::ALL.len()],
    /// The hand each arm followed at the last posed instant (right, left).
    arm_of: [Option<usize>; 2],
    series: Vec<WorkerSample>,
    /// Keeps the series within [`crate::series_cap::MAX_SERIES_BYTES`] in a session of
    /// any length (the worst scores and deepest collision are kept apart anyway).
    cap: SeriesCap,
}

impl WorkerTrack {
    /// A track for `settings`; the body from the built-in anthropometry.
    pub fn new(settings: WorkerSettings) -> Result<WorkerTrack, WorkerError> {
        let body = body(settings.population)?;
        let mut t = WorkerTrack {
            settings,
            body,
            manikin: None,
            home: None,
            steps: Vec::new(),
            step_count: 0,
            next_time: 0.0,
            instants: 0,
            reach: Default::default(),
            collisions: Vec::new(),
            worst_rula: None,
            worst_reba: None,
            worst_posture: None,
            worst_part_poses: Vec::new(),
            now: None,
            body_pose: None,
            class_instants: [0; PostureClass::ALL.len()],
            arm_of: [None; 2],
            series: Vec::with_capacity(1024),
            cap: SeriesCap::of_rows(std::mem::size_of::<WorkerSample>()),
        };
        t.reset();
        Ok(t)
    }

    /// Back to the start of a study.
    pub fn reset(&mut self) {
        self.manikin = match self.settings.stance {
            super::settings::Stance::At(p) => Some(self.settings.manikin(self.body, p)),
            super::settings::Stance::Auto { .. } => None,
        };
        self.home = self.manikin.map(|m| m.placement);
        self.steps.clear();
        self.step_count = 0;
        self.next_time = 0.0;
        self.instants = 0;
        self.reach = Default::default();
        self.collisions.clear();
        self.worst_rula = None;
        self.worst_reba = None;
        self.worst_posture = None;
        self.worst_part_poses.clear();
        self.now = None;
        self.body_pose = None;
        self.class_instants = [0; PostureClass::ALL.len()];
        self.arm_of = [None; 2];
        self.series.clear();
        self.cap.reset();
    }

    pub fn settings(&self) -> &WorkerSettings {
        &self.settings
    }

    /// The manikin as last posed, if it has been.
    pub fn posture(&self) -> Option<&Posture> {
        self.now.as_ref().map(|n| &n.posture)
    }

    /// From now on the worker is posed by a VR user's body: the headset draws the eyes,
    /// each controller its arm (a controller not tracked leaves its arm to the hands).
    pub fn set_body_pose(&mut self, pose: BodyPose) {
        self.body_pose = Some(pose);
    }

    /// The manikin's body (its dimensions and capsule radii).
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// The last posed instant: posture, scores, class and contacts, if posed yet.
    pub fn now(&self) -> Option<&WorkerNow> {
        self.now.as_ref()
    }

    /// The class of the posture as last posed, if it has been: the rows of the push and
    /// pull tables that judge the hand forces now ([`crate::ergonomics::table_posture`]).
    pub fn posture_class(&self) -> Option<PostureClass> {
        self.now.map(|n| n.class)
    }

    /// The posed instants so far (the rows of `worker.csv`).
    pub fn series(&self) -> &[WorkerSample] {
        &self.series
    }

    /// Whether [`Self::observe`] would pose the worker at `time`.
    pub fn due(&self, time: f64) -> bool {
        time + 1e-12 >= self.next_time
    }

    /// Poses the worker for the hands in `records` (hand order; the first two are the
    /// worker's) at `state`'s time, if due; `static_work` whether the work counts as
    /// static for the scores (the ergonomic profile's continuous duty).
    pub fn observe(
        &mut self,
        model: &Model,
        state: &State,
        records: &[HandRecord],
        static_work: bool,
    ) {
        let time = state.time;
        if !self.due(time) {
            return;
        }
        self.next_time = if self.settings.interval > 0.0 {
            time + self.settings.interval
        } else {
            0.0
        };
        let head = self.body_pose.and_then(|b| b.head);
        let mut manikin = match (self.manikin, records.first(), head) {
            (Some(m), _, _) => m,
            (None, Some(first), _) => {
                let p = self.settings.stance.place(first.load.position, &self.body);
                let m = self.settings.manikin(self.body, p);
                self.manikin = Some(m);
                m
            }
            (None, None, Some(h)) => {
                let m = self
                    .settings
                    .manikin(self.body, self.settings.stance.place_under(h));
                self.manikin = Some(m);
                m
            }
            (None, None, None) => return,
        };
        self.home.get_or_insert(manikin.placement);
        let seated = manikin.seat.is_some();
        let walked = head.filter(|_| !seated);
        if let Some(step) = walked.and_then(|h| walk_step(&self.body, &manikin.placement, h.eyes)) {
            let to = Placement {
                position: manikin.placement.position + step,
                ..manikin.placement
            };
            self.take_step(&mut manikin, to, time, StepCause::Walk);
        }
        // the first two hands; the one further to the worker's right to the right arm; a
        // single hand to the arm on its side, but it stays with the arm that held it
        // until it is a quarter shoulder width past the midline
        let mut hand = [None; 2];
        let mut target = [None; 2];
        let mut force = [0.0; 2];
        let lateral = |p: DVec3| manikin.placement.local(p - manikin.placement.position).y;
        let mut picked: [Option<&HandRecord>; 2] = [records.first(), records.get(1)];
        if let [Some(a), Some(b)] = picked {
            if lateral(b.load.position) < lateral(a.load.position) {
                picked = [Some(b), Some(a)];
            }
        } else if let [Some(a), None] = picked {
            let y = lateral(a.load.position);
            let margin = 0.25 * self.body.dims.shoulder_width;
            let left = match self.arm_of {
                [Some(h), _] if h == a.hand => y > margin,
                [_, Some(h)] if h == a.hand => y > -margin,
                _ => y > 0.0,
            };
            if left {
                picked = [None, Some(a)];
            }
        }
        for (i, r) in picked.iter().enumerate() {
            if let Some(r) = r {
                hand[i] = Some(r.hand);
                target[i] = Some(r.load.position);
                force[i] = r.load.force.length();
            }
        }
        self.arm_of = hand;
        if let Some(body) = self.body_pose {
            for (t, controller) in target.iter_mut().zip(body.hands) {
                if controller.is_some() {
                    *t = controller;
                }
            }
        }
        let mut posture = manikin.solve_with_head(target, head);
        if self.settings.steps && head.is_none() && !seated {
            if let Some((to, hand)) = self.reach_step(model, state, &manikin, &posture, hand) {
                self.take_step(&mut manikin, to, time, StepCause::Reach { hand });
                posture = manikin.solve_with_head(target, head);
            } else if let Some(to) = self.return_step(model, state, &manikin, &posture, target) {
                self.take_step(&mut manikin, to, time, StepCause::Return);
                posture = manikin.solve_with_head(target, head);
            }
        }
        let options = ScoreOptions {
            static_or_repeated: static_work,
            ..self.settings.scores
        };
        let scores = score_posture(&posture, force, &options);
        let class = PostureClass::of(&posture, manikin.placement.up);
        self.class_instants[class.index()] += 1;
        let mut deepest_now: f64 = 0.0;
        let mut contacts = [None; CAPSULE_COUNT];
        for (c, contact) in capsules(&self.body, &posture).iter().zip(&mut contacts) {
            if !checked(c.segment) {
                continue;
            }
            *contact = deepest(model, state, c, &target, self.body.dims.hand);
            if let Some(p) = *contact {
                deepest_now = deepest_now.max(p.depth);
                self.note_collision(model, c.segment.name(), p.obstacle, p.depth, time);
            }
        }
        for side in Side::BOTH {
            let i = side.index();
            if hand[i].is_none() {
                continue;
            }
            let r = posture.arms[i].residual;
            let rec = &mut self.reach[i];
            if rec.hand.is_none() || r > rec.worst {
                rec.worst = r;
                rec.time = time;
                rec.hand = hand[i];
            }
            if r > REACH_TOLERANCE {
                rec.first_out.get_or_insert(time);
                rec.last_out = Some(time);
            }
        }
        if self
            .worst_rula
            .is_none_or(|w| scores.rula.grand > w.score.grand)
        {
            self.worst_rula = Some(ScoreAt {
                score: scores.rula,
                time,
            });
            self.worst_posture = Some(posture);
            self.worst_part_poses.clear();
            self.worst_part_poses
                .extend((0..model.environment.parts.len()).map(|k| {
                    model
                        .kinematics
                        .placement_at(k, time, &state.part_moves)
                        .pose
                }));
        }
        if self
            .worst_reba
            .is_none_or(|w| scores.reba.reba > w.score.reba)
        {
            self.worst_reba = Some(ScoreAt {
                score: scores.reba,
                time,
            });
        }
        self.instants += 1;
        if self.cap.take() {
            self.sample(time, hand, &target, &posture, scores, deepest_now, class);
        }
        self.now = Some(WorkerNow {
            time,
            placement: manikin.placement,
            steps: self.step_count,
            posture,
            hand,
            scores,
            class,
            contacts,
        });
    }

    /// The stance a step towards the target of the arm furthest out of reach leads to,
    /// from where the worker was first placed — turned first to face a target more than
    /// [`pliant_worker::TURN_BEARING`] off its facing ([`pliant_worker::reach_turn`]),
    /// then moved by [`pliant_worker::reach_step`] — and that arm's hand; `None` when both
    /// arms reach, neither a turn nor a step helps, the stance is there already, or the
    /// legs would be inside a part or hose at the new stance even after
    /// [`STEP_HALVINGS`] halvings of the step.
    fn reach_step(
        &self,
        model: &Model,
        state: &State,
        manikin: &Manikin,
        posture: &Posture,
        hand: [Option<usize>; 2],
    ) -> Option<(Placement, usize)> {
        let home = self.home?;
        let side = Side::BOTH
            .into_iter()
            .filter(|s| posture.arms[s.index()].residual > REACH_TOLERANCE)
            .max_by(|a, b| {
                posture.arms[a.index()]
                    .residual
                    .total_cmp(&posture.arms[b.index()].residual)
            })?;
        let target = posture.arms[side.index()].target?;
        let turn = reach_turn(&home, target);
        let facing = turn.map_or(home, |angle| home.turned(angle));
        let mut offset = match reach_step(&self.body, &facing, side, target) {
            Some(offset) => offset,
            None if turn.is_some() => DVec3::ZERO,
            None => return None,
        };
        for _ in 0..=STEP_HALVINGS {
            let to = Placement {
                position: home.position + offset,
                ..facing
            };
            if same_stance(&to, &manikin.placement) {
                return None;
            }
            if !self.legs_inside(model, state, &manikin.at(to)) {
                return Some((to, hand[side.index()]?));
            }
            if offset == DVec3::ZERO {
                return None;
            }
            offset *= 0.5;
        }
        None
    }

    /// The stance where the worker was first placed, to step back to once every arm
    /// reaches its target from there (the inverse kinematics at that stance leaves each
    /// within [`REACH_TOLERANCE`]) and the legs would not be inside a part or hose there;
    /// `None` while the worker stands there, or an arm out of reach at the stance it
    /// stepped to still needs the step. Taken only when every arm reaches where it
    /// stands, so the worker never steps back into a stance it would have to leave again.
    fn return_step(
        &self,
        model: &Model,
        state: &State,
        manikin: &Manikin,
        posture: &Posture,
        target: [Option<DVec3>; 2],
    ) -> Option<Placement> {
        let home = self.home?;
        let reaches = |p: &Posture| p.arms.iter().all(|a| !(a.residual > REACH_TOLERANCE));
        if same_stance(&home, &manikin.placement) || !reaches(posture) {
            return None;
        }
        let placed = manikin.at(home);
        (reaches(&placed.solve(target)) && !self.legs_inside(model, state, &placed)).then_some(home)
    }

    /// Whether the pelvis, a thigh or a shank of `manikin` standing upright is inside a
    /// part or a hose.
    fn legs_inside(&self, model: &Model, state: &State, manikin: &Manikin) -> bool {
        let upright = manikin.posture(TrunkAngles::default(), [None; 2]);
        capsules(&self.body, &upright).iter().any(|c| {
            matches!(
                c.segment,
                Segment::Pelvis | Segment::Thigh(_) | Segment::Shank(_)
            ) && deepest(model, state, c, &[None; 2], self.body.dims.hand).is_some()
        })
    }

    /// Moves `manikin` to the stance `to` (a step along the floor, a turn about the
    /// vertical, or both) and notes the step.
    fn take_step(&mut self, manikin: &mut Manikin, to: Placement, time: f64, cause: StepCause) {
        let from = manikin.placement;
        manikin.placement = to;
        self.manikin = Some(*manikin);
        self.step_count += 1;
        if self.steps.len() < MAX_STEP_NOTES {
            self.steps.push(StepNote {
                who: self.settings.population.describe(),
                time,
                length: (to.position - from.position).length(),
                turn: from.turn_to(&to),
                words: describe_step(&from, &to),
                from: from.position,
                to: to.position,
                cause,
            });
        }
    }

    /// Adds the instant to the series, thinning it when full (the rows of the highest
    /// RULA and REBA scores and the deepest collision kept).
    #[allow(clippy::too_many_arguments)]
    fn sample(
        &mut self,
        time: f64,
        hand: [Option<usize>; 2],
        target: &[Option<DVec3>; 2],
        posture: &Posture,
        scores: PostureScores,
        deepest_now: f64,
        posture_class: PostureClass,
    ) {
        let arm = |i: usize| &posture.arms[i];
        self.series.push(WorkerSample {
            time,
            hand,
            residual: [0, 1].map(|i| target[i].map(|_| arm(i).residual)),
            rula: scores.rula.grand,
            reba: scores.reba.reba,
            trunk_flexion: posture.trunk.flexion,
            trunk_lateral: posture.trunk.lateral,
            trunk_twist: posture.trunk.twist,
            neck_flexion: posture.neck_flexion,
            upper_arm: [0, 1].map(|i| arm(i).flexion),
            elbow: [0, 1].map(|i| arm(i).elbow_flexion),
            collision_depth: deepest_now,
            posture_class,
        });
        let worst = |key: fn(&WorkerSample) -> f64| {
            (0..self.series.len())
                .max_by(|&a, &b| key(&self.series[a]).total_cmp(&key(&self.series[b])))
        };
        if self.series.len() >= self.cap.max_rows() {
            let kept = [
                worst(|s| s.rula as f64),
                worst(|s| s.reba as f64),
                worst(|s| s.collision_depth),
            ];
            if let Some(keep) = self
                .cap
                .thin(self.series.len(), |i| kept.contains(&Some(i)))
            {
                let mut k = keep.iter();
                self.series.retain(|_| k.next().copied().unwrap_or(true));
            }
        }
    }

    fn note_collision(
        &mut self,
        model: &Model,
        segment: String,
        with: Obstacle,
        depth: f64,
        time: f64,
    ) {
        let found = self
            .collisions
            .iter_mut()
            .find(|c| c.with == with && c.segment == segment);
        match found {
            Some(c) => {
                if depth > c.depth {
                    c.depth = depth;
                    c.time = time;
                }
                c.last_time = time;
            }
            None => self.collisions.push(BodyCollision {
                segment,
                part: with.name(model),
                obstacle: with.kind(),
                with,
                depth,
                time,
                first_time: time,
                last_time: time,
            }),
        }
    }

    /// The account so far.
    pub fn summary(&self) -> WorkerSummary {
        WorkerSummary {
            who: self.settings.population.describe(),
            body: self.body,
            seat: self.settings.seat,
            placement: self.manikin.map(|m| m.placement),
            instants: self.instants,
            reach: self.reach,
            collisions: self.collisions.clone(),
            worst_rula: self.worst_rula,
            worst_reba: self.worst_reba,
            worst_posture: self.worst_posture,
            worst_part_poses: self.worst_part_poses.clone(),
            class_instants: ClassInstants {
                upright: self.class_instants[PostureClass::Upright.index()],
                bent_trunk: self.class_instants[PostureClass::BentTrunk.index()],
                arms_above_shoulder: self.class_instants[PostureClass::ArmsAboveShoulder.index()],
                sitting: self.class_instants[PostureClass::Sitting.index()],
                sitting_bent_trunk: self.class_instants[PostureClass::SittingBentTrunk.index()],
            },
            steps: self.steps.clone(),
            step_count: self.step_count,
            decide: self.settings.decide,
        }
    }
}

impl WorkerSummary {
    /// What the worker could not do: each arm's worst reach beyond
    /// [`REACH_TOLERANCE`], each segment's deepest collision with each part.
    pub fn findings(&self) -> Vec<WorkerFinding> {
        let mut out = Vec::new();
        for side in Side::BOTH {
            let r = &self.reach[side.index()];
            if let (Some(first), Some(last), Some(hand)) = (r.first_out, r.last_out, r.hand) {
                out.push(WorkerFinding::OutOfReach {
                    who: self.who.clone(),
                    arm: side.name(),
                    hand,
                    distance: r.worst,
                    time: r.time,
                    first_time: first,
                    last_time: last,
                });
            }
        }
        for c in &self.collisions {
            out.push(WorkerFinding::Collision {
                who: self.who.clone(),
                segment: c.segment.clone(),
                part: c.part.clone(),
                obstacle: c.obstacle,
                depth: c.depth,
                time: c.time,
                first_time: c.first_time,
                last_time: c.last_time,
            });
        }
        out
    }

    /// The worst posture scores and when, if the worker was posed.
    pub fn posture_note(&self) -> Option<PostureNote> {
        Some(PostureNote {
            who: self.who.clone(),
            rula: self.worst_rula?,
            reba: self.worst_reba?,
        })
    }
}

/// Whether two stances are the same to 1 nm and 1 nrad (a step or turn smaller than that
/// is none).
fn same_stance(a: &Placement, b: &Placement) -> bool {
    (a.position - b.position).length() < 1e-9 && (a.forward - b.forward).length() < 1e-9
}
