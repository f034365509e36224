//! The timeline's `settle` is the workcell's relaxation (`Workcell::settle`): it ends at
//! rest when the residual — the largest out-of-balance force and moment on a free node,
//! contact counted — is within its tolerances, under every solver; a hose lying on a part
//! is in balance only with the part's push counted; a settle given too little time says
//! it is not at rest and reports the residual it had.

use pliant_assembly::{RunSummary, SettleOutcome, Workcell};
use pliant_core::relax::residual_after;
use pliant_core::{SolverKind, State};
use pliant_scene::load_scene_str;
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
