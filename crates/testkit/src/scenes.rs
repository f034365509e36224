//! Pieces of mini-scenes in the scene format (docs/scene-format.md), for the tests that
//! write a scene file in a few lines: put together with `format!` and the test's own
//! tables. Each piece starts and ends with a newline. Scenes a test builds from typed
//! pieces: [`crate::scene_text`].

use crate::scene_text::{fix, grab, hose, move_hand, solver, SceneText};

/// The scene format's head in millimetres (kept a macro so the pieces below can start
/// with it).
macro_rules! head_mm {
    () => {
        "\nformat = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n"
    };
}

/// The head of a scene in millimetres: format, version and length unit.
pub const HEAD_MM: &str = head_mm!();

/// [`HEAD_MM`] and a `[simulation]` table without gravity (a test may add its own
/// `solver = …` line after it).
pub const WEIGHTLESS_MM: &str = concat!(head_mm!(), "\n[simulation]\ngravity = [0, 0, 0]\n");

/// [`HEAD_MM`] (gravity on) and a 300 mm hose "h" of library hose 3 along +x, 2 m above
/// the origin: a scene a test gives its parts.
pub const RAISED_HOSE3_300: &str = concat!(
    head_mm!(),
    r#"
[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 2000]
path = [{ line = { to = [300, 0, 2000] } }]
"#
);

/// A 300 mm hose "h" of library hose 3 along +x from the origin (mm).
pub const HOSE3_300: &str = r#"
[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 0]
path = [{ line = { to = [300, 0, 0] } }]
"#;

/// Two 200 mm hoses "a" and "b" of library hose 1 along +x, 20 mm apart (mm), joined
/// by a junction "tee" at a's end and b's start: a test adds its `body = …` line next.
pub const TEE_MM: &str = r#"
[[hoses]]
name = "a"
material = "hose1"
elements = 4
start = [0, 0, 0]
path = [{ line = { to = [200, 0, 0] } }]

[[hoses]]
name = "b"
material = "hose1"
elements = 4
start = [220, 0, 0]
path = [{ line = { to = [400, 0, 0] } }]

[[junctions]]
name = "tee"
ends = [{ hose = "a", end = "end" }, { hose = "b", end = "start" }]
"#;

/// A part "door": a 20 mm box below and beyond the far end of [`HOSE3_300`] (mm), which
/// a test may give a `motion` or `movable` line next.
pub const DOOR: &str = r#"
[[parts]]
name = "door"
box = { size = [20, 20, 20] }
position = [320, 0, -40]
"#;

/// An EPDM of E = 8 MPa in tension and compression, ν 0.45, ρ 1150 kg/m³, called
/// "epdm" (a test may add its own `relaxation = …` line after it).
pub const EPDM: &str = r#"
[materials.epdm]
e_tension_mpa = 8
e_compression_mpa = 8
poisson = 0.45
density_kg_m3 = 1150
"#;

/// The steel of the library's metal lines (E = 210 GPa, ν 0.3, ρ 7850 kg/m³) without a
/// yield stress, called "elastic_steel": the elastic twin of a yielding steel line.
pub const ELASTIC_STEEL: &str = r#"
[materials.elastic_steel]
e_tension_mpa = 210000
e_compression_mpa = 210000
poisson = 0.3
density_kg_m3 = 7850
"#;

/// `scene` and then hose `name` of library hose 3, 10 elements, straight from `start` to
/// `end` (mm), fixed at its start, its end grabbed by hand 0 and moved by `by` (mm) over
/// `duration_s`: what a worker's tests give him to hold.
pub fn held_hose(
    scene: SceneText,
    name: &str,
    start: [f64; 3],
    end: [f64; 3],
    by: [f64; 3],
    duration_s: f64,
) -> SceneText {
    scene
        .with(hose(name, "hose3", start, end).number("elements", 10.0))
        .with(fix(name, 0))
        .with(grab(0, end))
        .with(move_hand(0, by, duration_s))
}

/// A scene (mm, the static solver) for a worker's tests: `extra` (a `[worker]`, parts,
/// another hose) and then the [`held_hose`] `name` from `start` to `end`, lowered 20 mm
/// over `duration_s`.
pub fn held_hose_lowered(
    extra: &str,
    name: &str,
    start: [f64; 3],
    end: [f64; 3],
    duration_s: f64,
) -> String {
    let scene = SceneText::mm().with(solver("static")).raw(extra);
    held_hose(scene, name, start, end, [0.0, 0.0, -20.0], duration_s).into()
}
