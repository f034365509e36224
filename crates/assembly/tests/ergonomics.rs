//! SPEC I3 / I4: the built-in ergonomic tables, profiles, classification and colours.

use glam::DVec3;
use pliant_assembly::ergonomics::{
    colour_rgb, colour_value, Duty, ErgonomicLimits, ErgonomicProfile, ErgonomicsError, LoadKind,
    Population, Posture, PullPosture, PushPosture, TorqueGrip,
};

use Duty::{Continuous, Occasional};
use Population::{Men, Women};

/// SPEC I3 typed in again, row by row: (continuous women, continuous men, occasional
/// women, occasional men); guide values as (lo, hi).
type GuideRow = [(f64, f64); 4];
type LimitRow = [f64; 4];

const PUSH_GUIDE: [(PushPosture, GuideRow); 3] = [
    (
        PushPosture::Standing,
        [(1.0, 6.0), (2.0, 11.0), (2.0, 29.0), (4.0, 54.0)],
    ),
    (
        PushPosture::Crouching,
        [(0.3, 1.7), (0.4, 2.2), (0.66, 8.5), (0.7, 11.0)],
    ),
    (
        PushPosture::Sitting,
        [(0.6, 3.6), (1.4, 8.3), (1.2, 18.0), (2.8, 41.0)],
    ),
];
const PUSH_LIMIT: [(PushPosture, LimitRow); 3] = [
    (PushPosture::Standing, [18.0, 32.0, 94.0, 169.0]),
    (PushPosture::Crouching, [15.0, 25.0, 81.0, 131.0]),
    (PushPosture::Sitting, [16.0, 32.0, 85.0, 170.0]),
];
const PULL_GUIDE: [(PullPosture, GuideRow); 3] = [
    (
        PullPosture::StandingLever,
        [(1.0, 6.2), (2.4, 14.0), (2.0, 31.0), (4.7, 71.0)],
    ),
    (
        PullPosture::CrouchingLever,
        [(0.9, 5.3), (1.5, 8.9), (1.8, 27.0), (3.0, 45.0)],
    ),
    (
        PullPosture::Handle,
        [(1.0, 6.0), (2.0, 12.0), (4.0, 20.0), (9.0, 45.0)],
    ),
];
const PULL_LIMIT: [(PullPosture, LimitRow); 3] = [
    (PullPosture::StandingLever, [21.0, 41.0, 112.0, 218.0]),
    (PullPosture::CrouchingLever, [18.0, 22.0, 53.0, 89.0]),
    (PullPosture::Handle, [12.5, 27.0, 67.5, 143.0]),
];
const TORQUE_GUIDE: [(TorqueGrip, GuideRow); 2] = [
    (
        TorqueGrip::Screwdriver,
        [(0.01, 0.07), (0.02, 0.12), (0.02, 0.35), (0.04, 0.59)],
    ),
    (
        TorqueGrip::THandle,
        [(0.05, 0.3), (0.1, 0.6), (0.15, 1.0), (0.3, 1.9)],
    ),
];
const TORQUE_LIMIT: [(TorqueGrip, LimitRow); 2] = [
    (TorqueGrip::Screwdriver, [0.22, 0.35, 1.2, 1.8]),
    (TorqueGrip::THandle, [0.6, 1.2, 3.2, 6.4]),
];

/// The four columns in the order of the rows above.
const COLUMNS: [(Duty, Population); 4] = [
    (Continuous, Women),
    (Continuous, Men),
    (Occasional, Women),
    (Occasional, Men),
];

fn limits() -> &'static ErgonomicLimits {
    ErgonomicLimits::builtin().expect("built-in limits parse")
}

#[test]
fn builtin_tables_match_every_number_of_spec_i3() {
    let l = limits();
    let mut checked = 0;
    for (posture, row) in PUSH_GUIDE {
        for ((duty, pop), (lo, hi)) in COLUMNS.into_iter().zip(row) {
            let g = l.push_guide(posture, pop, duty);
            assert_eq!((g.lo, g.hi), (lo, hi), "push guide {posture} {duty} {pop}");
            checked += 1;
        }
    }
    for (posture, row) in PUSH_LIMIT {
        for ((duty, pop), v) in COLUMNS.into_iter().zip(row) {
            assert_eq!(
                l.push_limit(posture, pop, duty),
                v,
                "push limit {posture} {duty} {pop}"
            );
            checked += 1;
        }
    }
    for (posture, row) in PULL_GUIDE {
        for ((duty, pop), (lo, hi)) in COLUMNS.into_iter().zip(row) {
            let g = l.pull_guide(posture, pop, duty);
            assert_eq!((g.lo, g.hi), (lo, hi), "pull guide {posture} {duty} {pop}");
            checked += 1;
        }
    }
    for (posture, row) in PULL_LIMIT {
        for ((duty, pop), v) in COLUMNS.into_iter().zip(row) {
            assert_eq!(
                l.pull_limit(posture, pop, duty),
                v,
                "pull limit {posture} {duty} {pop}"
            );
            checked += 1;
        }
    }
    for (grip, row) in TORQUE_GUIDE {
        for ((duty, pop), (lo, hi)) in COLUMNS.into_iter().zip(row) {
            let g = l.torque_guide(grip, pop, duty);
            assert_eq!((g.lo, g.hi), (lo, hi), "torque guide {grip} {duty} {pop}");
            checked += 1;
        }
    }
    for (grip, row) in TORQUE_LIMIT {
        for ((duty, pop), v) in COLUMNS.into_iter().zip(row) {
            assert_eq!(
                l.torque_limit(grip, pop, duty),
                v,
                "torque limit {grip} {duty} {pop}"
            );
            checked += 1;
        }
    }
    // 3 + 3 + 3 + 3 + 2 + 2 rows of 4 cells.
    assert_eq!(checked, 64);
}

#[test]
fn every_table_names_its_dissertation_table_and_unit() {
    let l = limits();
    let expected = [
        ("push_guide", "table 3.6"),
        ("push_limit", "table 3.7"),
        ("pull_guide", "table 3.8"),
        ("pull_limit", "table 3.9"),
        ("torque_guide", "table 3.10"),
        ("torque_limit", "table 3.11"),
    ];
    for (info, (key, table)) in l.tables().into_iter().zip(expected) {
        assert_eq!(info.key, key);
        assert!(info.source.contains(table), "{key}: {}", info.source);
        assert!(info.source.contains("SPEC I3"), "{key}: {}", info.source);
        let unit = if key.starts_with("torque") {
            "N m"
        } else {
            "N"
        };
        assert_eq!(info.unit, unit, "{key}");
    }
}

#[test]
fn broken_limit_files_are_refused_with_a_reason() {
    let text = pliant_assembly::ergonomics::ERGONOMICS_TOML;
    let cases = [
        (
            text.replace("women = 18.0", "women = -18.0"),
            "finite and positive",
        ),
        (text.replace("[1.0, 6.0]", "[6.0, 1.0]"), "lo <= hi"),
        (
            text.replace("unit = \"N m\"", "unit = \"N\""),
            "unit must be",
        ),
        (
            text.replace(
                "sitting = { continuous = { women = 16.0",
                "lying = { continuous = { women = 16.0",
            ),
            "unknown push posture `lying`",
        ),
        (
            text.replace("women = 94.0", "women = 1.0"),
            "exceeds the limit value",
        ),
    ];
    for (broken, needle) in cases {
        match ErgonomicLimits::parse(&broken) {
            Err(ErgonomicsError::File(message)) => {
                assert!(message.contains(needle), "`{message}` lacks `{needle}`")
            }
            other => panic!("expected a file error containing `{needle}`, got {other:?}"),
        }
    }
}

#[test]
fn names_parse_leniently_and_refuse_unknown_values_listing_the_allowed_ones() {
    assert_eq!("Standing".parse::<PushPosture>(), Ok(PushPosture::Standing));
    assert_eq!(
        "standing-lever".parse::<PullPosture>(),
        Ok(PullPosture::StandingLever)
    );
    assert_eq!(" T-Handle ".parse::<TorqueGrip>(), Ok(TorqueGrip::THandle));
    assert_eq!("MEN".parse::<Population>(), Ok(Men));
    assert_eq!("continuous".parse::<Duty>(), Ok(Continuous));
    assert_eq!("sitting".parse::<Posture>(), Ok(Posture::Sitting));

    let err = "kneeling".parse::<PushPosture>().unwrap_err();
    assert_eq!(
        err.to_string(),
        "unknown push posture `kneeling`; allowed: standing, crouching, sitting"
    );
    let err = "lever".parse::<PullPosture>().unwrap_err();
    assert!(err
        .to_string()
        .contains("standing_lever, crouching_lever, handle"));
    assert!("wrench"
        .parse::<TorqueGrip>()
        .unwrap_err()
        .to_string()
        .contains("screwdriver, t_handle"));
    assert!("children"
        .parse::<Population>()
        .unwrap_err()
        .to_string()
        .contains("women, men"));
    assert!("daily"
        .parse::<Duty>()
        .unwrap_err()
        .to_string()
        .contains("continuous, occasional"));
}

#[test]
fn profiles_parse_from_strings_and_round_trip() {
    let default = ErgonomicProfile::default();
    assert_eq!(default.push_posture, PushPosture::Standing);
    assert_eq!(default.pull_posture, PullPosture::StandingLever);
    assert!(!default.moments_decide);
    assert_eq!(default.population, Women);
    assert_eq!(default.duty, Occasional);
    assert_eq!("".parse::<ErgonomicProfile>(), Ok(default));

    let p: ErgonomicProfile =
        "posture=sitting, population=men, duty=continuous, moments_decide=true"
            .parse()
            .expect("valid profile");
    assert_eq!(p.push_posture, PushPosture::Sitting);
    assert_eq!(p.pull_posture, PullPosture::Handle);
    assert!(p.moments_decide);
    assert_eq!((p.population, p.duty), (Men, Continuous));
    assert_eq!(p.to_string().parse::<ErgonomicProfile>(), Ok(p));
    assert_eq!(
        ErgonomicProfile::for_posture(Posture::Crouching, Men, Continuous),
        "posture=crouching,population=men,duty=continuous"
            .parse()
            .unwrap()
    );

    for (text, needle) in [
        ("posture", "key=value"),
        ("height=tall", "unknown key `height`"),
        ("push=kneeling", "allowed: standing, crouching, sitting"),
        ("duty=sometimes", "allowed: continuous, occasional"),
        ("moments_decide=maybe", "must be true or false"),
        (
            "torque=screwdriver",
            "twist is judged against the screwdriver row",
        ),
    ] {
        let err = text.parse::<ErgonomicProfile>().unwrap_err();
        assert!(err.to_string().contains(needle), "`{err}` lacks `{needle}`");
    }
}

#[test]
fn force_along_the_reference_direction_is_push_against_it_pull() {
    let l = limits();
    let profile = ErgonomicProfile::default(); // standing, standing lever, women, occasional
    let d = DVec3::new(0.0, 0.0, 2.0); // any length: only the sense counts
                                       // 47 N push plus a 10 N lateral part: |f| counts against the push limit 94 N.
    let f = DVec3::new(10.0, 0.0, 47.0);
    let c = l.classify_force(&profile, f, d).unwrap();
    assert_eq!(c.kind, LoadKind::Push);
    assert_eq!(c.magnitude, f.length());
    assert_eq!(c.limit, 94.0);
    assert_eq!(c.ratio, f.length() / 94.0);
    assert!(!c.exceeds_limit());

    let c = l
        .classify_force(&profile, DVec3::new(0.0, 0.0, -224.0), d)
        .unwrap();
    assert_eq!(c.kind, LoadKind::Pull);
    assert_eq!(c.limit, 112.0);
    assert_eq!(c.ratio, 2.0);
    assert!(c.exceeds_limit());
    assert!(!c.within_guide());

    // Purely lateral and zero forces count as push.
    let c = l
        .classify_force(&profile, DVec3::new(5.0, 0.0, 0.0), d)
        .unwrap();
    assert_eq!(c.kind, LoadKind::Push);
    let c = l.classify_force(&profile, DVec3::ZERO, d).unwrap();
    assert_eq!((c.kind, c.ratio), (LoadKind::Push, 0.0));
    assert!(c.within_guide());
}

#[test]
fn hand_torque_splits_into_twist_on_the_screwdriver_row_and_bending_on_the_t_handle_row() {
    let l = limits();
    let profile: ErgonomicProfile = "population=men,duty=continuous".parse().unwrap();
    // hose axis at the hand along −z (any length); torque 0.3 N·m about it (twist) and
    // 0.4 N·m across it (bending); force 30 N pushing along −z plus 40 N across.
    let d = DVec3::new(0.0, 0.0, -3.0);
    let a = l
        .assess(
            &profile,
            DVec3::new(40.0, 0.0, -30.0),
            DVec3::new(0.0, 0.4, 0.3),
            d,
        )
        .unwrap();
    assert_eq!((a.axial_force, a.lateral_force), (30.0, 40.0));
    assert_eq!(a.force.kind, LoadKind::Push);
    assert_eq!(a.force.magnitude, 50.0);
    assert_eq!(a.twist.kind, LoadKind::Twist);
    assert!((a.twist.magnitude - 0.3).abs() < 1e-15);
    // screwdriver, continuous, men: guide 0.02–0.12, limit 0.35 (tables 3.10 / 3.11)
    assert_eq!((a.twist.guide.hi, a.twist.limit), (0.12, 0.35));
    assert_eq!(a.bending.kind, LoadKind::Bending);
    assert!((a.bending.magnitude - 0.4).abs() < 1e-15);
    // T-handle, continuous, men: guide 0.1–0.6, limit 1.2
    assert_eq!((a.bending.guide.hi, a.bending.limit), (0.6, 1.2));
    // The twist is above its guide range (0.86 of the limit), the bending within it.
    assert!(!a.twist.within_guide() && !a.twist.exceeds_limit());
    assert!(a.bending.within_guide());
    assert_eq!(a.worst_moment().kind, LoadKind::Twist);
}

#[test]
fn moments_are_guidance_unless_the_profile_makes_them_decide() {
    let l = limits();
    let d = DVec3::X;
    // Push 16 N of 32 N (0.5); bending 2.4 N·m, twice the T-handle's 1.2 N·m
    // (dissertation 3.3.3: bending and twist never make an installation fail).
    let (f, t) = (DVec3::new(16.0, 0.0, 0.0), DVec3::new(0.0, 2.4, 0.0));
    let guide: ErgonomicProfile = "population=men,duty=continuous".parse().unwrap();
    let a = l.assess(&guide, f, t, d).unwrap();
    assert_eq!(a.force.ratio, 0.5);
    assert_eq!(a.bending.ratio, 2.0);
    assert!(a.bending.exceeds_limit());
    assert_eq!(a.worst().kind, LoadKind::Push);
    assert!(a.feasible());
    assert_eq!(a.colour_value(), 0.5);

    let decide: ErgonomicProfile = "population=men,duty=continuous,moments_decide=true"
        .parse()
        .unwrap();
    let a = l.assess(&decide, f, t, d).unwrap();
    assert_eq!(a.worst().kind, LoadKind::Bending);
    assert!(!a.feasible());
    assert_eq!(a.colour_value(), 1.0);

    // Pull 82 N of 41 N: infeasible, red, whatever the moments.
    let a = l
        .assess(&guide, DVec3::new(-82.0, 0.0, 0.0), DVec3::ZERO, d)
        .unwrap();
    assert_eq!(a.worst().kind, LoadKind::Pull);
    assert!(!a.feasible());
    assert_eq!(a.colour_value(), 1.0);
    let red = a.colour();
    assert_eq!((red.r, red.g, red.b), (1.0, 0.0, 0.0));
}

#[test]
fn bad_hand_inputs_are_errors() {
    let l = limits();
    let p = ErgonomicProfile::default();
    assert!(l.classify_force(&p, DVec3::X, DVec3::ZERO).is_err());
    assert!(l
        .classify_force(&p, DVec3::new(f64::NAN, 0.0, 0.0), DVec3::X)
        .is_err());
    assert!(l
        .classify_force(&p, DVec3::X, DVec3::new(0.0, f64::INFINITY, 0.0))
        .is_err());
    assert!(l
        .classify_moments(&p, DVec3::splat(f64::NAN), DVec3::X)
        .is_err());
    assert!(l.classify_moments(&p, DVec3::X, DVec3::ZERO).is_err());
}

#[test]
fn colour_runs_blue_green_red() {
    assert_eq!(colour_value(0.0), 0.0);
    assert_eq!(colour_value(0.3), 0.3);
    assert_eq!(colour_value(7.0), 1.0);
    assert_eq!(colour_value(-1.0), 0.0);
    assert_eq!(colour_value(f64::NAN), 1.0);
    let rgb = |c: f64| {
        let x = colour_rgb(c);
        (x.r, x.g, x.b)
    };
    assert_eq!(rgb(0.0), (0.0, 0.0, 1.0));
    assert_eq!(rgb(0.5), (0.0, 1.0, 0.0));
    assert_eq!(rgb(1.0), (1.0, 0.0, 0.0));
    assert_eq!(rgb(3.0), (1.0, 0.0, 0.0));
    assert_eq!(rgb(0.25), (0.0, 0.5, 0.5));
    assert_eq!(rgb(0.75), (0.5, 0.5, 0.0));
}
