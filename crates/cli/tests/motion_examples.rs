//! The README's range-of-motion examples run as a user runs them: `pliant run` writes
//! `motion.csv` against the moving part's coordinate, the report draws it, and the
//! verdict names the worst position in the motion's own unit.

use pliant_testkit::scene_text::{fix, move_part, rotate_part, SceneText};
use pliant_testkit::scenes::{DOOR, HOSE3_300, WEIGHTLESS_MM};
use std::path::Path;
use std::process::Command;

fn examples() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"))
}

/// `pliant run --quiet SCENE --out OUT`.
fn pliant_run(scene: &Path, out: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
        .args(["run", "--quiet"])
        .arg(scene)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// Runs `examples/NAME` into a fresh folder: (the folder, the verdict's reasons, the rows
/// of motion.csv as numbers, its header).
fn run_example(name: &str) -> (tempfile::TempDir, Vec<String>, Vec<Vec<f64>>, Vec<String>) {
    let out = tempfile::tempdir().unwrap();
    let o = pliant_run(&examples().join(name), out.path());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("report.json")).unwrap())
            .unwrap();
    let reasons = report["verdict"]["reasons"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_str().unwrap().to_string())
        .collect();
    let csv = std::fs::read_to_string(out.path().join("motion.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()).collect())
        .collect();
    let html = std::fs::read_to_string(out.path().join("report.html")).unwrap();
    assert!(
        html.contains("Range of motion"),
        "no range-of-motion section"
    );
    (out, reasons, rows, header)
}

fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

#[test]
fn the_door_hinge_example_names_the_angle_where_the_hose_bends_tightest() {
    let (_out, reasons, rows, header) = run_example("door_hinge.toml");
    let angle = column(&header, "angle_deg");
    let ratio = column(&header, "door hose: bend_radius_ratio");
    let pillar = column(&header, "clearance_m door hose to pillar");
    column(&header, "max_fixing_force_n");
    // the door opens 0 → 70° and closes again
    let most = rows.iter().map(|r| r[angle]).fold(0.0, f64::max);
    assert!((most - 70.0).abs() < 1e-9, "largest angle {most}");
    assert!(rows.last().unwrap()[angle].abs() < 1e-9);
    // closed, the hose is far from its minimum bend radius; open, past it
    let closed = rows.iter().find(|r| r[angle] < 1.0).unwrap();
    let open = rows.iter().find(|r| r[angle] == 70.0).unwrap();
    assert!(
        closed[ratio] < 0.1 && open[ratio] > 1.0,
        "{closed:?} {open:?}"
    );
    assert!(
        rows.iter().all(|r| r[pillar] > -1e-3),
        "pressed into the pillar"
    );
    // the verdict puts the worst bend at the door's angle, in degrees
    let bend = reasons
        .iter()
        .find(|r| r.contains("bend_radius check"))
        .unwrap_or_else(|| panic!("{reasons:?}"));
    assert!(bend.ends_with("at door angle 70°"), "{bend}");
    assert!(
        reasons
            .iter()
            .any(|r| r.starts_with("over the motion of part 'door' (angle 0° … 70°)")),
        "{reasons:?}"
    );
}

#[test]
fn the_rocking_engine_example_reports_a_cycle_of_phases_and_the_fan_clearance() {
    let (_out, reasons, rows, header) = run_example("engine_rocking.toml");
    let phase = column(&header, "phase_deg");
    let upper = column(&header, "upper: min_bend_radius_m");
    let fan = column(&header, "clearance_m upper to fan hub");
    column(&header, "clearance_m lower to fan hub");
    // two cycles at 1.5 Hz sampled every 10 ms: every phase bin of 30° is visited
    for bin in 0..12 {
        let lo = 30.0 * bin as f64;
        assert!(
            rows.iter().any(|r| r[phase] >= lo && r[phase] < lo + 30.0),
            "no row in phase {lo}°…{}°",
            lo + 30.0
        );
    }
    // the engine's rocking changes the upper hose's bend: its radius varies over the cycle
    let (lo, hi) = rows
        .iter()
        .map(|r| r[upper])
        .fold((f64::INFINITY, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
    assert!(hi - lo > 0.01, "upper hose radius {lo}…{hi} m");
    // the fan keeps its 25 mm: no clearance violation
    assert!(rows.iter().all(|r| r[fan] > 0.025));
    assert!(
        !reasons.iter().any(|r| r.contains("comes within")),
        "{reasons:?}"
    );
    let upper_bend = reasons
        .iter()
        .find(|r| r.starts_with("hose 'upper': bend_radius check"))
        .unwrap_or_else(|| panic!("{reasons:?}"));
    assert!(
        upper_bend.contains(", at engine block phase "),
        "{upper_bend}"
    );
}

/// A door opened by the timeline (`rotate_part`, then `move_part`): `pliant run` carries
/// the hose end mounted on it to the closed form of the turn, and a timeline naming a
/// part the scene has not is refused with the field and the parts' names.
#[test]
fn a_timeline_that_turns_a_part_runs_and_a_wrong_part_is_named() {
    let timeline: String = SceneText::piece()
        .with(fix("h", 0))
        .with(fix("h", -1).text("part", "door"))
        .with(
            rotate_part("door", [0.0, 0.0, 1.0], [500.0, 0.0, 0.0])
                .number("by_deg", 45.0)
                .number("duration_s", 0.5),
        )
        .with(
            move_part("door")
                .point("to", [0.0, 0.0, 20.0])
                .number("duration_s", 0.2),
        )
        .into();
    let scene = format!("{WEIGHTLESS_MM}solver = \"static\"\n{HOSE3_300}{DOOR}{timeline}");
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("door.toml");
    std::fs::write(&file, &scene).unwrap();
    let out = dir.path().join("out");
    let o = pliant_run(&file, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // the last recorded pose of the hose's last node
    let nodes = std::fs::read_to_string(out.join("nodes.csv")).unwrap();
    let last = nodes
        .lines()
        .rfind(|l| l.split(',').nth(2) == Some("6"))
        .unwrap();
    let v: Vec<f64> = last.split(',').map(|x| x.parse().unwrap()).collect();
    // turned by 45° about the pin, then the door's centre c = (0.32, 0, −0.04) put 20 mm
    // above where the scene placed it: the end at c + (0, 0, 0.02) + R (x − c)
    let (c, s) = (45f64.to_radians().cos(), 45f64.to_radians().sin());
    let expected = [0.32 - 0.02 * c, -0.02 * s, 0.02];
    for k in 0..3 {
        assert!(
            (v[3 + k] - expected[k]).abs() < 1e-9,
            "end at {:?}, expected {expected:?}",
            &v[3..6]
        );
    }
    // swept against the angle the timeline turns the door by (without the lift)
    let lift = scene.find("[[timeline]]\naction = \"move_part\"").unwrap();
    let swept = format!("{}\n[sweep]\npart = \"door\"\n", &scene[..lift]);
    std::fs::write(&file, swept).unwrap();
    let o = pliant_run(&file, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("motion.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(header[1], "angle_deg", "{header:?}");
    // the quintic smooth-step of the turn, 45° · s(t / 0.5 s), at every checked instant
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let tau = (v[0] / 0.5).clamp(0.0, 1.0);
        let s = tau.powi(3) * (10.0 - 15.0 * tau + 6.0 * tau * tau);
        assert!((v[1] - 45.0 * s).abs() < 1e-5, "at {} s: {}°", v[0], v[1]);
    }
    // a part the scene has not
    std::fs::write(
        &file,
        scene.replace("part = \"door\"\naxis", "part = \"lid\"\naxis"),
    )
    .unwrap();
    let o = pliant_run(&file, &out);
    assert!(!o.status.success());
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(
        said.contains("timeline[2].part") && said.contains("parts are: door"),
        "{said}"
    );
}

/// Whether `p` lies inside the closed triangle mesh `mesh`: the parity of a ray's
/// crossings (Möller–Trumbore), the ray off every axis so that it meets no edge of the
/// axis-aligned faces.
fn inside(mesh: &stl_io::IndexedMesh, p: [f64; 3]) -> bool {
    let dir = [1.0, 0.012_345, 0.006_789];
    let v = |i: usize| mesh.vertices[i].0.map(f64::from);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut crossings = 0;
    for f in &mesh.faces {
        let (a, b, c) = (v(f.vertices[0]), v(f.vertices[1]), v(f.vertices[2]));
        let (e1, e2) = (sub(b, a), sub(c, a));
        let q = cross(dir, e2);
        let det = dot(e1, q);
        if det.abs() < 1e-18 {
            continue;
        }
        let s = sub(p, a);
        let u = dot(s, q) / det;
        let r = cross(s, e1);
        let w = dot(dir, r) / det;
        if u < 0.0 || w < 0.0 || u + w > 1.0 {
            continue;
        }
        if dot(e2, r) / det > 0.0 {
            crossings += 1;
        }
    }
    crossings % 2 == 1
}

/// The door-hinge example's swept envelope: one closed STL per hose, in summary.json
/// with its clearance to the pillar (which stands still; the door's is per instant in
/// motion.csv), that clearance no more than the smallest recorded over time and less by
/// at most the envelope's bound (2.42 voxels), and every recorded tube inside the mesh.
#[test]
fn the_door_hinge_example_writes_the_hose_envelope_with_its_clearance_to_the_pillar() {
    let (out, _reasons, rows, header) = run_example("door_hinge.toml");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap())
            .unwrap();
    let envelopes = &summary["envelopes"];
    let h = envelopes["voxel_m"].as_f64().unwrap();
    // hose1: d 10/16 mm, so voxels of min(5 mm, 8 mm / 2)
    assert!((h - 0.004).abs() < 1e-12, "{envelopes}");
    assert_eq!(envelopes["moving_parts"], serde_json::json!(["door"]));
    let hose = &envelopes["hoses"][0];
    assert_eq!(hose["hose"], "door hose");
    assert_eq!(hose["closed"], true);
    let clearance = hose["clearance"].as_array().unwrap();
    assert!(clearance.iter().all(|c| c["part"] != "door"), "{hose}");
    let pillar = clearance
        .iter()
        .find(|c| c["part"] == "pillar")
        .unwrap_or_else(|| panic!("{hose}"))["clearance_m"]
        .as_f64()
        .unwrap();
    let column = header
        .iter()
        .position(|c| c == "clearance_m door hose to pillar")
        .unwrap();
    let recorded = rows.iter().map(|r| r[column]).fold(f64::INFINITY, f64::min);
    println!(
        "door hinge envelope: {} voxels, clearance to the pillar {:.2} mm, smallest recorded {:.2} mm ({:.2} voxels less)",
        hose["voxels"],
        1e3 * pillar,
        1e3 * recorded,
        (recorded - pillar) / h
    );
    assert!(pillar <= recorded + 1e-9, "{pillar} > {recorded}");
    assert!(
        pillar >= recorded - 2.42 * h,
        "{pillar} < {recorded} − 2.42 h"
    );
    // the mesh holds every recorded tube: the nodes of nodes.csv at the checked instants,
    // 8 mm (the outer radius) from each in 14 directions
    let stl = out.path().join(hose["stl"].as_str().unwrap());
    let mesh = stl_io::read_stl(&mut std::fs::File::open(&stl).unwrap()).unwrap();
    assert_eq!(mesh.faces.len() as u64, hose["triangles"].as_u64().unwrap());
    let checked: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let nodes = std::fs::read_to_string(out.path().join("nodes.csv")).unwrap();
    let r = 0.008 * (1.0 - 1e-9);
    let s = 1.0 / 3f64.sqrt();
    let mut directions = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    for i in [-s, s] {
        for j in [-s, s] {
            for k in [-s, s] {
                directions.push([i, j, k]);
            }
        }
    }
    let mut tested = 0;
    for line in nodes.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        if !checked.iter().any(|&t| (t - v[0]).abs() < 5e-7) {
            continue;
        }
        for d in &directions {
            let p = [v[3] + r * d[0], v[4] + r * d[1], v[5] + r * d[2]];
            assert!(
                inside(&mesh, p),
                "t = {} s node {}: {p:?} outside",
                v[0],
                v[2]
            );
            tested += 1;
        }
    }
    assert!(tested > 1000, "{tested} points");
    let html = std::fs::read_to_string(out.path().join("report.html")).unwrap();
    assert!(html.contains("Swept envelopes") && html.contains(hose["stl"].as_str().unwrap()));
    // the same surface as GLB (its contents are checked in pliant-assembly's sweep::glb):
    // a binary glTF 2.0 whose header gives its length, linked from the report
    let glb_name = hose["glb"].as_str().unwrap();
    let glb = std::fs::read(out.path().join(glb_name)).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    assert_eq!(u32::from_le_bytes(glb[4..8].try_into().unwrap()), 2);
    assert_eq!(
        u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
        glb.len()
    );
    assert!(html.contains(glb_name));
}

/// The picture at the worst bend draws the door where it was then (opened 70°), not
/// where the scene placed it: seen from above, its outline reaches along +y.
#[test]
fn the_worst_bend_picture_draws_the_door_at_its_angle() {
    let (out, ..) = run_example("door_hinge.toml");
    let html = std::fs::read_to_string(out.path().join("report.html")).unwrap();
    let picture = html
        .find("when hose 'door hose' was bent tightest")
        .map(|at| &html[at..])
        .unwrap_or_else(|| panic!("no picture of the worst bend"));
    assert!(picture.contains("the parts where they were then"));
    // the first view (from above): the door's polygon, in pixels, y down
    let view = &picture[..picture.find("</svg>").unwrap()];
    let door = view
        .split("<polygon")
        .find(|p| p.contains("<title>door</title>"))
        .unwrap();
    let points: Vec<[f64; 2]> = door
        .split("points=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .split(' ')
        .map(|xy| {
            let mut c = xy.split(',').map(|v| v.parse::<f64>().unwrap());
            [c.next().unwrap(), c.next().unwrap()]
        })
        .collect();
    let span = |k: usize| {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[k]), b.max(p[k]))
            });
        hi - lo
    };
    // closed the door (800 × 30 mm from above) is long in x; at 70° its length is
    // mostly along y: |sin 70°| · 800 > |cos 70°| · 800 + 30
    assert!(span(1) > 1.5 * span(0), "door outline {points:?}");
}
