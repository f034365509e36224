//! Regression inputs for the defects found by hardening (malformed and absurd inputs), run
//! through the fuzz targets in the bounded slice of the test command: each must hold the
//! target's properties (no panic, no broken promise), and the defect's own symptom is
//! checked where the target can see it.

use pliant_assembly::workcell::log::{header_line, line_text, InputLog, LogHeader, LogLine};
use pliant_assembly::workcell::StampedInput;
use pliant_assembly::{Input, WorkcellOptions};
use pliant_fuzz::seeds;
use pliant_fuzz::targets::Target;

fn engine_bay() -> &'static str {
    seeds::SCENES[0]
}

/// A sealed log of `n` resets, 10 ticks apart, with a final mark.
fn log_of(n: u64) -> String {
    let header = LogHeader::new(
        "s",
        "s.toml",
        "scene.toml",
        ".",
        WorkcellOptions::default(),
        1e-3,
    );
    let mut s = header_line(&header);
    for k in 0..n {
        s.push_str(&line_text(&LogLine::Input(StampedInput {
            tick: 10 * k,
            input: Input::Reset,
        })));
    }
    s.push_str(&line_text(&LogLine::Mark { tick: 10 * n }));
    s
}

/// "one corrupt line in the middle, and `pliant replay` exits 0 with the first 96 of
/// 194 inputs": the damage is found and named, with the 97 inputs after it.
#[test]
fn a_corrupt_line_in_the_middle_of_194_inputs_is_damage() {
    let mut lines: Vec<String> = log_of(194).lines().map(String::from).collect();
    let half = lines[97].len() / 2;
    lines[97].truncate(half); // cut mid-line, not the last line
    let text = lines.join("\n") + "\n";
    assert_eq!(Target::SessionLog.run(text.as_bytes()), Ok(()));
    let r = InputLog::read_bytes(text.as_bytes(), "t").unwrap();
    let d = r.damage.expect("the damage is found");
    assert_eq!((d.line, r.log.inputs.len(), d.inputs_after), (98, 96, 97));
}

/// "A log whose tick is 10¹² or 2⁶³ replays for ever": refused as damage.
#[test]
fn absurd_ticks_are_refused() {
    for tick in [1_000_000_000_000u64, 1 << 63] {
        let mut text = log_of(3);
        text.push_str(&line_text(&LogLine::Mark { tick }));
        assert_eq!(Target::SessionLog.run(text.as_bytes()), Ok(()));
        let r = InputLog::read_bytes(text.as_bytes(), "t").unwrap();
        assert!(r.damage.unwrap().reason.contains("beyond"));
        assert_eq!(r.log.end_tick, 30);
    }
}

/// "the three 1e300 load / gravity / rotation cases": refused at load.
#[test]
fn scenes_with_1e300_gravity_load_or_rotation_are_refused() {
    let gravity = engine_bay().replacen("gravity = [0, 0, -9.81]", "gravity = [0, 0, -1e300]", 1);
    let load = format!(
        "{}\n[[timeline]]\naction = \"load\"\nhose = \"upper\"\nnode = -1\nforce_n = [0, 0, 1e300]\n",
        engine_bay()
    );
    let rotation = format!(
        "{}\n[[timeline]]\naction = \"move\"\nhose = \"upper\"\nnode = -1\nrotate = {{ axis = [0, 0, 1], angle_deg = 1e300 }}\nduration_s = 1\n",
        engine_bay()
    );
    for (text, field) in [
        (gravity, "simulation.gravity"),
        (load, "force_n"),
        (rotation, "angle_deg"),
    ] {
        assert_eq!(Target::SceneToml.run(text.as_bytes()), Ok(()));
        let e = pliant_scene::load_scene_str_in(&text, "r.toml", &seeds::examples_dir())
            .err()
            .unwrap_or_else(|| panic!("accepted: {field}"))
            .to_string();
        assert!(e.contains(field) && e.contains("out of range"), "{e}");
    }
}

/// "`pliant calibrate` with a 1e308 mm specimen exits 0 and writes e_bending_mpa = NaN".
#[test]
fn a_1e308_mm_specimen_gives_no_material() {
    let spec = seeds::CALIBRATION_SPEC.replacen("d_outer_mm = 16", "d_outer_mm = 1e308", 1);
    assert_ne!(spec, seeds::CALIBRATION_SPEC);
    assert_eq!(Target::CalibrationSpec.run(spec.as_bytes()), Ok(()));
    let e = pliant_calibrate::Spec::parse(&spec, "s.toml").unwrap_err();
    assert!(e.to_string().contains("out of range"), "{e}");
    let span = seeds::CALIBRATION_SPEC.replacen("length_mm = 200", "length_mm = 1e308", 1);
    assert!(pliant_calibrate::Spec::parse(&span, "s.toml").is_err());
}

/// "About 640 KB of TOML — 5 000 hoses of 4 elements": a fuzzed scene of that size
/// loads or is refused, within the target's limits, without an abort.
#[test]
fn a_scene_of_5000_small_hoses_is_handled() {
    let mut text = String::from("format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n");
    for k in 0..5000 {
        text.push_str(&format!(
            "[[hoses]]\nname = \"h{k}\"\nmaterial = \"hose1\"\nelements = 4\nstart = [0, {k}, 0]\npath = [ {{ line = {{ to = [100, {k}, 0] }} }} ]\n"
        ));
    }
    assert!(text.len() > 300_000);
    assert_eq!(Target::SceneToml.run(text.as_bytes()), Ok(()));
    // the target's limits (2 000 elements) refuse it before building anything
    let options = pliant_scene::LoadOptions {
        limits: pliant_scene::Limits {
            max_elements: 2_000,
            ..Default::default()
        },
        ..Default::default()
    };
    let e = pliant_scene::load_scene_str_with(&text, "many.toml", &seeds::examples_dir(), &options)
        .expect_err("refused");
    assert!(e.to_string().contains("element"), "{e}");
}

/// "a 100 000-character key is echoed whole in an error": the protocol target takes it.
#[test]
fn a_protocol_message_with_a_100000_character_key_is_handled() {
    let key = "k".repeat(100_000);
    let message = format!("{{\"type\":\"grab\",\"{key}\":1}}");
    assert_eq!(Target::Protocol.run(message.as_bytes()), Ok(()));
}

/// The KBL and calibration CSV targets take inputs of absurd numbers.
#[test]
fn absurd_numbers_in_kbl_and_csv_are_handled() {
    let kbl = seeds::KBL[0].replace("<X>", "<X>1e308");
    assert_eq!(Target::Kbl.run(kbl.as_bytes()), Ok(()));
    let csv: String = std::iter::once("force_N,deflection_mm\n".to_string())
        .chain((0..20).map(|k| format!("{},{}\n", k as f64 * 5e306, k as f64 * 1e-3)))
        .collect();
    for k in 0..4 {
        // the input's length picks the curve replaced
        let padded = format!("{csv}{}", "\n".repeat(k));
        assert_eq!(Target::CalibrationCsv.run(padded.as_bytes()), Ok(()));
    }
}

/// A study whose numbers are finite as written but overflow once converted to SI (a
/// material property set in MPa: × 10⁶) was accepted with an infinite mean; it is
/// refused naming the field, and the study target holds.
#[test]
fn a_study_value_that_overflows_in_si_units_is_refused() {
    let seeds = Target::Study.seeds();
    let demo = String::from_utf8(seeds[1].clone()).unwrap();
    let overflowing = demo
        .replace(
            "mean = 9.0\nstd = 1.5\nmin = 6\n",
            "mean = 1e305\nstd = 1.5\nmin = 6\n",
        )
        .replace("levels = [7.5, 9.0, 10.5]", "levels = [7.5, 1e305]");
    assert_ne!(overflowing, demo);
    assert_eq!(Target::Study.run(overflowing.as_bytes()), Ok(()));
}

/// A study whose `vary`, `property` or `length_unit` is a list instead of a name made the
/// reader look the list up as a key (Python's TypeError, found by the study target at
/// input 41 179 of seed 42); it is refused naming the field, and the study target holds.
#[test]
fn a_list_where_a_study_names_a_kind_is_refused() {
    let seeds = Target::Study.seeds();
    let demo = String::from_utf8(seeds[1].clone()).unwrap();
    for (name, list) in [
        ("vary = \"", "vary = [\""),
        ("length_unit = \"", "length_unit = [\""),
        ("property = \"", "property = [\""),
    ] {
        let at = demo.find(name).expect(name);
        let end = demo[at + name.len()..].find('"').unwrap() + at + name.len() + 1;
        let listed = format!(
            "{}{}{}]{}",
            &demo[..at],
            list,
            &demo[at + name.len()..end],
            &demo[end..]
        );
        assert_ne!(listed, demo);
        assert_eq!(Target::Study.run(listed.as_bytes()), Ok(()), "{name}");
    }
}
