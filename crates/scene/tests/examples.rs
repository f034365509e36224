//! Every example scene loads, and the built-in demo and the thesis experiments come out
//! as specified.

use glam::DVec3;
use pliant_assembly::{Action, MovePath, NodeRef};
use pliant_scene::{demo_scene, load_scene_file, load_scene_json_str, load_scene_str, LengthUnit};
use std::path::{Path, PathBuf};

fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn example_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(examples_dir())
        .expect("examples/ exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        // studies (format "pliant-study", docs/study.md) live beside the scenes they vary
        .filter(|p| {
            !std::fs::read_to_string(p).is_ok_and(|t| t.contains("format = \"pliant-study\""))
        })
        .collect();
    files.sort();
    files
}

#[test]
fn all_examples_load() {
    let files = example_files();
    assert!(
        files.len() >= 5,
        "expected demo + 4 thesis scenes, found {files:?}"
    );
    for f in files {
        let scene = load_scene_file(&f).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scene.world.hoses.is_empty());
        assert_eq!(scene.source, f.display().to_string());
    }
}

#[test]
fn every_example_builds_a_core_model() {
    for f in example_files() {
        let scene = load_scene_file(&f).unwrap_or_else(|e| panic!("{e}"));
        if let Err(e) = pliant_core::Model::build(&scene.world) {
            panic!("{}: {e}", f.display());
        }
    }
}

fn coolant_demo() -> pliant_scene::LoadedScene {
    load_scene_file(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo.toml"))
        .expect("demo.toml loads")
}

#[test]
fn built_in_demo_is_the_engine_bay() {
    let scene = demo_scene().expect("built-in demo loads");
    assert!(scene.source.contains("engine_bay"));
    assert!(!scene.parts.is_empty() && !scene.stubs.is_empty() && scene.clips.len() >= 2);
    assert!(scene
        .timeline
        .actions
        .iter()
        .any(|a| matches!(a, Action::Grab { .. })));
}

#[test]
fn coolant_demo_scene_is_as_described() {
    let scene = coolant_demo();
    assert_eq!(scene.name, "Demo: coolant hose");
    assert_eq!(scene.length_unit, LengthUnit::Millimetre);
    assert_eq!(scene.hose_names, vec!["coolant".to_string()]);
    let hose = &scene.world.hoses[0];
    assert_eq!(hose.sections[0].d_inner, 0.027);
    assert_eq!(hose.sections[0].d_outer, 0.035);
    let info = &scene.hoses[0];
    assert!((0.6..0.8).contains(&info.length), "length {}", info.length);
    // Default element length 1.5 d_outer = 52.5 mm, but the 150 mm arc needs spacing
    // ≤ 150·π/8 ≈ 58.9 mm: the default already satisfies it.
    assert!(info.element_length <= 1.5 * 0.035 + 1e-12);
    assert_eq!(hose.nodes.len(), info.elements + 1);
    assert!((hose.nodes[0] - DVec3::new(0.0, 0.0, 0.3)).length() < 1e-12);
    assert!((hose.nodes[info.elements] - DVec3::new(0.4, 0.33, 0.3)).length() < 1e-12);
    let kinds: Vec<&str> = scene
        .timeline
        .actions
        .iter()
        .map(|a| match a {
            Action::Fix { .. } => "fix",
            Action::Mount { .. } => "mount",
            Action::Move { .. } => "move",
            Action::Release { .. } => "release",
            Action::Tie { .. } => "tie",
            Action::Settle { .. } => "settle",
            Action::Run { .. } => "run",
            Action::Load { .. } => "load",
            Action::Unload { .. } => "unload",
            Action::Grab { .. } | Action::GrabNode { .. } => "grab",
            Action::MoveHand { .. } => "move_hand",
            Action::AlignHand { .. } => "align_hand",
            Action::AimHand { .. } => "aim_hand",
            Action::ReleaseHand { .. } => "release_hand",
            Action::MovePart { .. } => "move_part",
            Action::RotatePart { .. } => "rotate_part",
        })
        .collect();
    assert_eq!(kinds, ["fix", "move", "run", "release", "settle"]);
    match &scene.timeline.actions[1] {
        Action::Move {
            node,
            path: Some(MovePath::To(points)),
            rotation: Some(r),
            duration,
            wait,
        } => {
            assert_eq!(
                *node,
                NodeRef {
                    hose: 0,
                    node: info.elements
                }
            );
            assert_eq!(points.len(), 3);
            assert!((r.angle - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
            assert_eq!(*duration, 3.0);
            assert!(*wait);
        }
        other => panic!("unexpected {other:?}"),
    }
    match scene.timeline.actions[4] {
        Action::Settle { max_duration, .. } => assert_eq!(max_duration, 20.0),
        ref other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn thesis_scenes_match_the_experiments() {
    let offsets = [
        DVec3::new(0.05, 0.0, 0.0),
        DVec3::new(-0.12, 0.0, 0.0),
        DVec3::new(-0.12, 0.12, 0.12),
        DVec3::new(-0.12, 0.0, 0.0),
    ];
    for (i, expected_by) in offsets.iter().enumerate() {
        let path = examples_dir().join(format!("thesis_{}.toml", i + 1));
        let scene = load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.world.settings.gravity, DVec3::ZERO);
        let hose = &scene.world.hoses[0];
        assert_eq!(hose.nodes.len(), 21);
        assert_eq!(hose.sections[0].d_outer, 0.04);
        assert_eq!(hose.sections[0].d_inner, 0.03);
        let e = 12.35965e6;
        assert!(
            (hose.material.e_tension - e).abs() < 1e-6
                && (hose.material.e_compression - e).abs() < 1e-6
        );
        assert_eq!(hose.material.density, 940.0);
        for (k, node) in hose.nodes.iter().enumerate() {
            let dz = match k {
                10 => 0.001,
                9 | 11 => 0.0005,
                _ => 0.0,
            };
            let expected = DVec3::new(0.025 * k as f64, 0.0, dz);
            assert!((*node - expected).length() < 1e-15, "node {k}: {node}");
        }
        assert_eq!(
            scene.timeline.actions[0],
            Action::Fix {
                node: NodeRef { hose: 0, node: 0 }
            }
        );
        match &scene.timeline.actions[1] {
            Action::Move {
                node,
                path: Some(MovePath::By(points)),
                rotation,
                duration,
                ..
            } => {
                assert_eq!(node.node, 20);
                assert_eq!(points.len(), 1);
                assert!((points[0] - *expected_by).length() < 1e-15);
                assert_eq!(*duration, 20.0);
                assert_eq!(rotation.is_some(), i == 3);
                if let Some(r) = rotation {
                    assert_eq!(r.axis, DVec3::Y);
                    assert!((r.angle - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
                }
            }
            other => panic!("unexpected {other:?}"),
        }
        assert!(matches!(scene.timeline.actions[2], Action::Settle { .. }));
    }
}

#[test]
fn metres_and_millimetres_give_the_same_scene() {
    let mm = load_scene_file(&examples_dir().join("thesis_3.toml")).expect("loads");
    let text = mm
        .text
        .replace("length_unit = \"mm\"", "length_unit = \"m\"")
        .replace(
            "d_inner = 30, d_outer = 40",
            "d_inner = 0.03, d_outer = 0.04",
        )
        .replace("[500, 0, 0]", "[0.5, 0, 0]")
        .replace("[0, 0, 0.5]", "[0, 0, 0.0005]")
        .replace("[0, 0, 1]", "[0, 0, 0.001]")
        .replace("[-120, 120, 120]", "[-0.12, 0.12, 0.12]");
    let m = load_scene_str(&text, "thesis_3_m.toml").expect("loads");
    for (a, b) in mm.world.hoses[0].nodes.iter().zip(&m.world.hoses[0].nodes) {
        assert!((*a - *b).length() < 1e-15);
    }
    assert_eq!(mm.timeline, m.timeline);
}

#[test]
fn json_scene_loads_like_toml() {
    let toml_scene = coolant_demo();
    let value: toml::Value = toml::from_str(&toml_scene.text).expect("valid toml");
    let json = serde_json::to_string_pretty(&value).expect("serialises");
    let json_scene = load_scene_json_str(&json, "demo.json").expect("json loads");
    assert_eq!(json_scene.world, toml_scene.world);
    assert_eq!(json_scene.timeline, toml_scene.timeline);
}

#[test]
fn documented_example_loads() {
    let doc = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md"),
    )
    .expect("docs/scene-format.md exists");
    let start = doc
        .find("## Complete annotated example")
        .expect("section exists");
    let block = doc[start..]
        .split("```toml\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("toml block");
    let scene = load_scene_str(block, "scene-format.md").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.hose_names, ["coolant", "return"]);
    assert_eq!(scene.timeline.actions.len(), 11);
    assert_eq!(scene.stubs.len(), 1);
    assert_eq!(scene.clips.len(), 1);
    assert_eq!(scene.world.settings.damping_stiffness, Some(0.0002));
    assert_eq!(scene.hoses[1].elements, 20);
    pliant_core::Model::build(&scene.world).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn stiffened_spans_resolve_and_bad_ones_are_refused() {
    let scene = demo_scene().expect("demo loads");
    let spans = scene.stiffened_spans();
    assert_eq!(spans.len(), 1);
    assert_eq!((spans[0].first, spans[0].last), (3, 5));
    let base = pliant_scene::DEMO_SCENE_TOML;
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for (span, field, reason) in [
        (
            "{ first = 5, last = 3 }",
            "stiffened[0].last",
            "must come after first",
        ),
        ("{ first = 2, last = 99 }", "stiffened[0].last", ""),
        (
            "{ first = 1, last = 3 }, { first = 3, last = 4 }",
            "stiffened[1]",
            "overlaps",
        ),
    ] {
        let text = base.replace(
            "stiffened = [{ first = 3, last = 5 }]",
            &format!("stiffened = [{span}]"),
        );
        let err = pliant_scene::load_scene_str_in(&text, "bay.toml", &examples)
            .expect_err(span)
            .to_string();
        assert!(err.contains(field) && err.contains(reason), "{span}: {err}");
    }
}
