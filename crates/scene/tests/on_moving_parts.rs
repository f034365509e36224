//! What sits on a moving part goes with it: a hose fixed at both ends to one part (`fix`
//! with `part`) is carried rigidly, and a clip declared on a part (`part = "..."`) carries
//! the hose it holds, under every solver.

use glam::{DQuat, DVec3};
use pliant_assembly::{run_timeline, NoObserver, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;

/// A hose from (0, 0, 0) to (300, 0, 0) mm with both ends fixed to a door that turns
/// 0 → 60° about the vertical through (500, 0, 0) in 1 s.
const FIXED_ON_DOOR: &str = r#"
format = "pliant-scene"
version = 1
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]

[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 0]
path = [{ line = { to = [300, 0, 0] } }]

[[parts]]
name = "door"
box = { size = [20, 20, 20] }
position = [150, 0, -60]
motion = { kind = "hinge", axis = [0, 0, 1], point = [500, 0, 0], angle_deg = { times_s = [0, 1], values = [0, 60] } }

[[timeline]]
action = "fix"
hose = "h"
node = 0
part = "door"

[[timeline]]
action = "fix"
hose = "h"
node = -1
part = "door"

[[timeline]]
action = "run"
duration_s = 1.2
"#;

#[test]
fn a_hose_fixed_at_both_ends_to_a_moving_part_moves_rigidly_under_every_solver() {
    let scene = load_scene_str(FIXED_ON_DOOR, "door.toml").unwrap_or_else(|e| panic!("{e}"));
    let turn = DQuat::from_rotation_z(60f64.to_radians());
    let hinge = DVec3::new(0.5, 0.0, 0.0);
    for solver in SolverKind::ALL {
        let options = WorkcellOptions {
            solver: Some(solver),
            initial_loads: false,
            ..Default::default()
        };
        let mut cell = scene.workcell(options).unwrap();
        let rest: Vec<DVec3> = cell.state().x.clone();
        run_timeline(&mut cell, &scene.timeline, &mut NoObserver)
            .unwrap_or_else(|e| panic!("{solver}: {e}"));
        let x = &cell.state().x;
        let worst = rest
            .iter()
            .zip(x)
            .map(|(&r, &now)| (hinge + turn * (r - hinge) - now).length())
            .fold(0.0, f64::max);
        // every node where the door carries it: no strain, no sag (no gravity); the
        // dynamic solvers keep a little of the swing's inertial load (µm over 0.3 m)
        eprintln!("{solver}: {worst:.3e} m from the carried shape");
        assert!(worst < 1e-5, "{solver}: {worst} m from the carried shape");
        let strain = x
            .windows(2)
            .zip(rest.windows(2))
            .map(|(a, b)| ((a[1] - a[0]).length() / (b[1] - b[0]).length() - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!("{solver}: strain {strain:.3e}");
        assert!(strain < 1e-5, "{solver}: strain {strain}");
    }
    // `fix` with `part` is a mount
    assert!(matches!(
        &scene.timeline.actions[0],
        pliant_assembly::Action::Mount { part, .. } if part == "door"
    ));
}

/// A hose fixed at its start; its far part lies in the seat of a clip on a carriage that
/// slides 50 mm up (z) in 1 s. `TYPE` is the clip's type.
const CLIP_ON_CARRIAGE: &str = r#"
format = "pliant-scene"
version = 1
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]

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

#[test]
fn a_hose_in_a_clip_on_a_moving_part_goes_with_the_clip() {
    for (kind, solvers) in [
        ("fixed", &SolverKind::ALL[..]),
        ("rotating", &[SolverKind::Explicit][..]),
    ] {
        let text = CLIP_ON_CARRIAGE.replace("TYPE", kind);
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
    let text = CLIP_ON_CARRIAGE
        .replace("TYPE", "fixed")
        .replace("part = \"carriage\"", "part = \"sled\"");
    let e = load_scene_str(&text, "clip.toml").unwrap_err();
    assert_eq!(e.field(), Some("clips[0].part"), "{e}");
    assert!(e.to_string().contains("carriage"), "{e}");
}
