//! `[sweep]`: a range-of-motion study loads in SI with its parts resolved, broken entries
//! name the field, and a slow sweep gives the same worst position quasi-statically (the
//! static solver, a pose per input) and dynamically (the explicit solver).

use pliant_core::SolverKind;
use pliant_scene::{load_scene_file, load_scene_str};
use std::path::Path;

fn door_example() -> pliant_scene::LoadedScene {
    load_scene_file(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/door_hinge.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_sweep_loads_in_si_and_broken_entries_name_the_field() {
    let scene = door_example();
    let sweep = scene.checks.sweep.as_ref().expect("[sweep]");
    assert_eq!(sweep.part, 1); // "door"
    assert_eq!(sweep.clearance_parts, vec![0, 1]);
    let text = std::fs::read_to_string(scene.source.as_str()).unwrap();
    let with = |sweep: &str| {
        let start = text.find("\n[sweep]\n").unwrap() + 1;
        let end = start + text[start..].find("\n\n").unwrap();
        format!("{}{sweep}{}", &text[..start], &text[end..])
    };
    let ok = load_scene_str(
        &with("[sweep]\npart = \"door\"\nmin_clearance = 25\n"),
        "d.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let s = ok.checks.sweep.unwrap();
    assert!((s.min_clearance.unwrap() - 0.025).abs() < 1e-15);
    assert!(s.clearance_parts.is_empty(), "every part by default");
    for (sweep, field, message) in [
        ("[sweep]\npart = \"boot\"\n", "sweep.part", "names no part"),
        (
            "[sweep]\npart = \"pillar\"\n",
            "sweep.part",
            "does not move",
        ),
        (
            "[sweep]\npart = \"door\"\nclearance_to = [\"door\", \"fan\"]\n",
            "sweep.clearance_to[1]",
            "names no part",
        ),
        (
            "[sweep]\npart = \"door\"\nmin_clearance = -2\n",
            "sweep.min_clearance",
            "-2",
        ),
    ] {
        let e = load_scene_str(&with(sweep), "d.toml").unwrap_err();
        assert_eq!(e.field(), Some(field), "{sweep}: {e}");
        assert!(e.to_string().contains(message), "{sweep}: {e}");
    }
}

/// The door example with its `[sweep]` section replaced by `sweep`.
fn door_with(sweep: &str) -> String {
    let text = std::fs::read_to_string(door_example().source.as_str()).unwrap();
    let start = text.find("\n[sweep]\n").unwrap() + 1;
    let end = start + text[start..].find("\n\n").unwrap();
    format!("{}{sweep}{}", &text[..start], &text[end..])
}

#[test]
fn the_envelope_voxel_is_the_scenes_and_one_too_fine_for_its_grid_is_refused() {
    let sweep = |voxel: &str| format!("[sweep]\npart = \"door\"\nenvelope_voxel = {voxel}\n");
    let scene =
        load_scene_str(&door_with(&sweep("2.5")), "d.toml").unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.checks.sweep.as_ref().unwrap();
    let voxel = settings.envelope_voxel.expect("the scene's voxel");
    assert!((voxel - 0.0025).abs() < 1e-15, "{voxel}: mm to m");
    // the run's envelopes are made of voxels of that size
    let (_, run) = pliant_runs::run_with(&scene, None).unwrap_or_else(|e| panic!("{e}"));
    let swept = run.checks.sweep.unwrap().swept.unwrap();
    assert_eq!(swept.voxel, voxel);
    assert!(swept.refused.is_none(), "{:?}", swept.refused);
    // the default when none is given: half the thinnest outer radius, at most 5 mm
    let plain = load_scene_str(&door_with("[sweep]\npart = \"door\"\n"), "d.toml").unwrap();
    assert_eq!(plain.checks.sweep.unwrap().envelope_voxel, None);
    for (voxel, message) in [
        ("0", "greater than 0"),
        ("-1", "greater than 0"),
        // 1 µm voxels over a door-sized hose: ≫ 400 million cells
        ("0.001", "choose a voxel of at least"),
    ] {
        let e = load_scene_str(&door_with(&sweep(voxel)), "d.toml").unwrap_err();
        assert_eq!(e.field(), Some("sweep.envelope_voxel"), "{voxel}: {e}");
        assert!(e.to_string().contains(message), "{voxel}: {e}");
    }
    // the smallest voxel the error offers is accepted
    let e = load_scene_str(&door_with(&sweep("0.001")), "d.toml").unwrap_err();
    let text = e.to_string();
    let offered: f64 = text
        .split("at least ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{text}"));
    load_scene_str(&door_with(&sweep(&format!("{offered}"))), "d.toml")
        .unwrap_or_else(|e| panic!("{offered} mm refused: {e}"));
}

#[test]
fn a_slow_door_sweep_is_the_same_quasi_statically_and_dynamically() {
    let scene = door_example();
    let mut worst = Vec::new();
    for solver in [SolverKind::Static, SolverKind::Explicit] {
        let (_, run) =
            pliant_runs::run_with(&scene, Some(solver)).unwrap_or_else(|e| panic!("{e}"));
        let sweep = run.checks.sweep.expect("the sweep's rows");
        let bend = sweep
            .worst()
            .into_iter()
            .find(|w| w.what == "hose 'door hose': bend radius")
            .unwrap();
        eprintln!(
            "{solver}: smallest bend radius {:.2} mm at {:.1}°",
            1e3 * bend.value,
            bend.coordinate.to_degrees()
        );
        worst.push(bend);
    }
    let (q, d) = (&worst[0], &worst[1]);
    // the door moves slowly (70° in 2 s): inertia changes the bend by little
    assert!((q.value - d.value).abs() < 0.05 * q.value, "{q:?} {d:?}");
    assert!(q.coordinate.to_degrees() > 60.0 && d.coordinate.to_degrees() > 60.0);
}

/// A live session has no planned end, so its range-of-motion rows would grow without
/// bound; they are capped (`pliant_assembly::series_cap`) and the cap is what a live
/// session is checked against: a scene whose planned run fits its memory limit is refused
/// as a live session when the cap does not fit beside it.
#[test]
fn a_live_session_is_checked_against_its_capped_series() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/door_hinge.toml");
    let estimate = door_example().estimate.memory_bytes();
    let with_limit = |bytes: u64| {
        let options = pliant_scene::LoadOptions {
            limits: pliant_scene::Limits::with_memory(bytes),
            ..Default::default()
        };
        pliant_scene::load_scene_file_with(&path, &options).unwrap_or_else(|e| panic!("{e}"))
    };
    let tight = with_limit(estimate + 4_000_000);
    tight
        .check_planned_steps(1e-4, u64::MAX)
        .unwrap_or_else(|e| panic!("the planned run fits: {e}"));
    let e = tight.check_live_session().unwrap_err();
    assert!(e.contains("range-of-motion"), "{e}");
    let roomy = with_limit(estimate + pliant_scene::budget::MAX_CAPPED_SERIES_BYTES);
    roomy
        .check_live_session()
        .unwrap_or_else(|e| panic!("the capped rows fit: {e}"));
}
