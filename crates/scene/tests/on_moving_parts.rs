//! What sits on a moving part goes with it: a clip declared on a part (`part = "..."`)
//! carries the hose it holds, under every solver (a hose fixed at both ends to one part:
//! `moving_parts.rs`).

use pliant_assembly::{run_timeline, NoObserver, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_testkit::scenes::WEIGHTLESS_MM;

/// A hose fixed at its start; its far part lies in the seat of a clip on a carriage that
/// slides 50 mm up (z) in 1 s. `TYPE` is the clip's type.
fn clip_on_carriage() -> String {
    let rest = r#"
[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 0]
path = [{ line = { to = [400, 0, 0] } }]

[[parts]]
name = "carriage"
box = { size = [20, 80, 20] }
position = [300, 0, -60]
motion = { kind = "slide", direction = [0, 0, 1], distance = { times_s = [0.1, 1.1], values = [0, 50] } }

[[clips]]
name = "clip on the carriage"
part = "carriage"
origin = [300, 0, 0]
opening = [0, 0, 1]
orientation = [1, 0, 0]
opening_width = 30
inner_diameter = 36
snap_force_n = 40
type = "TYPE"

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "run"
duration_s = 1.6
"#;
    format!("{WEIGHTLESS_MM}{rest}")
}

#[test]
fn a_hose_in_a_clip_on_a_moving_part_goes_with_the_clip() {
    for (kind, solvers) in [
        ("fixed", &SolverKind::ALL[..]),
        ("rotating", &[SolverKind::Explicit][..]),
    ] {
        let text = clip_on_carriage().replace("TYPE", kind);
        let scene = load_scene_str(&text, "clip.toml").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.clips[0].part, Some(0));
        for &solver in solvers {
            let options = WorkcellOptions {
                solver: Some(solver),
                initial_loads: false,
                ..Default::default()
            };
            let mut cell = scene.workcell(options).unwrap();
            run_timeline(&mut cell, &scene.timeline, &mut NoObserver)
                .unwrap_or_else(|e| panic!("{kind}, {solver}: {e}"));
            let x = &cell.state().x;
            // the node at the clip (x = 300 mm) has risen with it by 50 mm
            let at_clip = x
                .iter()
                .min_by(|a, b| (a.x - 0.3).abs().total_cmp(&(b.x - 0.3).abs()))
                .unwrap();
            assert!(
                (at_clip.z - 0.05).abs() < 1e-3,
                "{kind}, {solver}: node at the clip at z = {} m",
                at_clip.z
            );
            // the fixed start stayed, the free end rose beyond the clip
            assert!(x[0].length() < 1e-9, "{kind}, {solver}");
            assert!(x.last().unwrap().z > 0.045, "{kind}, {solver}: {x:?}");
            let report = &cell.fastener_reports()[0];
            assert!(report.assembled, "{kind}, {solver}: {report:?}");
        }
    }
    // a clip on a part the scene has not names the field
    let text = clip_on_carriage()
        .replace("TYPE", "fixed")
        .replace("part = \"carriage\"", "part = \"sled\"");
    let e = load_scene_str(&text, "clip.toml").unwrap_err();
    assert_eq!(e.field(), Some("clips[0].part"), "{e}");
    assert!(e.to_string().contains("carriage"), "{e}");
}
