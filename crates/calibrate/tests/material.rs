//! The calibrated material loads: material.toml in a scene through the scene loader,
//! library_entry.toml through the library's parser; and the conversions to the
//! project's material fields are those of `pliant_core::Section`.

use pliant_calibrate::calibrate_file;
use pliant_calibrate::synthetic::{example_files, Truth};
use pliant_core::SectionProperties;

#[test]
fn the_material_loads_in_a_scene_and_reproduces_the_measured_stiffness() {
    let truth = Truth::EXAMPLE;
    let dir = tempfile::tempdir().unwrap();
    let (files, _) = example_files(&truth, 0.002, 3);
    for (name, text) in &files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let c = calibrate_file(&dir.path().join("hose.toml")).unwrap();
    let out = dir.path().join("out");
    let paths = c.write(&out).unwrap();
    assert_eq!(paths.len(), 4);
    let material = std::fs::read_to_string(out.join("material.toml")).unwrap();
    let scene = format!(
        "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n\n{material}\n\
         [[hoses]]\nname = \"h\"\nmaterial = \"calibrated_hose\"\nsection = {{ d_inner = 10, d_outer = 16 }}\n\
         elements = 10\nstart = [0, 0, 0]\npath = [{{ line = {{ to = [500, 0, 0] }} }}]\n"
    );
    let loaded = pliant_scene::load_scene_str(&scene, "calibrated.toml")
        .unwrap_or_else(|e| panic!("{e}\n{scene}"));
    let hose = &loaded.world.hoses[0];
    let m = &hose.material;
    assert!((m.e_tension - truth.e_tension).abs() / truth.e_tension < 0.01);
    assert!((m.e_compression - truth.e_compression).abs() / truth.e_compression < 0.01);
    // the section's stiffness, as the solver computes it, is the measured one
    let p = SectionProperties::of(&hose.sections[0], m);
    assert!(
        (p.bending[0] - truth.ei()).abs() / truth.ei() < 0.01,
        "{} vs {}",
        p.bending[0],
        truth.ei()
    );
    assert!(
        (p.torsion - truth.gj()).abs() / truth.gj() < 0.02,
        "{} vs {}",
        p.torsion,
        truth.gj()
    );
    assert!((m.poisson - 0.45).abs() < 0.02, "nu = {}", m.poisson);
    // the library entry parses with the library's own reader, with its sources
    let lib = pliant_scene::Library::parse(
        &std::fs::read_to_string(out.join("library_entry.toml")).unwrap(),
    )
    .unwrap();
    let e = lib.get("calibrated_hose").unwrap();
    assert!((e.material.e_tension - m.e_tension).abs() < 1e-6 * m.e_tension);
    let src = e.values.iter().find(|v| v.key == "e_tension_mpa").unwrap();
    assert!(
        matches!(&src.provenance, pliant_scene::Provenance::Source(s) if s.contains("tension.csv"))
    );
    // JSON and HTML
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("calibration.json")).unwrap())
            .unwrap();
    assert_eq!(json["tests"].as_array().unwrap().len(), 5);
    assert!(json["tests"][0]["range"]["last_line"].as_u64().unwrap() > 10);
    let html = std::fs::read_to_string(out.join("calibration.html")).unwrap();
    assert_eq!(html.matches("<svg").count(), 10);
    assert!(html.contains("linear range"));
}

#[test]
fn a_torsion_test_the_material_cannot_hold_is_given_in_the_section() {
    // G larger than E_b / 2 needs ν < 0: fine; G smaller than E_b / 3 needs ν > 0.5: not
    let truth = Truth {
        shear: 12.0e6 / 4.0,
        ..Truth::EXAMPLE
    };
    let dir = tempfile::tempdir().unwrap();
    let (files, _) = example_files(&truth, 0.001, 5);
    for (name, text) in &files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let c = calibrate_file(&dir.path().join("hose.toml")).unwrap();
    assert!(!c.material.gj_held_by_material);
    assert!(
        c.material.warnings.iter().any(|w| w.contains("gj_n_m2")),
        "{:?}",
        c.material.warnings
    );
    let toml = c.material_toml();
    assert!(
        toml.contains("# section = { d_inner = 10, d_outer = 16, ei1_n_m2"),
        "{toml}"
    );
    assert_eq!(c.material.poisson.value, 0.49);
}

#[test]
fn one_test_alone_marks_what_it_does_not_measure_as_assumptions() {
    let truth = Truth::EXAMPLE;
    let dir = tempfile::tempdir().unwrap();
    let (files, _) = example_files(&truth, 0.002, 2);
    for (name, text) in &files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    // torsion alone: E from G with the default ν, so ν stays an assumption
    let spec = "name = \"rod\"\nd_inner_mm = 10\nd_outer_mm = 16\ndensity_kg_m3 = 1000\n\
                [[tests]]\nkind = \"torsion\"\ncsv = \"torsion.csv\"\nlength_mm = 300\n";
    std::fs::write(dir.path().join("t.toml"), spec).unwrap();
    let c = calibrate_file(&dir.path().join("t.toml")).unwrap();
    let m = &c.material;
    assert!(m.poisson.assumption.is_some() && m.e_tension_mpa.assumption.is_some());
    assert!(m.gj_n_m2.is_some());
    // the section line reproduces GJ exactly; the library entry of a solid rod parses
    let spec = "name = \"rod\"\nd_inner_mm = 0\nd_outer_mm = 16\ndensity_kg_m3 = 1000\n\
                [[tests]]\nkind = \"three_point_bending\"\ncsv = \"bending.csv\"\nlength_mm = 200\n";
    std::fs::write(dir.path().join("b.toml"), spec).unwrap();
    let c = calibrate_file(&dir.path().join("b.toml")).unwrap();
    let lib = pliant_scene::Library::parse(&c.library_toml()).unwrap();
    assert!(lib.get("rod").is_some());
    assert!(c.material_toml().contains("e_bending_mpa"));
    assert!(c.material.e_compression_mpa.assumption.is_some());
}
