//! RULA (McAtamney & Corlett 1993) and REBA (Hignett & McAtamney 2000).
//!
//! The papers' own worked examples could not be retrieved for this build, so the cases
//! here are built from the published tables and scoring rules directly: each expected
//! value was read off the tables by hand (row and column named in the comment). RULA's
//! tables A and B agree value by value with several independent transcriptions in public
//! code; the REBA tables were compared, value by value, with an independent transcription
//! (the `ergonomics` Python package, rs9000/ergonomics `reba.py`, whose doctests —
//! trunk 20°, neck 10°, walking with 50° knee flexion: table A = 4; upper arm 45°,
//! elbow 70°, wrist twisted: table B = 2 — are repeated below). Every table is also
//! checked to never decrease along any of its axes, which the published tables do not.

use glam::DVec3;
use pliant_worker::reba::{self, tables as rt, Coupling, RebaInput};
use pliant_worker::rula::{self, tables as ut, RulaInput};
use pliant_worker::{body, score_posture, Manikin, Placement, Population, ScoreOptions, Sex};

fn rad(deg: f64) -> f64 {
    deg.to_radians()
}

/// A comfortable posture: upper arm 50° (3), elbow 80° (1), wrist neutral (1), twist
/// mid-range (1): table A[3][1][1][1] = 3; 1 kg intermittent: force 0, muscle 0 → C = 3.
/// Neck 15° (2), trunk 30° (3), legs balanced (1): table B[2][3][1] = 4 → D = 4.
/// Table C[3][4] = 4: action level 2.
#[test]
fn rula_moderate_case() {
    let s = rula::score(&RulaInput {
        upper_arm: rad(50.0),
        lower_arm: rad(80.0),
        neck: rad(15.0),
        trunk: rad(30.0),
        legs_balanced: true,
        load_kg: 1.0,
        ..Default::default()
    });
    assert_eq!(
        (s.upper_arm, s.lower_arm, s.wrist, s.wrist_twist),
        (3, 1, 1, 1)
    );
    assert_eq!((s.posture_a, s.wrist_and_arm), (3, 3));
    assert_eq!(
        (s.neck, s.trunk, s.legs, s.posture_b, s.neck_trunk_leg),
        (2, 3, 1, 4, 4)
    );
    assert_eq!((s.grand, s.action_level), (4, 2));
}

/// The worst corner: upper arm 100° (4) + abducted = 5, elbow 30° (2) + across = 3,
/// wrist 20° (3) + deviated = 4, twist near the end (2): table A[5][3][4][2] = 8; static
/// (muscle 1), 12 kg (force 3) → C = 12. Neck in extension (4) + twisted + side-bent = 6,
/// trunk 70° (4) + 2 = 6, legs unbalanced (2): table B[6][6][2] = 9 → D = 13. Table
/// C[8+][7+] = 7: action level 4.
#[test]
fn rula_worst_case() {
    let s = rula::score(&RulaInput {
        upper_arm: rad(100.0),
        arm_abducted: true,
        lower_arm: rad(30.0),
        across_midline_or_out: true,
        wrist: rad(20.0),
        wrist_deviated: true,
        wrist_twist_near_end: true,
        neck: rad(-5.0),
        neck_twisted: true,
        neck_side_bent: true,
        trunk: rad(70.0),
        trunk_twisted: true,
        trunk_side_bent: true,
        legs_balanced: false,
        static_or_repeated: true,
        load_kg: 12.0,
        ..Default::default()
    });
    assert_eq!(
        (s.upper_arm, s.lower_arm, s.wrist, s.wrist_twist),
        (5, 3, 4, 2)
    );
    assert_eq!(
        (s.posture_a, s.muscle_use, s.force, s.wrist_and_arm),
        (8, 1, 3, 12)
    );
    assert_eq!(
        (s.neck, s.trunk, s.legs, s.posture_b, s.neck_trunk_leg),
        (6, 6, 2, 9, 13)
    );
    assert_eq!((s.grand, s.action_level), (7, 4));
}

/// The ranges' bounds and the force score's steps as the paper words them (20° is still
/// score 1, 20.01° is 2; 2 kg intermittent 1, static 2; 10 kg intermittent still 1, more
/// than 10 kg intermittent 2, static 3; a shock 3).
#[test]
fn rula_bounds() {
    assert_eq!(rula::upper_arm_position(20.0), 1);
    assert_eq!(rula::upper_arm_position(20.01), 2);
    assert_eq!(rula::upper_arm_position(-20.01), 2);
    assert_eq!(rula::upper_arm_position(90.0), 3);
    assert_eq!(rula::upper_arm_position(90.01), 4);
    assert_eq!(rula::neck_position(-0.1), 4);
    assert_eq!(rula::neck_position(10.0), 1);
    assert_eq!(rula::trunk_position(0.0), 1);
    assert_eq!(rula::trunk_position(60.01), 4);
    assert_eq!(rula::force_score(1.99, true, false), 0);
    assert_eq!(rula::force_score(2.0, false, false), 1);
    assert_eq!(rula::force_score(2.0, true, false), 2);
    assert_eq!(rula::force_score(10.0, false, false), 1);
    assert_eq!(rula::force_score(10.01, false, false), 2);
    assert_eq!(rula::force_score(10.01, true, false), 3);
    assert_eq!(rula::force_score(0.0, false, true), 3);
    assert_eq!(
        [1, 2, 3, 4, 5, 6, 7].map(rula::action_level),
        [1, 1, 2, 2, 3, 3, 4]
    );
}

/// REBA: trunk 30° (3), neck 25° (2), legs bilateral (1): table A[3][2][1] = 4; 7 kg
/// (load 1) → A = 5. Upper arm 60° (3), elbow 120° (2), wrist 10° (1): table B[3][2][1]
/// = 4; coupling fair (1) → B = 5. Table C[5][5] = 6, activity 1 → REBA 7: medium (2).
#[test]
fn reba_medium_case() {
    let s = reba::score(&RebaInput {
        trunk: rad(30.0),
        neck: rad(25.0),
        load_kg: 7.0,
        upper_arm: rad(60.0),
        lower_arm: rad(120.0),
        wrist: rad(10.0),
        coupling: Coupling::Fair,
        activity: 1,
        ..Default::default()
    });
    assert_eq!(
        (s.trunk, s.neck, s.legs, s.posture_a, s.load, s.score_a),
        (3, 2, 1, 4, 1, 5)
    );
    assert_eq!(
        (s.upper_arm, s.lower_arm, s.wrist, s.posture_b, s.score_b),
        (3, 2, 1, 4, 5)
    );
    assert_eq!((s.score_c, s.reba, s.risk_level), (6, 7, 2));
}

/// The independent transcription's doctests: table A[trunk 2][neck 1][legs 3] = 4 and
/// table B[upper arm 2][lower arm 1][wrist 2] = 2.
#[test]
fn reba_matches_an_independent_transcription() {
    let a = reba::score(&RebaInput {
        trunk: rad(20.0),
        neck: rad(10.0),
        unilateral: true,
        knee_flexion: rad(50.0),
        upper_arm: rad(45.0),
        lower_arm: rad(70.0),
        wrist_deviated_or_twisted: true,
        ..Default::default()
    });
    assert_eq!((a.neck, a.trunk, a.legs, a.posture_a), (1, 2, 3, 4));
    assert_eq!(
        (a.upper_arm, a.lower_arm, a.wrist, a.posture_b),
        (2, 1, 2, 2)
    );
}

/// The worst corner: trunk 70° + twist = 5, neck extension + twist = 3, unilateral with
/// knees at 70° = 4: table A[5][3][4] = 9; 15 kg with shock: load 3 → A = 12. Upper arm
/// 120° + abducted + raised = 6, elbow 10° (2), wrist 30° + twisted = 3: table
/// B[6][2][3] = 9, coupling unacceptable 3 → B = 12. Table C[12][12] = 12 + activity 3 =
/// 15: very high (4).
#[test]
fn reba_worst_case() {
    let s = reba::score(&RebaInput {
        trunk: rad(70.0),
        trunk_twisted_or_side_bent: true,
        neck: rad(-10.0),
        neck_twisted_or_side_bent: true,
        unilateral: true,
        knee_flexion: rad(70.0),
        load_kg: 15.0,
        shock: true,
        upper_arm: rad(120.0),
        arm_abducted_or_rotated: true,
        shoulder_raised: true,
        lower_arm: rad(10.0),
        wrist: rad(30.0),
        wrist_deviated_or_twisted: true,
        coupling: Coupling::Unacceptable,
        activity: 3,
        ..Default::default()
    });
    assert_eq!(
        (s.trunk, s.neck, s.legs, s.posture_a, s.score_a),
        (5, 3, 4, 9, 12)
    );
    assert_eq!(
        (s.upper_arm, s.lower_arm, s.wrist, s.posture_b, s.score_b),
        (6, 2, 3, 9, 12)
    );
    assert_eq!((s.score_c, s.reba, s.risk_level), (12, 15, 4));
    assert_eq!(reba::trunk_position(-25.0), 3);
    assert_eq!(reba::trunk_position(-10.0), 2);
    assert_eq!(
        [1, 2, 3, 4, 7, 8, 10, 11].map(reba::risk_level),
        [0, 1, 1, 2, 2, 3, 3, 4]
    );
}

/// The published tables never decrease along any axis (a worse body part never gives a
/// better score): checked on every pair of neighbours.
#[test]
fn tables_never_decrease() {
    let a = &ut::TABLE_A;
    for u in 0..6 {
        for l in 0..3 {
            for w in 0..4 {
                for t in 0..2 {
                    let v = a[u][l][w][t];
                    if u + 1 < 6 {
                        assert!(a[u + 1][l][w][t] >= v, "RULA A {u} {l} {w} {t}");
                    }
                    if l + 1 < 3 {
                        assert!(a[u][l + 1][w][t] >= v, "RULA A {u} {l} {w} {t}");
                    }
                    if w + 1 < 4 {
                        assert!(a[u][l][w + 1][t] >= v, "RULA A {u} {l} {w} {t}");
                    }
                    if t + 1 < 2 {
                        assert!(a[u][l][w][t + 1] >= v, "RULA A {u} {l} {w} {t}");
                    }
                }
            }
        }
    }
    let b = &ut::TABLE_B;
    for n in 0..6 {
        for t in 0..6 {
            for g in 0..2 {
                let v = b[n][t][g];
                if n + 1 < 6 {
                    assert!(b[n + 1][t][g] >= v, "RULA B {n} {t} {g}");
                }
                if t + 1 < 6 {
                    assert!(b[n][t + 1][g] >= v, "RULA B {n} {t} {g}");
                }
                if g + 1 < 2 {
                    assert!(b[n][t][g + 1] >= v, "RULA B {n} {t} {g}");
                }
            }
        }
    }
    let c = &ut::TABLE_C;
    for i in 0..8 {
        for j in 0..7 {
            if i + 1 < 8 {
                assert!(c[i + 1][j] >= c[i][j], "RULA C {i} {j}");
            }
            if j + 1 < 7 {
                assert!(c[i][j + 1] >= c[i][j], "RULA C {i} {j}");
            }
        }
    }
    let a = &rt::TABLE_A;
    for t in 0..5 {
        for n in 0..3 {
            for g in 0..4 {
                let v = a[t][n][g];
                if t + 1 < 5 {
                    assert!(a[t + 1][n][g] >= v, "REBA A {t} {n} {g}");
                }
                if n + 1 < 3 {
                    assert!(a[t][n + 1][g] >= v, "REBA A {t} {n} {g}");
                }
                if g + 1 < 4 {
                    assert!(a[t][n][g + 1] >= v, "REBA A {t} {n} {g}");
                }
            }
        }
    }
    let b = &rt::TABLE_B;
    for u in 0..6 {
        for l in 0..2 {
            for w in 0..3 {
                let v = b[u][l][w];
                if u + 1 < 6 {
                    assert!(b[u + 1][l][w] >= v, "REBA B {u} {l} {w}");
                }
                if l + 1 < 2 {
                    assert!(b[u][l + 1][w] >= v, "REBA B {u} {l} {w}");
                }
                if w + 1 < 3 {
                    assert!(b[u][l][w + 1] >= v, "REBA B {u} {l} {w}");
                }
            }
        }
    }
    let c = &rt::TABLE_C;
    for i in 0..12 {
        for j in 0..12 {
            if i + 1 < 12 {
                assert!(c[i + 1][j] >= c[i][j], "REBA C {i} {j}");
            }
            if j + 1 < 12 {
                assert!(c[i][j + 1] >= c[i][j], "REBA C {i} {j}");
            }
        }
    }
    // the corners of the published tables
    assert_eq!((ut::TABLE_A[0][0][0][0], ut::TABLE_A[5][2][3][1]), (1, 9));
    assert_eq!((ut::TABLE_B[0][0][0], ut::TABLE_B[5][5][1]), (1, 9));
    assert_eq!((rt::TABLE_A[0][2][0], rt::TABLE_A[4][2][3]), (3, 9));
    assert_eq!((rt::TABLE_C[5][0], rt::TABLE_C[0][11]), (6, 7));
}

/// The manikin: an overhead reach scores worse than a reach at elbow height, and a
/// heavy hand force raises RULA's force score.
#[test]
fn manikin_postures_are_scored() {
    let b = body(Population::new(Sex::Male, 50.0).unwrap()).unwrap();
    let m = Manikin::new(b, Placement::new(DVec3::ZERO, DVec3::X, DVec3::Z).unwrap());
    let o = ScoreOptions::default();
    let easy = m.solve([Some(DVec3::new(0.35, -0.2, 1.0)), None]);
    let high = m.solve([Some(DVec3::new(0.2, -0.2, 2.0)), None]);
    let low = m.solve([Some(DVec3::new(0.45, -0.2, 0.35)), None]);
    let (se, sh, sl) = (
        score_posture(&easy, [10.0, 0.0], &o),
        score_posture(&high, [10.0, 0.0], &o),
        score_posture(&low, [10.0, 0.0], &o),
    );
    assert_eq!(se.rula.trunk, 1, "{easy:?}");
    assert_eq!(sh.rula.upper_arm, 4, "{high:?}");
    assert!(sh.rula.grand > se.rula.grand, "{se:?} {sh:?}");
    assert!(sl.rula.trunk >= 3 && sl.reba.trunk >= 3, "{sl:?}");
    assert!(sl.reba.reba > se.reba.reba);
    let heavy = score_posture(&easy, [150.0, 0.0], &o);
    assert_eq!(heavy.rula.force, 2); // 15.3 kg, intermittent
    let held = score_posture(
        &easy,
        [150.0, 0.0],
        &ScoreOptions {
            static_or_repeated: true,
            ..o
        },
    );
    assert_eq!((held.rula.force, held.rula.muscle_use), (3, 1));
    assert_eq!(heavy.reba.load, 2);
    assert!(heavy.rula.grand >= se.rula.grand);
}

/// What the RULA paper says of its table C in words (McAtamney & Corlett 1993, "Stage 3:
/// development of the grand score and action list"): "For a grand score of 1 or 2, the
/// working posture would have scored 2 or less for both body segment groups A and B".
/// Read on the table: a grand score of at most 2 exactly where scores C and D are both at
/// most 2. (The sentence goes on "and the scores for muscle use and force would be 0",
/// which the table does not hold exactly: posture scores A = B = 1 with muscle use 1 give
/// C = D = 2 and a grand score of 2 — checked below, so that a change of either is seen.)
#[test]
fn rula_grand_score_of_1_or_2_as_the_paper_words_it() {
    for (c, row) in ut::TABLE_C.iter().enumerate() {
        for (d, &grand) in row.iter().enumerate() {
            let (c, d) = (c + 1, d + 1);
            assert_eq!(grand <= 2, c <= 2 && d <= 2, "table C[{c}][{d}] = {grand}");
        }
    }
    // the best posture, held static: muscle use 1 on both groups, grand score still 2
    let s = rula::score(&RulaInput {
        lower_arm: rad(80.0),
        legs_balanced: true,
        static_or_repeated: true,
        ..Default::default()
    });
    assert_eq!((s.posture_a, s.posture_b, s.muscle_use), (1, 1, 1));
    assert_eq!((s.wrist_and_arm, s.neck_trunk_leg, s.grand), (2, 2, 2));
}

/// REBA's body-part ranges as published (Hignett & McAtamney 2000, table 1; restated by
/// the authors as table 42.2 of "Fundamentals and Assessment Tools for Occupational
/// Ergonomics", ch. 42): trunk upright 1, 0–20° flexion or extension 2, 20–60° flexion or
/// more than 20° extension 3, more than 60° flexion 4; neck 0–20° flexion 1, more than
/// 20° flexion or in extension 2; legs bilateral 1, unilateral 2, +1 for knees at
/// 30–60°, +2 beyond 60°; load under 5 kg 0, 5–10 kg 1, more than 10 kg 2, +1 for a
/// shock. Each band checked on both sides of its edges.
#[test]
fn reba_body_part_ranges_as_published() {
    for (deg, score) in [
        (0.0, 1),
        (0.1, 2),
        (20.0, 2),
        (20.1, 3),
        (60.0, 3),
        (60.1, 4),
        (-0.1, 2),
        (-20.0, 2),
        (-20.1, 3),
    ] {
        assert_eq!(reba::trunk_position(deg), score, "trunk {deg}°");
    }
    let neck = |deg: f64| {
        reba::score(&RebaInput {
            neck: rad(deg),
            ..Default::default()
        })
        .neck
    };
    // (through radians and back: the edges themselves are not exact, so a tenth of a
    // degree either side)
    assert_eq!([0.0, 19.9, 20.1, -0.1].map(neck), [1, 1, 2, 2]);
    let legs = |unilateral: bool, knee: f64| {
        reba::score(&RebaInput {
            unilateral,
            knee_flexion: rad(knee),
            ..Default::default()
        })
        .legs
    };
    assert_eq!(
        [
            legs(false, 0.0),
            legs(true, 0.0),
            legs(false, 29.9),
            legs(false, 30.1),
            legs(false, 59.9),
            legs(false, 60.1),
            legs(true, 60.1),
        ],
        [1, 2, 1, 2, 2, 3, 4]
    );
    assert_eq!(
        [4.99, 5.0, 10.0, 10.01].map(|kg| reba::load_score(kg, false)),
        [0, 1, 1, 2]
    );
    assert_eq!(reba::load_score(0.0, true), 1);
}
