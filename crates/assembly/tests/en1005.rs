//! EN 1005-3 as an alternative ergonomic profile — F_R against a hand
//! calculation, the risk zones, the profile's keys and errors, and the verdict's words.

use glam::DVec3;
use pliant_assembly::ergonomics::{
    normal_quantile, En1005Action, En1005Tables, ErgonomicLimits, ErgonomicProfile, LoadKind,
    RiskZone, Standard,
};
use pliant_assembly::workcell::{HandPeak, Peak, RunSummary, Stage, Tally, Verdict};

fn limits() -> &'static ErgonomicLimits {
    ErgonomicLimits::builtin().expect("built-in limits parse")
}

fn profile(text: &str) -> ErgonomicProfile {
    text.parse().unwrap_or_else(|e| panic!("{text}: {e}"))
}

#[test]
fn normal_quantile_matches_the_table_values() {
    // Φ⁻¹ from printed tables (to 7 digits): 1st, 5th, 15th, 50th, 99th percentile
    for (p, z) in [
        (0.01, -2.326_347_9),
        (0.05, -1.644_853_6),
        (0.15, -1.036_433_4),
        (0.5, 0.0),
        (0.99, 2.326_347_9),
    ] {
        assert!((normal_quantile(p) - z).abs() < 1e-7, "z({p})");
    }
    assert!(normal_quantile(0.0).is_nan() && normal_quantile(1.0).is_nan());
}

#[test]
fn default_en1005_profile_has_every_multiplier_one_so_f_r_is_f_b() {
    let p = profile("standard=en1005-3");
    assert_eq!(p.standard, Standard::En1005_3);
    let t = limits().en1005();
    let push = t.limit(&p.en1005, true);
    let pull = t.limit(&p.en1005, false);
    // Table 1, whole body work standing: push 200 N, pull 145 N; 15th percentile,
    // m_v = m_f = m_d = 1
    assert_eq!((push.f_b, push.f_r), (200.0, 200.0));
    assert_eq!((pull.f_b, pull.f_r), (145.0, 145.0));
    assert_eq!((push.m_v, push.m_f, push.m_d), (1.0, 1.0, 1.0));
}

#[test]
fn f_r_equals_the_hand_calculation_for_chosen_multipliers() {
    // Arm work sitting with trunk support, push: F_B = 275 N (Table 1).
    // 5th percentile: F_Br = F_B exp((z_5 − z_15) · 0.3), z from printed tables.
    // velocity high: m_v = 0.8; 1 action/min of 5 s (long, band 0.2–2): m_f = 0.4;
    // 4 h a day (band 2–8 h): m_d = 0.5.
    let p = profile(
        "standard=en1005-3, action=arm_trunk_support, percentile=5, velocity=high, \
         frequency_per_min=1, action_time_s=5, duration_h=4",
    );
    let f_br = 275.0 * ((-1.644_853_6_f64 + 1.036_433_4) * 0.3).exp();
    let by_hand = f_br * 0.8 * 0.4 * 0.5;
    let l = limits().en1005().limit(&p.en1005, true);
    assert!((l.f_br - f_br).abs() < 1e-6 * f_br, "{} vs {f_br}", l.f_br);
    assert!(
        (l.f_r - by_hand).abs() < 1e-6 * by_hand,
        "{} vs {by_hand}",
        l.f_r
    );
    assert_eq!((l.m_v, l.m_f, l.m_d), (0.8, 0.4, 0.5));
    // what a hand push is judged against: guide up to 0.5 F_R, limit 0.7 F_R
    let c = limits()
        .classify_force(&p, DVec3::new(0.0, 0.0, 10.0), DVec3::Z)
        .unwrap();
    assert!((c.limit - 0.7 * by_hand).abs() < 1e-6 * by_hand);
    assert!((c.guide.hi - 0.5 * by_hand).abs() < 1e-6 * by_hand);
    // the short action of the same frequency: m_f = 0.8; domestic use = 1st percentile
    let short = profile("standard=en1005-3, frequency_per_min=1, action_time_s=2, use=domestic");
    let l = limits().en1005().limit(&short.en1005, false);
    let f_br = 145.0 * ((-2.326_347_9_f64 + 1.036_433_4) * 0.3).exp();
    assert_eq!(l.m_f, 0.8);
    assert!((l.f_r - f_br * 0.8).abs() < 1e-6 * f_br);
}

#[test]
fn a_force_in_each_zone_is_judged_in_that_zone() {
    let p = profile("standard=en1005-3");
    let d = DVec3::Z; // push along +d, pull against it; F_R push 200 N, pull 145 N
    for (force, f_r, zone) in [
        (DVec3::new(0.0, 0.0, 99.0), 200.0, RiskZone::Recommended), // m 0.495
        (DVec3::new(0.0, 0.0, 101.0), 200.0, RiskZone::NotRecommended), // 0.505
        (DVec3::new(0.0, 0.0, 139.0), 200.0, RiskZone::NotRecommended), // 0.695
        (DVec3::new(0.0, 0.0, 141.0), 200.0, RiskZone::ToBeAvoided), // 0.705
        (DVec3::new(0.0, 0.0, -72.0), 145.0, RiskZone::Recommended), // 0.497
        (DVec3::new(0.0, 0.0, -80.0), 145.0, RiskZone::NotRecommended), // 0.552
        (DVec3::new(30.0, 0.0, -100.0), 145.0, RiskZone::ToBeAvoided), // |f| 104.4: 0.72
    ] {
        let c = limits().classify_force(&p, force, d).unwrap();
        let j = c.en1005.expect("EN 1005-3 judges the force");
        assert_eq!(j.zone, zone, "{force}");
        assert_eq!(j.f_r, f_r);
        assert!((j.m_r - force.length() / f_r).abs() < 1e-12);
        // Pliant's terms: within the guide = recommended, over the limit = to be avoided
        assert_eq!(c.within_guide(), zone == RiskZone::Recommended, "{force}");
        assert_eq!(c.exceeds_limit(), zone == RiskZone::ToBeAvoided, "{force}");
    }
    // the dissertation's profile gives no EN 1005-3 judgement
    let c = limits()
        .classify_force(&ErgonomicProfile::default(), DVec3::Z, d)
        .unwrap();
    assert!(c.en1005.is_none());
}

#[test]
fn moments_are_still_judged_by_the_torque_tables() {
    // EN 1005-3 gives no turning limits: twist and bending keep tables 3.10 / 3.11
    let en = profile("standard=en1005-3");
    let a = limits()
        .assess(&en, DVec3::Z, DVec3::new(0.5, 0.0, 0.5), DVec3::Z)
        .unwrap();
    let b = limits()
        .assess(
            &ErgonomicProfile::default(),
            DVec3::Z,
            DVec3::new(0.5, 0.0, 0.5),
            DVec3::Z,
        )
        .unwrap();
    assert_eq!((a.twist, a.bending), (b.twist, b.bending));
}

#[test]
fn profile_round_trips_and_the_default_is_unchanged() {
    let p = profile(
        "population=men, standard=en1005-3, action=arm, percentile=10, velocity=high, \
         frequency_per_min=3, action_time_s=1.5, duration_h=2",
    );
    assert_eq!(p.en1005.action, En1005Action::Arm);
    assert_eq!(p.to_string().parse::<ErgonomicProfile>(), Ok(p));
    // the default profile writes as before (no standard key) and judges by the tables
    let d = ErgonomicProfile::default();
    assert_eq!(d.standard, Standard::Dissertation);
    assert!(!d.to_string().contains("standard"), "{d}");
    // back to the dissertation: the EN 1005-3 parameters are dropped
    let back = profile("standard=en1005-3, action=arm, standard=dissertation");
    assert_eq!(back, ErgonomicProfile::default());
}

#[test]
fn bad_keys_and_values_name_the_key() {
    for (text, needle) in [
        (
            "action=arm",
            "`action` is an EN 1005-3 parameter: give `standard=en1005-3` first",
        ),
        (
            "standard=iso-11228",
            "unknown standard `iso-11228`; allowed: dissertation, en1005_3",
        ),
        (
            "standard=en1005-3, action=kneeling",
            "unknown EN 1005-3 action `kneeling`; allowed: whole_body, arm_trunk_support, arm",
        ),
        (
            "standard=en1005-3, velocity=fast",
            "unknown EN 1005-3 velocity `fast`; allowed: low, high",
        ),
        (
            "standard=en1005-3, use=garage",
            "`use` must be professional or domestic",
        ),
        (
            "standard=en1005-3, percentile=0.5",
            "`percentile` must lie in [1, 50]",
        ),
        (
            "standard=en1005-3, percentile=many",
            "`percentile` must be a number",
        ),
        (
            "standard=en1005-3, frequency_per_min=30",
            "`frequency_per_min` must lie in [0, 20] per minute",
        ),
        (
            "standard=en1005-3, duration_h=10",
            "`duration_h` must lie in [0, 8] h",
        ),
        (
            "standard=en1005-3, action_time_s=-1",
            "`action_time_s` must lie in",
        ),
        (
            "standard=en1005-3, duration_h=NaN",
            "`duration_h` must lie in",
        ),
    ] {
        let err = text.parse::<ErgonomicProfile>().unwrap_err().to_string();
        assert!(err.contains(needle), "`{text}`: `{err}` lacks `{needle}`");
    }
}

#[test]
fn data_file_errors_name_the_table() {
    let text = pliant_assembly::ergonomics::EN1005_3_TOML;
    for (from, to, needle) in [
        (
            "whole_body_push = 200.0",
            "whole_body_push = -200.0",
            "basic_force.whole_body_push",
        ),
        ("long = 0.4", "long = 1.4", "frequency.bands[1]"),
        (
            "{ max_h = 2.0, m = 0.8 }",
            "{ max_h = 0.5, m = 0.8 }",
            "duration bands",
        ),
        (
            "not_recommended_max = 0.7",
            "not_recommended_max = 0.4",
            "risk_zones",
        ),
        (
            "arm = { push = \"arm_push\"",
            "arm = { push = \"arm_shove\"",
            "no row `arm_shove`",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let err = En1005Tables::parse(&text.replace(from, to))
            .unwrap_err()
            .to_string();
        assert!(err.contains(needle), "`{err}` lacks `{needle}`");
    }
    // every table says where it comes from
    let t = En1005Tables::parse(text).unwrap();
    for (key, source) in t.sources() {
        assert!(source.contains("EN 1005-3"), "{key}: {source}");
    }
}

#[test]
fn verdict_names_the_standard_and_the_zone_of_each_hand_load() {
    let p = profile("standard=en1005-3"); // F_R push 200 N, pull 145 N
    let mut tally = Tally::default();
    tally.hand_peaks.push(HandPeak {
        hand: 0,
        push: Peak {
            magnitude: 150.0, // m_r 0.75: to be avoided
            time: 2.0,
            fastener: None,
        },
        pull: Peak {
            magnitude: 80.0, // m_r 0.55: not recommended
            time: 3.0,
            fastener: None,
        },
        ..Default::default()
    });
    tally.hand_peaks.push(HandPeak {
        hand: 1,
        push: Peak {
            magnitude: 60.0, // 0.3: recommended
            time: 1.0,
            fastener: None,
        },
        ..Default::default()
    });
    let run = RunSummary {
        hand_peaks: tally.judge_hands(Some(limits()), &p),
        standard: p.standard,
        ..Default::default()
    };
    let v = Verdict::judge(&run, None, Stage::Final);
    assert_eq!(v.feasible, Some(false));
    assert_eq!(v.standard, "EN 1005-3:2002+A1:2008");
    assert!(
        v.reasons
            .iter()
            .any(|r| r.starts_with("hand 0: push of 150.0 N at t = 2.00 s is TO BE AVOIDED (m_r = F/F_R = 0.75 > 0.7; EN 1005-3, whole body work, standing: F_R = 200.0 N")),
        "{:?}",
        v.reasons
    );
    assert!(
        v.warnings
            .iter()
            .any(|w| w.starts_with("hand 0: pull of 80.0 N at t = 3.00 s is NOT RECOMMENDED (0.5 < m_r = F/F_R = 0.55 ≤ 0.7")),
        "{:?}",
        v.warnings
    );
    assert_eq!(v.zones.len(), 3, "{:?}", v.zones);
    assert!(v.zones[2].starts_with("hand 1: push of 60.0 N at t = 1.00 s is RECOMMENDED"));
    assert_eq!(run.hand_peaks[0].worst_kind, Some(LoadKind::Push));
    // the dissertation's profile: no zones, its own standard named
    let run = RunSummary {
        hand_peaks: tally.judge_hands(Some(limits()), &ErgonomicProfile::default()),
        ..Default::default()
    };
    let v = Verdict::judge(&run, None, Stage::Final);
    assert!(v.zones.is_empty());
    assert_eq!(v.standard, "dissertation tables 3.6–3.11 (Schmidtke)");
    assert!(v.reasons[0].contains("table 3.7"), "{:?}", v.reasons);
}
