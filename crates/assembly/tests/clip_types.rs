//! Fixings by type. Each clip type's free directions (in its VEC frame:
//! Y along the hose, Z against the mounting direction, X = Y × Z) carry no reaction and its
//! fixed ones carry the load — checked by static equilibrium of a hose seated in the clip
//! ([`ClipSpec::seat_hold`], the load case the runtime puts on a seated node). The sliding
//! guide's friction is Coulomb, μ N.

use glam::{DQuat, DVec3};
use pliant_assembly::clip::{ClipKind, ClipSpec};
use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::{Model, SimSettings, State};

const N: usize = 12; // elements
const F: f64 = 10.0; // test force [N]
const M: f64 = 0.5; // test moment [N m]

/// Library hose 3, 0.3 m along global X, no gravity.
fn model() -> Model {
    let mut model = pliant_testkit::hose3_along_x(
        N,
        SimSettings {
            gravity: DVec3::ZERO,
            damping_mass: 4.0,
            ..Default::default()
        },
    );
    model.hose_contact.active = false;
    model
}

/// The bending modulus of hose 3: E_b = 4 E_t E_c / (√E_t + √E_c)².
fn bending_modulus() -> f64 {
    let (et, ec) = (6.9442e6f64, 8.6913e6f64);
    4.0 * et * ec / (et.sqrt() + ec.sqrt()).powi(2)
}

/// A clip of `kind` seating the hose's last node: hose along its Y (global X), opening
/// (its Z) along global Z, so its X is global −Y.
fn clip(kind: ClipKind, friction: f64) -> ClipSpec {
    ClipSpec::new(
        DVec3::new(0.3, 0.0, 0.0),
        DVec3::Z,
        DVec3::X,
        0.030,
        0.036,
        50.0,
    )
    .unwrap()
    .with_fixing(kind, friction, None)
    .unwrap()
}

/// The clip's axes X, Y, Z in global axes.
fn axes(c: &ClipSpec) -> [DVec3; 3] {
    let r = glam::DMat3::from_quat(c.frame());
    [r.x_axis, r.y_axis, r.z_axis]
}

fn load(state: &mut State, node: usize, force: DVec3, moment: DVec3) {
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node,
        force,
        moment,
        ramp: None,
    }));
}

/// The hose seated in the clip at its tip (and, with `clamped`, clamped at its root),
/// loaded at the tip; the static solution.
fn solve(c: &ClipSpec, clamped: bool, force: DVec3, moment: DVec3) -> State {
    let model = model();
    let mut state = State::at_rest(&model);
    if clamped {
        state.loads.add(LoadCase::Fix(Fix {
            node: 0,
            position: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
        }));
    }
    state.loads.add(c.seat_hold(N, state.x[N], state.q[N]));
    load(&mut state, N, force, moment);
    let report = StaticSolver::new(&model)
        .unwrap()
        .solve(&model, &mut state)
        .unwrap();
    assert!(report.converged, "{report:?}");
    state
}

#[test]
fn the_vec_frame_follows_orientation_and_opening() {
    let [x, y, z] = axes(&clip(ClipKind::Fixed, 0.0));
    assert!((y - DVec3::X).length() < 1e-15, "Y {y}");
    assert!((z - DVec3::Z).length() < 1e-15, "Z {z}");
    assert!((x + DVec3::Y).length() < 1e-15, "X {x}");
}

/// Free directions: with the root clamped, a tip load along a free direction leaves the
/// clip's reaction along it at round-off and the root carries all of it. Fixed
/// directions: the hose held by the clip alone, the clip's reaction balances the load
/// exactly (static equilibrium).
#[test]
fn free_directions_carry_nothing_and_fixed_ones_carry_the_load() {
    for kind in [
        ClipKind::Fixed,
        ClipKind::Rotating,
        ClipKind::Sliding,
        ClipKind::CableTie,
    ] {
        let c = clip(kind, 0.0);
        let e = axes(&c);
        for k in 0..3 {
            // translation along e[k]
            let f = e[k] * F;
            if kind.free_translation()[k] {
                let s = solve(&c, true, f, DVec3::ZERO);
                let clip_part = s.reaction_force[N].dot(e[k]);
                assert!(
                    clip_part.abs() <= 1e-9 * F,
                    "{kind:?} T{k}: clip {clip_part}"
                );
                let root = s.reaction_force[0].dot(e[k]);
                assert!((root + F).abs() <= 1e-6 * F, "{kind:?} T{k}: root {root}");
            } else {
                let s = solve(&c, false, f, DVec3::ZERO);
                let r = s.reaction_force[N];
                assert!((r + f).length() <= 1e-6 * F, "{kind:?} T{k}: {r} vs {f}");
            }
            // rotation about e[k]
            let m = e[k] * M;
            if kind.free_rotation()[k] {
                // a small moment: the hose turns at the clip as a propped cantilever's
                // pinned end does, θ = M L / (4 EI) (linear beam theory), the clip's
                // translations holding it
                let m = m * 0.02;
                let s = solve(&c, true, DVec3::ZERO, m);
                let clip_part = s.reaction_moment[N].dot(e[k]);
                assert!(
                    clip_part.abs() <= 1e-9 * M,
                    "{kind:?} R{k}: clip {clip_part}"
                );
                let q0 = State::at_rest(&model()).q[N];
                let turned = pliant_core::math::log_map(s.q[N] * q0.conjugate()).dot(e[k]);
                let ei = bending_modulus() * std::f64::consts::PI / 64.0
                    * (0.035f64.powi(4) - 0.027f64.powi(4));
                let theta = 0.02 * M * 0.3 / (4.0 * ei);
                println!(
                    "{kind:?} R{k}: turned {turned:.6} rad, beam theory {theta:.6} (ratio {:.5})",
                    turned / theta
                );
                assert!(
                    (turned / theta - 1.0).abs() <= 0.01,
                    "{kind:?} R{k}: {turned} vs {theta}"
                );
            } else {
                let s = solve(&c, false, DVec3::ZERO, m);
                let r = s.reaction_moment[N];
                assert!((r + m).length() <= 1e-6 * M, "{kind:?} R{k}: {r} vs {m}");
            }
        }
    }
}

/// The sliding guide holds an axial pull below μ N by static friction (reaction = the
/// pull, exactly), and above it slides with the friction force μ N.
#[test]
fn the_sliding_guide_resists_with_coulomb_friction() {
    let mu = 0.3;
    let c = clip(ClipKind::Sliding, mu);
    let [x, y, _] = axes(&c);
    let p = 20.0; // pressing across the guide (its X): N = 20 N, μ N = 6 N
                  // sticking: 5 N along the hose is held
    let s = solve(&c, false, x * p + y * 5.0, DVec3::ZERO);
    let r = s.reaction_force[N];
    assert!((r.dot(y) + 5.0).abs() <= 1e-6 * p, "stick {r}");
    assert!((r.dot(x) + p).abs() <= 1e-6 * p, "normal {r}");
    // sliding: 8 N along the hose exceeds μ N; over implicit steps the hose slides and the
    // guide's friction is μ N
    let model = model();
    let mut state = State::at_rest(&model);
    state.loads.add(c.seat_hold(N, state.x[N], state.q[N]));
    load(&mut state, N, x * p + y * 8.0, DVec3::ZERO);
    let mut solver = ImplicitSolver::new(
        &model,
        ImplicitOptions {
            time_step: 1e-3,
            ..Default::default()
        },
    )
    .unwrap();
    let start = state.x[N].dot(y);
    let mut worst: f64 = 0.0;
    for step in 0..200 {
        solver.step(&model, &mut state).unwrap();
        if step >= 50 {
            let r = state.reaction_force[N];
            let (normal, friction) = (r.dot(x).abs(), r.dot(y).abs());
            worst = worst.max((friction - mu * normal).abs() / (mu * normal));
        }
    }
    let slid = state.x[N].dot(y) - start;
    println!("slid {slid} m, worst |friction − μN|/μN = {worst:e}");
    assert!(slid > 0.01, "the hose did not slide: {slid}");
    assert!(worst <= 1e-3, "{worst}");
}

#[test]
fn friction_only_on_a_sliding_guide() {
    let base = ClipSpec::new(DVec3::ZERO, DVec3::Z, DVec3::X, 0.03, 0.036, 50.0).unwrap();
    let err = base
        .with_fixing(ClipKind::Fixed, 0.3, None)
        .unwrap_err()
        .to_string();
    assert!(err.contains("friction"), "{err}");
    assert!(base.with_fixing(ClipKind::Sliding, -0.1, None).is_err());
    let err = base
        .with_fixing(ClipKind::Rotating, 0.0, Some(0.0))
        .unwrap_err()
        .to_string();
    assert!(err.contains("holding_force"), "{err}");
}

/// Hose 3 lying across the seat of a clip at x = 162.5 mm (opening +Z, hose along X),
/// seated after 0.05 s, then pulled up with `pull` \[N\] on its node 7 (the seated node) for
/// 0.05 s (a hose pulled loose flies off: the run stops before it is fast); the run's
/// final state and the clip's report.
fn seat_and_pull(spec: ClipSpec, pull: f64) -> (State, pliant_assembly::FastenerReport) {
    use pliant_assembly::{Action, ClipSite, NoObserver, NodeRef, Runner, Timeline};
    let model = pliant_testkit::hose3_along_x(20, SimSettings::default());
    let mut state = State::at_rest(&model);
    let site = ClipSite {
        name: "clip".into(),
        spec,
        hose: 0,
        part: None,
        by_hand: false,
    };
    let timeline = Timeline {
        actions: vec![
            Action::Run { duration: 0.05 },
            Action::Load {
                node: NodeRef { hose: 0, node: 7 },
                force: DVec3::Z * pull,
                moment: DVec3::ZERO,
                ramp: 0.0,
                name: None,
            },
            Action::Run { duration: 0.05 },
        ],
    };
    let summary = Runner::new(&model)
        .with_fasteners(vec![], vec![site])
        .run(&timeline, &mut state, &mut NoObserver)
        .unwrap();
    (state, summary.fasteners[0].clone())
}

fn clip_at_the_seat(kind: ClipKind, holding: Option<f64>) -> ClipSpec {
    let mu = if kind == ClipKind::Sliding { 0.3 } else { 0.0 };
    ClipSpec::new(
        DVec3::new(0.1625, 0.0, 0.0),
        DVec3::Z,
        DVec3::X,
        0.030,
        0.036,
        40.0,
    )
    .and_then(|c| c.with_fixing(kind, mu, holding))
    .unwrap()
}

/// At run time (explicit solver, the workcell's runner): hose 3 lying across the seat of
/// a rotating clip and of a sliding guide seats on its own (no hand: released in the seat),
/// the seated node is held by a support (not a fix), and the run stays finite and in the
/// seat.
#[test]
fn a_hose_released_in_the_seat_is_held_by_a_support() {
    for kind in [ClipKind::Rotating, ClipKind::Sliding] {
        let spec = clip_at_the_seat(kind, None);
        let (state, report) = seat_and_pull(spec, 0.0);
        assert!(report.assembled, "{kind:?}: {report:?}");
        let kinds: Vec<bool> = state
            .loads
            .iter()
            .filter(|(_, c)| !matches!(c, LoadCase::DeadLoad(_)))
            .map(|(_, c)| matches!(c, LoadCase::Support(_)))
            .collect();
        assert_eq!(kinds, [true], "{kind:?}");
        assert!(state.x.iter().all(|x| x.is_finite()), "{kind:?}");
        let centre = state
            .x
            .windows(2)
            .find_map(|w| spec.centre_on_segment(w[0], w[1]))
            .expect("the hose crosses the clip");
        let s = spec.opening_coordinate(centre);
        assert!(
            s.abs() <= 0.1 * spec.opening_distance(),
            "{kind:?}: s = {s}"
        );
    }
}

/// Pull-out force 60 N: a seated hose pulled out (along the opening) with 30 N stays
/// seated; with 100 N — more than the holding force and the snap force 40 N — it comes
/// loose and leaves the clip. A fixed clip (fix) and a rotating one (support) alike.
#[test]
fn a_hose_pulled_harder_than_the_holding_force_comes_loose() {
    for kind in [ClipKind::Fixed, ClipKind::Rotating] {
        let spec = clip_at_the_seat(kind, Some(60.0));
        let (_, held) = seat_and_pull(spec, 30.0);
        assert!(held.assembled, "{kind:?} 30 N: {held:?}");
        let (state, loose) = seat_and_pull(spec, 100.0);
        assert!(!loose.assembled, "{kind:?} 100 N: {loose:?}");
        let holds = state
            .loads
            .iter()
            .any(|(_, c)| matches!(c, LoadCase::Fix(_) | LoadCase::Support(_)));
        assert!(!holds, "{kind:?}: still held");
        // without a holding force the clip keeps it whatever the pull
        let (_, kept) = seat_and_pull(clip_at_the_seat(kind, None), 100.0);
        assert!(kept.assembled, "{kind:?} no holding force: {kept:?}");
    }
}
