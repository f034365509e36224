//! The memory estimate against the measured peak: `pliant run` of scenes that
//! stress each term of the estimate (`pliant_scene::budget`) — beam elements, many hoses
//! (the report's per-hose profiles and scene pictures), part triangles, hose–hose contact
//! pairs, the series a run records in memory (8 hands recorded every step for 25 000
//! steps) — in a child process whose peak resident memory is read from the kernel
//! (`wait4`'s `ru_maxrss`; nothing large is built in this process, whose resident memory
//! a child would inherit). Each run has a fixed number of steps: nothing here depends on
//! the machine's speed.
//!
//! The stated factor: the estimate is at least the measured peak, and at most
//! [`FACTOR`] times it. Measured (release build, 2026-11-29): 1 hose × 20 000 elements
//! 100 MB / 48 MB ≈ 2.1×, 1 000 hoses × 20 100 / 54 MB ≈ 1.8×, 327 680 triangles
//! 184 / 135 MB ≈ 1.4×, 1 000 hoses × 4 on one line (5·10⁶ contact pairs) 113 / 66 MB
//! ≈ 1.7×, the recorded series 36 / 26 MB ≈ 1.3× (without the series in the estimate
//! 16 / 26 MB ≈ 0.6×).

#![cfg(target_os = "linux")]

use std::path::Path;
use std::process::Command;

/// Largest ratio of the estimate to the measured peak.
const FACTOR: f64 = 3.0;

/// A scene of `hoses` = (y \[mm\], length \[mm\], elements) along +x, an optional part,
/// run for `duration` seconds.
fn scene(hoses: &[(f64, f64, usize)], part: &str, duration: f64) -> String {
    let mut s = String::from("format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n");
    s.push_str(part);
    for (k, (y, length, elements)) in hoses.iter().enumerate() {
        s.push_str(&format!(
            "[[hoses]]\nname = \"h{k}\"\nmaterial = \"hose1\"\nstart = [0, {y}, 0]\n\
             path = [{{ line = {{ to = [{length}, {y}, 0] }} }}]\nelements = {elements}\n"
        ));
    }
    s.push_str(&format!(
        "[[timeline]]\naction = \"run\"\nduration_s = {duration}\n"
    ));
    s
}

/// Peak resident memory \[bytes\] of `pliant run SCENE` (its exit status is not judged:
/// a run that diverges has had its peak too) and the time step it ran at \[s\] (from its
/// banner: no model is built in this process, whose memory a child would inherit).
fn peak_of_run(scene: &Path, out: &Path) -> (u64, f64) {
    let log = out.with_extension("stderr");
    #[allow(clippy::zombie_processes)] // waited for by wait4 below, which gives its rusage
    let child = Command::new(env!("CARGO_BIN_EXE_pliant"))
        .args(["run", "--quiet", "--threads", "1"])
        .arg(scene)
        .arg("--out")
        .arg(out)
        .stdout(std::process::Stdio::null())
        .stderr(std::fs::File::create(&log).unwrap())
        .spawn()
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: a zeroed rusage is a valid value for wait4 to fill; pid is our child's.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let waited = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(waited, pid, "wait4");
    let banner = std::fs::read_to_string(&log).unwrap();
    let dt = banner
        .split(", time step ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no time step in the banner:\n{banner}"));
    (usage.ru_maxrss as u64 * 1024, dt) // kB on Linux
}

/// One hose held by `hands` hands a quarter of its length apart (at most 8, the
/// timeline's hands), recorded every step for `steps` steps of the scene's time step:
/// the hands' series grow with the run.
fn held_scene(dir: &Path, hands: usize, steps: f64) -> String {
    let with_duration = |duration: f64| {
        let mut s = String::from(
            "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n\
             [output]\nrecord_interval_s = 0\n",
        );
        s.push_str(&format!(
            "[[hoses]]\nname = \"h\"\nmaterial = \"hose1\"\nstart = [0, 0, 0]\n\
             path = [{{ line = {{ to = [{}, 0, 0] }} }}]\nelements = {}\n",
            40 * hands,
            4 * hands
        ));
        for k in 0..hands {
            let x = 40 * k + 20;
            s.push_str(&format!(
                "[[timeline]]\naction = \"grab\"\nhand = {k}\nat = [{x}, 0, 0]\n"
            ));
        }
        s.push_str(&format!(
            "[[timeline]]\naction = \"run\"\nduration_s = {duration}\n"
        ));
        s
    };
    let probe = dir.join("probe.toml");
    std::fs::write(&probe, with_duration(1e-3)).unwrap();
    let dt = pliant_scene::load_scene_file(&probe)
        .unwrap()
        .build_model()
        .unwrap()
        .time_step;
    with_duration(steps * dt)
}

#[test]
fn the_memory_estimate_bounds_the_measured_peak_within_a_stated_factor() {
    let dir = tempfile::tempdir().unwrap();
    let ball = "[[parts]]\nname = \"ball\"\nsphere = { radius = 100, subdivisions = 7 }\n\
                position = [250, 0, -200]\n";
    let cases = [
        ("elements", scene(&[(0.0, 20_000.0, 20_000)], "", 2e-5)),
        (
            "hoses",
            scene(
                &(0..1000)
                    .map(|k| (30.0 * k as f64, 500.0, 20))
                    .collect::<Vec<_>>(),
                "",
                2e-3,
            ),
        ),
        ("triangles", scene(&[(0.0, 500.0, 10)], ball, 1e-3)),
        (
            "contact pairs",
            scene(&vec![(0.0, 500.0, 4); 1000], "", 1e-3),
        ),
        ("recorded series", held_scene(dir.path(), 8, 25_000.0)),
    ];
    let mut report = Vec::new();
    for (what, text) in cases {
        let path = dir.path().join(format!("{}.toml", what.replace(' ', "_")));
        std::fs::write(&path, &text).unwrap();
        let (peak, dt) = peak_of_run(&path, &dir.path().join(what.replace(' ', "_")));
        // the scene's own estimate and the series its run records in memory, as `pliant
        // run` checks them before it starts
        let loaded = pliant_scene::load_scene_file(&path).unwrap();
        let estimate = loaded.estimate.memory_bytes() + loaded.recorded(dt, false).bytes();
        let ratio = estimate as f64 / peak as f64;
        report.push(format!(
            "{what}: estimate {} MB, peak {} MB, ratio {ratio:.2}",
            estimate / 1_000_000,
            peak / 1_000_000
        ));
        assert!(
            (1.0..=FACTOR).contains(&ratio),
            "{what}: the estimate is {ratio:.2} × the measured peak (want 1 to {FACTOR}):\n{}",
            report.join("\n")
        );
    }
    eprintln!("{}", report.join("\n"));
}
