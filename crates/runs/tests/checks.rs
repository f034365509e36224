//! SPEC V3: the installation checks on scenes with known answers. A straight hose rolled
//! up by an end moment M bends into a circular arc of curvature κ = M / EI exactly (the
//! elastica of pure bending); the bend-radius check must find 1/κ wherever it breaks the
//! material's minimum, and nothing when the arc is gentle. A cantilever bent hard by a
//! tip load breaks it first at its root.

use pliant_assembly::checks::CheckKind;
use pliant_core::{Model, SolverKind};
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{fix, hose, run_for, solver, SceneText};

/// A 500 mm hose3 along x, 20 elements, no gravity, fixed at its start, with `load` (a
/// `load` action's key, `force_n` or `moment_nm`, and its vector) at its end; `extra` is
/// added at the top.
fn scene(load: (&str, [f64; 3]), extra: &str) -> String {
    let (key, vector) = load;
    SceneText::mm()
        .raw(extra)
        .with(solver("static").point("gravity", [0.0; 3]))
        .with(hose("h", "hose3", [0.0; 3], [500.0, 0.0, 0.0]).number("elements", 20.0))
        .with(fix("h", 0))
        .with(
            pliant_testkit::scene_text::load("h", -1)
                .point(key, vector)
                .number("ramp_s", 0.5),
        )
        .with(run_for(1.0))
        .into()
}

/// EI of the hose \[N·m²\] and its minimum bend radius \[m\].
fn stiffness_and_limit() -> (f64, f64) {
    let s = load_scene_str(&scene(("moment_nm", [0.0, 1.0, 0.0]), ""), "probe.toml").unwrap();
    let model = Model::build(&s.world).unwrap();
    let ei = model.elements[0].bending_stiffness;
    assert_eq!(ei[0], ei[1]);
    (ei[0], s.hoses[0].min_bend_radius)
}

#[test]
fn min_bend_radius_comes_from_the_material_data() {
    // hose3: 6 × 27 mm + 35 mm / 2 (data/materials.toml, rule marked as an assumption)
    let (_, r_min) = stiffness_and_limit();
    assert!((r_min - 0.1795).abs() < 1e-12, "{r_min}");
}

#[test]
fn a_hose_rolled_tighter_than_its_minimum_radius_is_reported_at_kappa_m_over_ei() {
    let (ei, r_min) = stiffness_and_limit();
    let radius = 0.12; // m, below r_min = 0.1795 m
    let m = ei / radius;
    let text = scene(("moment_nm", [0.0, m, 0.0]), "");
    let s = load_scene_str(&text, "rolled.toml").unwrap();
    let (_, run) = pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap();
    let v: Vec<_> = run
        .checks
        .violations
        .iter()
        .filter(|v| v.check == CheckKind::BendRadius)
        .collect();
    assert_eq!(v.len(), 1, "{:?}", run.checks.violations);
    let v = v[0];
    assert_eq!(v.hose_name, "h");
    assert_eq!(v.limit, r_min);
    // pure bending: κ = M/EI on every beam
    assert!(
        (v.value - radius).abs() < 1e-6 * radius,
        "bend radius {} against EI/M = {radius}",
        v.value
    );
    let p = &run.checks.profiles[0];
    for k in &p.curvature {
        assert!(
            (k * radius - 1.0).abs() < 1e-6,
            "κ = {k}, 1/R = {}",
            1.0 / radius
        );
    }
    // no twist in pure bending about a section axis
    assert!(p.max_twist < 1e-6, "twist {}", p.max_twist);
    assert!(!run
        .checks
        .violations
        .iter()
        .any(|v| v.check == CheckKind::Twist));
    // the verdict says so, naming the hose, the place and the values
    let verdict = pliant_assembly::Verdict::judge(&run, None, pliant_assembly::Stage::Final);
    assert_eq!(verdict.feasible, Some(false), "{:?}", verdict.reasons);
    let violated = verdict.findings.reasons.iter().find_map(|r| match r {
        pliant_assembly::Reason::CheckViolated { violation, .. } => Some(violation),
        _ => None,
    });
    assert_eq!(violated, Some(v), "{:?}", verdict.findings.reasons);
    assert!(
        verdict
            .reasons
            .iter()
            .any(|r| r.contains("hose 'h': bend_radius check")
                && r.contains("bend radius 120 mm")
                && r.contains("the minimum 180 mm")),
        "{:?}",
        verdict.reasons
    );
}

#[test]
fn a_gently_rolled_hose_passes_and_its_radius_is_still_reported() {
    let (ei, _) = stiffness_and_limit();
    let radius = 0.6;
    let text = scene(("moment_nm", [0.0, ei / radius, 0.0]), "");
    let s = load_scene_str(&text, "gentle.toml").unwrap();
    let (_, run) = pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap();
    assert!(
        run.checks.violations.is_empty(),
        "{:?}",
        run.checks.violations
    );
    let p = &run.checks.profiles[0];
    assert!((p.min_bend_radius - radius).abs() < 1e-6 * radius);
}

#[test]
fn a_cantilever_bent_hard_breaks_the_radius_first_at_its_root() {
    let (ei, r_min) = stiffness_and_limit();
    // tip force F: root moment ≈ F·L (less as it deflects); F·L = 3 EI / r_min is
    // well past the minimum radius at the root and nowhere near it at the tip.
    let f = 3.0 * ei / r_min / 0.5;
    let text = scene(("force_n", [0.0, 0.0, -f]), "");
    let s = load_scene_str(&text, "cantilever.toml").unwrap();
    let (cell, run) = pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap();
    let v = run
        .checks
        .violations
        .iter()
        .find(|v| v.check == CheckKind::BendRadius)
        .expect("bend radius violated");
    let p = &run.checks.profiles[0];
    assert_eq!(v.arc_length, p.arc_length[0], "worst at the root beam");
    assert!((v.arc_length - 0.0125).abs() < 1e-12);
    // the root beam's curvature is the moment at its midpoint over EI: M = F·(x_tip − x_mid)
    let state = cell.state();
    let info = &cell.model().hoses[0];
    let tip = state.x[info.node(info.node_count - 1)];
    let mid = 0.5 * (state.x[info.node(0)] + state.x[info.node(1)]);
    let m_mid = f * (tip.x - mid.x);
    let expected = ei / m_mid;
    assert!(
        (v.value - expected).abs() < 0.02 * expected,
        "root radius {} against EI/M = {expected}",
        v.value
    );
}

#[test]
fn checks_switch_off_or_warn_per_scene() {
    let (ei, _) = stiffness_and_limit();
    let load = ("moment_nm", [0.0, ei / 0.12, 0.0]);
    let off = scene(load, "[checks]\nbend_radius = false\n");
    let (_, run) = pliant_runs::run_with(
        &load_scene_str(&off, "off.toml").unwrap(),
        Some(SolverKind::Static),
    )
    .unwrap();
    assert!(run.checks.violations.is_empty());
    assert!(!run.checks.enabled.contains(&"bend_radius"));
    let warn = scene(load, "[checks]\ndecide = false\n");
    let (_, run) = pliant_runs::run_with(
        &load_scene_str(&warn, "warn.toml").unwrap(),
        Some(SolverKind::Static),
    )
    .unwrap();
    assert_eq!(run.checks.violations.len(), 1);
    let verdict = pliant_assembly::Verdict::judge(&run, None, pliant_assembly::Stage::Final);
    assert!(verdict
        .warnings
        .iter()
        .any(|w| w.contains("bend_radius check")));
    assert!(!verdict
        .reasons
        .iter()
        .any(|w| w.contains("bend_radius check")));
}

#[test]
fn bad_check_limits_are_errors_naming_the_field() {
    for (extra, field) in [
        (
            "[checks]\ntwist_limit_deg_per_m = -1\n",
            "checks.twist_limit_deg_per_m",
        ),
        (
            "[checks]\nrest_strain_limit = 0\n",
            "checks.rest_strain_limit",
        ),
        ("[checks]\nbend_radius = 3\n", "checks.bend_radius"),
        ("[checks]\nbend = true\n", "checks.bend"),
    ] {
        let err = load_scene_str(&scene(("moment_nm", [0.0, 1.0, 0.0]), extra), "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains(field), "`{err}` lacks `{field}`");
    }
}

/// The built-in demo tells a true story — the hose rests on a part, the
/// hand's bending moment is a warning only, and what makes it infeasible is the push into
/// the engine-corner clip (the reason names it) and the installation checks.
#[test]
fn the_engine_bay_demo_shows_contact_and_follows_the_new_rules() {
    let scene = pliant_scene::demo_scene().unwrap();
    let (_, run) = pliant_runs::run_with(&scene, None).unwrap();
    assert!(
        run.contacts.iter().any(|c| c.part == "heat shield"),
        "{:?}",
        run.contacts
    );
    let verdict = pliant_assembly::Verdict::judge(&run, None, pliant_assembly::Stage::Final);
    assert_eq!(verdict.feasible, Some(false));
    // the reason names the fastener the hand was pressing at its worst moment
    assert!(
        verdict
            .reasons
            .iter()
            .any(|r| r.starts_with("hand 0: push of")
                && r.ends_with("pressing the hose into clip 'clip engine corner'")),
        "{:?}",
        verdict.reasons
    );
    assert!(verdict
        .reasons
        .iter()
        .all(|r| !r.contains("bending moment")));
    assert!(
        verdict
            .warnings
            .iter()
            .any(|w| w.contains("bending moment")),
        "{:?}",
        verdict.warnings
    );
    assert!(run
        .checks
        .violations
        .iter()
        .any(|v| v.check == CheckKind::BendRadius && v.hose_name == "lower"));
    // both clips end seated: the hand opens slowly, so each press goes past the seat, and
    // pressing at the corner clip does not lift the radiator-side clip's seat
    let clips: Vec<_> = run
        .fasteners
        .iter()
        .filter(|f| f.kind == pliant_assembly::FastenerKind::Clip)
        .collect();
    assert_eq!(clips.len(), 2);
    assert!(
        clips
            .iter()
            .all(|f| f.final_state == pliant_assembly::FastenerState::Seated),
        "{clips:?}"
    );
}

/// A span with a minimum bend radius of its own (a protected stretch of a harness segment)
/// holds its elements to it: an arc gentler than the hose's minimum but tighter than the
/// span's is reported there, at the span's limit, and nowhere else.
#[test]
fn a_span_is_held_to_its_own_minimum_bend_radius() {
    let (ei, r_min) = stiffness_and_limit();
    let radius = 0.25; // m: above the hose's 0.1795 m, below the span's 0.3 m
    let m = ei / radius;
    let plain = scene(("moment_nm", [0.0, m, 0.0]), "");
    let path = "path = [{ line = { to = [500, 0, 0] } }]";
    // hose3's own tube (27/35 mm): the same stiffness over the span, so κ stays M/EI
    let with_span = plain.replacen(
        path,
        &format!("{path}\nspans = [{{ from = 200, to = 300, min_bend_radius = 300, section = {{ d_inner = 27, d_outer = 35 }} }}]"),
        1,
    );
    let bend = |text: &str| {
        let s = load_scene_str(text, "span.toml").unwrap();
        let (_, run) = pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap();
        let violations = run
            .checks
            .violations
            .into_iter()
            .filter(|v| v.check == CheckKind::BendRadius)
            .collect::<Vec<_>>();
        (violations, run.checks.profiles.into_iter().next().unwrap())
    };
    assert!(
        bend(&plain).0.is_empty(),
        "gentler than the hose's {r_min} m"
    );
    let (v, profile) = bend(&with_span);
    // the profile's worst bend is the span's, against the span's limit, and its allowed
    // curvature steps up over the span only
    assert_eq!(profile.allowed_bend_radius, 0.3);
    assert!((profile.worst_bend_ratio - 0.3 / radius).abs() < 1e-6);
    for (s, allowed) in profile.arc_length.iter().zip(&profile.allowed_curvature) {
        let expected = if (0.2..0.3).contains(s) { 0.3 } else { r_min };
        assert!(
            (allowed * expected - 1.0).abs() < 1e-12,
            "at s = {s} m: {allowed}"
        );
    }
    assert_eq!(v.len(), 1, "{v:?}");
    assert_eq!(v[0].limit, 0.3);
    assert!(
        (v[0].value - radius).abs() < 1e-6 * radius,
        "{}",
        v[0].value
    );
    assert!(
        (0.2..0.3).contains(&v[0].arc_length),
        "at {} m, inside the span",
        v[0].arc_length
    );
}
