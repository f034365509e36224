//! Calibration on the real main harness: name a KBL segment, fit its protection factor
//! back from the EI the model gives it.

use std::path::{Path, PathBuf};

use pliant_harness::bundle::BundleData;
use pliant_harness::model::ProtectionKind;
use pliant_harness::{bundle_of_segment, fit_protection_factor, read_kbl, HarnessError, Stiffness};

fn data(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/harness")
        .join(file)
}

#[test]
fn taped_segment_of_the_main_harness() {
    let h = read_kbl(&data("kblxml_2.4sr-1_tab016120_modulare_ltgs._160718.kbl")).unwrap();
    let d = BundleData::builtin();
    // The taped segment with the most wires.
    let best = h
        .segments
        .iter()
        .map(|s| bundle_of_segment(&h, &d, &s.kbl_id).unwrap())
        .filter(|b| b.protection.map(|p| p.kind) == Some(ProtectionKind::Tape))
        .max_by_key(|b| b.wires.len())
        .unwrap();
    let s = &best.section;
    println!(
        "{}: {} wires, EI slip {:.3e}, bonded {:.3e}, taped {:.3e} N·m²",
        best.kbl_id, s.wire_count, s.ei_slip, s.ei_bond, s.ei
    );
    let fit = fit_protection_factor(
        Stiffness::Bending,
        s.ei,
        &best.wires,
        Some(ProtectionKind::Tape),
    )
    .unwrap();
    assert!((fit.factor - d.protection["tape"].f_ei.value).abs() < 1e-12);
    assert_eq!(fit.key(), "tape");

    // By its <Id> text too.
    let seg = h.segments.iter().find(|x| x.kbl_id == best.kbl_id).unwrap();
    if let Some(name) = &seg.name {
        assert_eq!(bundle_of_segment(&h, &d, name).unwrap().kbl_id, best.kbl_id);
    }
    let e = bundle_of_segment(&h, &d, "Segment_999").unwrap_err();
    println!("{e}");
    assert!(matches!(e, HarnessError::UnknownSegment { .. }));
    assert!(e.to_string().contains("no segment \"Segment_999\""));
}
