//! Hands (SPEC I1, I2): the grabbed beam follows the hand rigidly, and the reported hand
//! load equals the exact load of the elastic rest of the hose.

use glam::DVec3;
use pliant_assembly::{
    Action, HandRecord, MovePath, NodeRef, Observer, Rotation, Runner, Timeline,
};
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};

const N: usize = 20;
const L: f64 = 0.5;

fn model() -> Model {
    let nodes = (0..=N)
        .map(|i| DVec3::new(L * i as f64 / N as f64, 0.0, 0.0))
        .collect();
    let hose = HoseSpec {
        name: "h".into(),
        material: Material::isotropic(12e6, 0.49, 940.0),
        nodes,
        sections: vec![Section::new(0.010, 0.016)],
        normal_hint: Some(DVec3::Y),
    };
    let settings = SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 20.0,
        ..Default::default()
    };
    Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: vec![],
        settings,
    })
    .unwrap()
}

#[derive(Default)]
struct LastHands(Vec<HandRecord>);
impl Observer for LastHands {
    fn wants_state(&self, _t: f64) -> bool {
        true
    }
    fn on_hands(&mut self, _t: f64, hands: &[HandRecord]) {
        self.0 = hands.to_vec();
    }
}

fn run(actions: Vec<Action>) -> (Model, State, LastHands) {
    run_observed(actions)
}

fn run_observed<O: Observer + Default>(actions: Vec<Action>) -> (Model, State, O) {
    let model = model();
    let mut state = State::at_rest(&model);
    let mut obs = O::default();
    Runner::new(&model)
        .run(&Timeline { actions }, &mut state, &mut obs)
        .unwrap();
    (model, state, obs)
}

/// Node 0 fixed, the hand grabbing at `at` and pulling it `dl` along x over 0.5 s.
fn pull_along_x(at: DVec3, dl: f64) -> Vec<Action> {
    vec![
        fix0(),
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at,
        },
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::By(vec![DVec3::new(dl, 0.0, 0.0)])),
            rotation: None,
            duration: 0.5,
            speed: None,
            spline: false,
            wait: true,
        },
    ]
}

fn fix0() -> Action {
    Action::Fix {
        node: NodeRef { hose: 0, node: 0 },
    }
}

#[test]
fn pulling_hand_feels_the_axial_stiffness_of_the_free_length() {
    let dl = 0.005;
    let grab_at = DVec3::new(L - 0.006, 0.001, 0.0); // nearest beam: the last one
    let mut actions = pull_along_x(grab_at, dl);
    actions.push(Action::Run { duration: 1.0 });
    let (model, state, obs) = run(actions);
    let free_length = L - L / N as f64; // the last beam moves rigidly with the hand
    let ea = model.elements[0].axial_stiffness_tension;
    let exact = ea * dl / free_length;
    let f = obs.0[0].load.force;
    assert!(
        (f.x - exact).abs() < 1e-3 * exact,
        "hand force {f:?} vs {exact} N"
    );
    assert!(f.y.abs() < 1e-6 * exact && f.z.abs() < 1e-6 * exact);
    // the grabbed nodes moved with the hand; the fixed end did not
    assert!((state.x[N].x - (L + dl)).abs() < 1e-12);
    assert!(state.x[0].length() < 1e-15);
    // a force towards the hose end the hand holds counts as a push (the push-on case;
    // the worker's position is not modelled yet, see HandLoad::direction)
    let a = obs.0[0].assessment.unwrap();
    assert_eq!(format!("{:?}", a.force.kind), "Push");
    assert!((a.force.magnitude - f.length()).abs() < 1e-12);
}

#[test]
fn twisting_hand_feels_the_torsional_stiffness() {
    let phi = 0.3;
    let (model, _, obs) = run(vec![
        fix0(),
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at: DVec3::new(L - 0.006, 0.0, 0.0),
        },
        Action::MoveHand {
            hand: 0,
            path: None,
            rotation: Some(Rotation {
                axis: DVec3::X,
                angle: phi,
            }),
            duration: 0.5,
            speed: None,
            spline: false,
            wait: true,
        },
        Action::Run { duration: 1.0 },
    ]);
    let gj = model.elements[0].torsion_stiffness;
    let exact = gj * phi / (L - L / N as f64);
    let t = obs.0[0].load.torque;
    assert!(
        (t.x - exact).abs() < 1e-3 * exact,
        "hand torque {t:?} vs {exact}"
    );
}

#[test]
fn two_hands_pull_with_equal_and_opposite_forces() {
    let dl = 0.004;
    let (_, _, obs) = run(vec![
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at: DVec3::new(0.006, 0.0, 0.0),
        },
        Action::Grab {
            grip: Default::default(),
            hand: 1,
            at: DVec3::new(L - 0.006, 0.0, 0.0),
        },
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::By(vec![DVec3::new(-dl, 0.0, 0.0)])),
            rotation: None,
            duration: 0.5,
            speed: None,
            spline: false,
            wait: false,
        },
        Action::MoveHand {
            hand: 1,
            path: Some(MovePath::By(vec![DVec3::new(dl, 0.0, 0.0)])),
            rotation: None,
            duration: 0.5,
            speed: None,
            spline: false,
            wait: true,
        },
        Action::Run { duration: 1.0 },
    ]);
    let (f0, f1) = (obs.0[0].load.force, obs.0[1].load.force);
    assert!((f0 + f1).length() < 1e-6 * f1.length(), "{f0:?} {f1:?}");
    assert!(f1.x > 0.0 && f0.x < 0.0);
}

#[test]
fn released_hand_applies_nothing_and_hose_relaxes() {
    let (model, state, _) = run(vec![
        fix0(),
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at: DVec3::new(L, 0.0, 0.0),
        },
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::By(vec![DVec3::new(0.0, 0.05, 0.0)])),
            rotation: None,
            duration: 0.5,
            speed: None,
            spline: false,
            wait: true,
        },
        Action::ReleaseHand { hand: 0 },
        Action::Settle {
            kinetic_energy_threshold: 1e-12,
            force_tolerance: 1e-3,
            moment_tolerance: 1e-4,
            max_duration: 20.0,
            finish: pliant_assembly::SettleFinish::Dynamic,
        },
    ]);
    // springs back to straight
    assert!(state.x[N].y.abs() < 1e-4, "tip y {}", state.x[N].y);
    assert!(!state.held[N] && !state.held[N - 1]);
    let _ = model;
}

/// Records the hand position at every recorded state.
#[derive(Default)]
struct HandPath(Vec<(f64, DVec3)>);
impl Observer for HandPath {
    fn wants_state(&self, _t: f64) -> bool {
        true
    }
    fn on_hands(&mut self, t: f64, hands: &[HandRecord]) {
        if let Some(r) = hands.first() {
            self.0.push((t, r.load.position));
        }
    }
}

#[test]
fn hand_moves_at_a_given_speed_along_a_spline() {
    let model = model();
    let mut state = State::at_rest(&model);
    let mut obs = HandPath::default();
    let start = DVec3::new(L, 0.0, 0.0);
    let via = DVec3::new(0.05, 0.05, 0.0);
    let end = DVec3::new(0.1, 0.0, 0.0);
    let actions = vec![
        fix0(),
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at: start,
        },
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::By(vec![via, end])),
            rotation: None,
            duration: 0.0,
            speed: Some(0.1),
            spline: true,
            wait: true,
        },
    ];
    Runner::new(&model)
        .run(&Timeline { actions }, &mut state, &mut obs)
        .unwrap();
    let (t_end, p_end) = *obs.0.last().unwrap();
    assert!(
        (p_end - (start + end)).length() < 1e-9,
        "ends at the last waypoint"
    );
    // duration = spline length / speed: a little more than the polyline's 0.1414 m
    let polyline = via.length() + (end - via).length();
    assert!(
        t_end > polyline / 0.1 && t_end < 1.2 * polyline / 0.1,
        "took {t_end} s"
    );
    // passes through the middle waypoint, but not along the straight chords
    let nearest = obs
        .0
        .iter()
        .map(|(_, p)| (*p - (start + via)).length())
        .fold(f64::INFINITY, f64::min);
    assert!(nearest < 2e-3, "misses the waypoint by {nearest} m");
    let to_segment = |p: DVec3, a: DVec3, b: DVec3| {
        let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
        (a + t * (b - a) - p).length()
    };
    let off_chords = obs
        .0
        .iter()
        .map(|(_, p)| {
            to_segment(*p, start, start + via).min(to_segment(*p, start + via, start + end))
        })
        .fold(0.0, f64::max);
    assert!(
        off_chords > 2e-3,
        "a spline rounds the corner, leaving the straight chords: {off_chords} m"
    );
}

/// Interactive input: `set_pose` makes the held nodes follow a pose set directly (held
/// until the next call), with the nodes' offsets from the hand kept rigid.
#[test]
fn set_pose_moves_held_nodes_to_the_target_pose() {
    use glam::DQuat;
    use pliant_assembly::Hand;
    let model = model();
    let mut state = State::at_rest(&model);
    let grab = DVec3::new(L, 0.0, 0.0);
    let mut hand = Hand::grab(&model, &mut state, grab).unwrap();
    let target = grab + DVec3::new(0.0, 0.01, 0.0);
    hand.set_pose(target, DQuat::IDENTITY);
    assert_eq!(hand.pose_at(state.time + 1.0), (target, DQuat::IDENTITY));
    for _ in 0..200 {
        let t = state.time + model.time_step;
        hand.update(&mut state, t);
        pliant_core::integrators::explicit::step(&model, &mut state);
    }
    let tip = state.x[N];
    assert!(
        (tip - target).length() < 1e-6,
        "tip {tip:?} target {target:?}"
    );
    let load = hand.load(&model, &state);
    assert!(load.force.length() > 0.0 && load.force.is_finite());
    assert!(!hand.moving(state.time));
}

/// Tip stretch x − L of the last node after each step, with the step's time.
#[derive(Default)]
struct TipTrace(Vec<(f64, f64)>);
impl Observer for TipTrace {
    fn wants_state(&self, _t: f64) -> bool {
        true
    }
    fn on_state(&mut self, _model: &Model, state: &State) {
        self.0.push((state.time, state.x[N].x - L));
    }
}

/// A hand opens over `RELEASE_TIME`: the force it held the hose with falls smoothly to
/// zero (1 − (3s² − 2s³)), so a stretched hose shortens with it instead of springing back
/// past its rest length as it does when the force vanishes within one step.
#[test]
fn a_hand_opens_over_the_release_time() {
    use pliant_assembly::hand::RELEASE_TIME;
    let dl = 0.005;
    let mut actions = pull_along_x(DVec3::new(L - 0.006, 0.0, 0.0), dl);
    actions.extend([
        Action::Run { duration: 0.5 },
        Action::ReleaseHand { hand: 0 },
        Action::Run {
            duration: 2.0 * RELEASE_TIME,
        },
    ]);
    let (_, state, trace): (_, _, TipTrace) = run_observed(actions);
    let released = 1.0;
    let at = |t: f64| {
        trace
            .0
            .iter()
            .find(|(time, _)| *time >= t)
            .map(|&(_, s)| s)
            .unwrap()
    };
    assert!((at(released - 0.01) - dl).abs() < 0.01 * dl);
    // half-way through the opening the hand still holds half its force: the hose, whose
    // axial period (4L/c ≈ 18 ms) is short against the opening, is stretched about half
    let half = at(released + 0.5 * RELEASE_TIME) / dl;
    assert!((0.35..0.65).contains(&half), "stretch {half} × dl half-way");
    // it never springs back past its rest length (an instant release swings to ≈ −0.5 dl)
    let least = trace
        .0
        .iter()
        .filter(|(t, _)| *t > released)
        .map(|&(_, s)| s)
        .fold(f64::INFINITY, f64::min);
    assert!(least > -0.1 * dl, "least stretch {} × dl", least / dl);
    // and once open, nothing is left on the node
    assert!(state
        .loads
        .iter()
        .all(|(_, c)| c.node() != N - 1 && c.node() != N));
}
