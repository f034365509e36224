//! The timeline's `settle` is the workcell's relaxation (`Workcell::settle`): it ends at
//! rest when the residual — the largest out-of-balance force and moment on a free node,
//! contact counted — is within its tolerances, under every solver; a hose lying on a part
//! is in balance only with the part's push counted; a settle given too little time says
//! it is not at rest and reports the residual it had. A settle finished by the static
//! solver (`finish = "static"`) waits for the hands, takes the static equilibrium and
//! lands where the dynamic settle does; one ending on the static equilibrium
//! (`finish = "static_equilibrium"`) is at rest there; where the static solve cannot be
//! taken either is the dynamic settle, bit for bit.

use pliant_assembly::workcell::SettleOptions;
use pliant_assembly::{Input, NoObserver, RunSummary, SettleOutcome, Workcell};
use pliant_core::relax::{residual_after, RelaxOptions};
use pliant_core::{SolverKind, State};
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{action, box_part, fix, grab, move_hand, SceneText};
use pliant_testkit::scenes::RAISED_HOSE3_300;

const SOLVERS: [SolverKind; 3] = [
    SolverKind::Explicit,
    SolverKind::Implicit,
    SolverKind::Static,
];
const FORCE_TOLERANCE: f64 = 1e-3;
const MOMENT_TOLERANCE: f64 = 1e-4;

/// The 300 mm hose 3 along +x, 2 m up, clamped at its start, with strong air damping so
/// that the dynamic solvers come to rest soon; `extra` (parts) after it; then a settle of
/// at most `max_duration_s`.
fn scene(extra: &str, max_duration_s: f64) -> String {
    format!(
        r#"{RAISED_HOSE3_300}elements = 10
{extra}
[simulation]
damping_mass_per_s = 40.0

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "settle"
force_tolerance_n = {FORCE_TOLERANCE}
moment_tolerance_nm = {MOMENT_TOLERANCE}
max_duration_s = {max_duration_s}
"#
    )
}

fn run(text: &str, solver: SolverKind) -> (Workcell, RunSummary) {
    let s = load_scene_str(text, "settle.toml").unwrap();
    pliant_runs::run_with(&s, Some(solver)).unwrap()
}

fn only_settle(summary: &RunSummary) -> &SettleOutcome {
    assert_eq!(summary.settles.len(), 1, "{:?}", summary.settles);
    &summary.settles[0]
}

/// Total weight of the hose \[N\] and the vertical support force on its clamped node.
fn weight_and_support(cell: &Workcell) -> (f64, f64) {
    let g = cell.model().gravity.length();
    let weight = cell.model().mass.iter().sum::<f64>() * g;
    (weight, cell.state().reaction_force[0].z)
}

/// The residual as a routine that forgets the parts' push would read it: the explicit
/// step keeps that push out of `force`, the Newton solvers in it.
fn residual_without_part_contact(solver: SolverKind, state: &State) -> f64 {
    (0..state.x.len())
        .filter(|&i| !state.held[i])
        .map(|i| match solver {
            SolverKind::Explicit => state.force[i].length(),
            _ => (state.force[i] - state.contact_force[i]).length(),
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_settle_ends_at_rest_on_its_residual_under_every_solver() {
    for solver in SOLVERS {
        let (cell, summary) = run(&scene("", 30.0), solver);
        let s = only_settle(&summary);
        assert!(s.at_rest, "{solver:?}: {s:?}");
        assert!(s.residual_force <= FORCE_TOLERANCE, "{solver:?}: {s:?}");
        assert!(s.residual_moment <= MOMENT_TOLERANCE, "{solver:?}: {s:?}");
        assert!(s.kinetic_energy < 1e-6, "{solver:?}: {s:?}");
        // the reported residual is the final state's
        let (f, m) = residual_after(solver, cell.state());
        assert_eq!((f, m), (s.residual_force, s.residual_moment), "{solver:?}");
        // in balance: the clamp carries the whole weight, give or take the tolerance
        // on each free node
        let (weight, support) = weight_and_support(&cell);
        let free = cell.state().held.iter().filter(|h| !**h).count() as f64;
        assert!(
            (support - weight).abs() <= free * FORCE_TOLERANCE,
            "{solver:?}: support {support} N, weight {weight} N"
        );
    }
}

#[test]
fn a_hose_lying_on_a_part_settles_with_the_parts_push_in_its_residual() {
    // a slab whose top touches the hose's underside (radius 17.5 mm) along its length
    let slab = "\n[[parts]]\nname = \"slab\"\nbox = { size = [400, 100, 40] }\nposition = [150, 0, 1962.5]\n";
    for solver in SOLVERS {
        let (cell, summary) = run(&scene(slab, 30.0), solver);
        let s = only_settle(&summary);
        assert!(s.at_rest, "{solver:?}: {s:?}");
        assert!(s.residual_force <= FORCE_TOLERANCE, "{solver:?}: {s:?}");
        // the slab carries most of the weight: without its push the hose is far from
        // balance
        let state = cell.state();
        let carried: f64 = state.contact_force.iter().map(|f| f.z).sum();
        let (weight, _) = weight_and_support(&cell);
        assert!(
            carried > 0.5 * weight,
            "{solver:?}: the slab carries {carried} N of {weight} N"
        );
        let forgetful = residual_without_part_contact(solver, state);
        assert!(
            forgetful > 50.0 * FORCE_TOLERANCE,
            "{solver:?}: {forgetful} N without the part's push"
        );
    }
}

#[test]
fn a_settle_too_short_to_come_to_rest_says_so_with_its_residual() {
    for solver in [SolverKind::Explicit, SolverKind::Implicit] {
        let (cell, summary) = run(&scene("", 0.005), solver);
        let s = only_settle(&summary);
        assert!(!s.at_rest, "{solver:?}: {s:?}");
        assert!(
            s.residual_force.is_finite() && s.residual_force > FORCE_TOLERANCE,
            "{solver:?}: {s:?}"
        );
        assert!(
            (s.time - 0.005).abs() <= cell.time_step(),
            "{solver:?}: ended at {} s",
            s.time
        );
    }
}

/// The hose of [`scene`] lying on a slab under it, lightly damped (the scene's default
/// damping), its tip taken by a hand, lifted 20 mm and let go; then a settle with
/// `finish`.
fn lifted_and_let_go(finish: &str) -> String {
    let settle = action("settle")
        .number("force_tolerance_n", FORCE_TOLERANCE)
        .number("moment_tolerance_nm", MOMENT_TOLERANCE)
        .number("max_duration_s", 30.0)
        .text("finish", finish);
    SceneText::piece().raw(&lifted_hose()).with(settle).into()
}

/// [`lifted_and_let_go`] without its settle.
fn lifted_hose() -> String {
    SceneText::piece()
        .raw(&format!("{RAISED_HOSE3_300}elements = 10"))
        .with_all([
            box_part("slab", [400.0, 100.0, 40.0], [150.0, 0.0, 1962.5]),
            fix("h", 0),
            grab(0, [300.0, 0.0, 2000.0]),
            move_hand(0, [0.0, 0.0, 20.0], 0.5),
            action("release_hand").number("hand", 0.0),
        ])
        .into()
}

/// Largest distance between the two states' nodes \[m\].
fn largest_distance(a: &State, b: &State) -> f64 {
    a.x.iter()
        .zip(&b.x)
        .map(|(p, q)| p.distance(*q))
        .fold(0.0, f64::max)
}

/// The ticks of the static solves a run's settle took.
fn static_solve_ticks(cell: &Workcell) -> Vec<u64> {
    cell.log()
        .iter()
        .filter(|s| matches!(s.input, Input::SolveStatic { .. }))
        .map(|s| s.tick)
        .collect()
}

#[test]
fn a_settle_finished_by_the_static_solver_lands_on_the_dynamic_settles_equilibrium() {
    let (dynamic, dynamic_run) = run(&lifted_and_let_go("dynamic"), SolverKind::Explicit);
    let (fast, fast_run) = run(&lifted_and_let_go("static"), SolverKind::Explicit);
    let (d, s) = (only_settle(&dynamic_run), only_settle(&fast_run));
    assert!(d.at_rest && s.at_rest, "dynamic {d:?}, static finish {s:?}");
    assert!(s.residual_force <= FORCE_TOLERANCE && s.residual_moment <= MOMENT_TOLERANCE);
    // one static solve, once the hand had let go and opened (a tenth of a second)
    let ticks = static_solve_ticks(&fast);
    assert_eq!(ticks.len(), 1, "{ticks:?}");
    let released = fast
        .log()
        .iter()
        .find(|s| matches!(s.input, Input::ReleaseHand { .. }))
        .map(|s| s.tick)
        .unwrap();
    let dt = fast.time_step();
    assert!(
        (ticks[0] - released) as f64 * dt >= 0.1 - 1e-9,
        "solved {} s after the release",
        (ticks[0] - released) as f64 * dt
    );
    assert!(static_solve_ticks(&dynamic).is_empty());
    // the same equilibrium, the hose back on the slab: two states each within 1 mN of
    // balance, 0.1 mm apart at most against the 20 mm the tip was lifted (measured:
    // 0.27 µm)
    let gap = largest_distance(dynamic.state(), fast.state());
    assert!(gap < 1e-4, "the two rests are {gap} m apart");
    // resting on the slab in both
    let carried = |c: &Workcell| c.state().contact_force.iter().map(|f| f.z).sum::<f64>();
    assert!(carried(&fast) > 0.0 && carried(&dynamic) > 0.0);
    // and sooner: the slow decay of the last oscillation is not stepped through
    assert!(
        s.time < d.time,
        "static finish at rest at {} s, dynamic at {} s",
        s.time,
        d.time
    );
}

#[test]
fn a_settle_ending_on_the_static_equilibrium_rests_where_the_solve_put_it() {
    let (dynamic, dynamic_run) = run(&lifted_and_let_go("dynamic"), SolverKind::Explicit);
    let (confirmed, confirmed_run) = run(&lifted_and_let_go("static"), SolverKind::Explicit);
    let (ended, ended_run) = run(
        &lifted_and_let_go("static_equilibrium"),
        SolverKind::Explicit,
    );
    let (d, c, e) = (
        only_settle(&dynamic_run),
        only_settle(&confirmed_run),
        only_settle(&ended_run),
    );
    assert!(e.at_rest, "{e:?}");
    // at rest at the instant of its one static solve, the same solve as the confirmed
    // finish's (the same steps up to it), with the solve's residual and no motion
    assert_eq!(static_solve_ticks(&ended), static_solve_ticks(&confirmed));
    assert_eq!(e.static_solve_time, Some(e.time));
    assert_eq!(e.static_solve_time, c.static_solve_time);
    assert!(e.residual_force <= FORCE_TOLERANCE && e.residual_moment <= MOMENT_TOLERANCE);
    assert!(ended.state().v.iter().all(|v| *v == glam::DVec3::ZERO));
    assert_eq!(e.kinetic_energy, 0.0);
    // sooner than the confirmed finish, which steps on from the same state
    assert!(e.time < c.time, "ended {e:?}, confirmed {c:?}");
    // and at the dynamic settle's equilibrium, as the confirmed finish is (0.1 mm of the
    // 20 mm lift)
    let gap = largest_distance(dynamic.state(), ended.state());
    assert!(gap < 1e-4, "the two rests are {gap} m apart ({d:?})");
}

#[test]
fn a_static_finish_the_solver_cannot_take_falls_back_to_the_dynamic_settle_bit_for_bit() {
    // the run up to its settle, twice; then the dynamic settle on one, and on the other
    // the static finish with one Newton iteration allowed: unconverged, so refused
    let text = lifted_hose();
    let (mut dynamic, _) = run(&text, SolverKind::Explicit);
    let (mut fallback, _) = run(&text, SolverKind::Explicit);
    let opts = SettleOptions {
        relax: RelaxOptions {
            force_tolerance: FORCE_TOLERANCE,
            moment_tolerance: MOMENT_TOLERANCE,
            max_steps: dynamic.steps_until_done(30.0),
            kinetic_damping: false,
        },
        kinetic_energy: 1e-6,
    };
    let d = dynamic.settle(&opts, &mut NoObserver).unwrap();
    let f = fallback
        .settle_finishing_static(&opts, 1, &mut NoObserver)
        .unwrap();
    assert!(d.converged, "{d:?}");
    assert_eq!(f.solve, None, "{f:?}");
    assert!(
        static_solve_ticks(&fallback).is_empty(),
        "a refused solve is not logged"
    );
    assert_eq!(f.relax, d);
    assert_eq!(fallback.state().x, dynamic.state().x);
    // and so does one that would end on the static equilibrium
    let (mut ending, _) = run(&text, SolverKind::Explicit);
    let e = ending
        .settle_ending_static(&opts, 1, &mut NoObserver)
        .unwrap();
    assert_eq!(e, f);
    assert_eq!(ending.state().x, dynamic.state().x);
    // given the iterations it needs, the same start takes the solve
    let (mut taken, _) = run(&text, SolverKind::Explicit);
    let t = taken
        .settle_finishing_static(&opts, 60, &mut NoObserver)
        .unwrap();
    let (solve, _) = t.solve.expect("the static solve taken");
    assert!(solve.converged && !solve.unstable, "{solve:?}");
    assert!(
        t.relax.converged && t.relax.steps < d.steps,
        "{t:?} against {d:?}"
    );
}
