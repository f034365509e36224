//! Connector stub and clip (SPEC L6, L7):
//! * `stub`: the press-fit pressure of library hose 3 (d_i 27 mm, d_a 35 mm, E_t
//!   6.9442 MPa, ν 0.49) on a 28 mm stub against the hand calculation (Lamé, SPEC L6:
//!   Q = 13.5/17.5, δ = 0.5 mm → p = 55 989.67 Pa); a hand pushing the hose end on at
//!   10 mm/s feels the sliding press-fit force at the reached depth (within 2 %); released,
//!   the end stays fixed on the stub.
//! * `clip`: the force law's peak equals the snap force at the opening, it is zero at first
//!   touch and at the seat; a hand pressing a hose into a clip and letting go at the seat
//!   leaves it seated, the largest clip force met on the way being the snap force (1 %).

use crate::Check;
use glam::DVec3;
use pliant_assembly::clip::ClipSpec;
use pliant_assembly::stub::{Friction, PressFit, StubSpec};
use pliant_assembly::{
    Action, ClipSite, HandRecord, MovePath, Observer, Runner, StubSite, Timeline,
};
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};

/// A straight hose of `n` elements along +x at height `z`, no gravity.
fn straight(material: &Material, section: Section, n: usize, length: f64, z: f64) -> Model {
    let nodes = (0..=n)
        .map(|i| DVec3::new(length * i as f64 / n as f64, 0.0, z))
        .collect();
    let hose = HoseSpec {
        name: "h".into(),
        material: material.clone(),
        nodes,
        sections: vec![section],
        normal_hint: Some(DVec3::Y),
    };
    let settings = SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 5.0,
        ..Default::default()
    };
    Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: vec![],
        settings,
    })
    .expect("fastener model builds")
}

#[derive(Default)]
struct Trace(Vec<(f64, DVec3, DVec3)>); // (time, hand force, end node position)
impl Observer for Trace {
    fn wants_state(&self, _t: f64) -> bool {
        true
    }
    fn on_hands(&mut self, t: f64, hands: &[HandRecord]) {
        if let Some(r) = hands.first() {
            self.0.push((t, r.load.force, DVec3::ZERO));
        }
    }
    fn on_state(&mut self, _m: &Model, s: &State) {
        if let Some(last) = self.0.last_mut() {
            last.2 = *s.x.last().unwrap_or(&DVec3::ZERO);
        }
    }
}

pub fn run_stub() -> Vec<Check> {
    let material = Material {
        e_tension: 6.9442e6,
        e_compression: 8.6913e6,
        e_bending: None,
        poisson: 0.49,
        density: 1100.0,
        plasticity: None,
        relaxation: Vec::new(),
        hysteresis: None,
    };
    let section = Section::new(0.027, 0.035);
    let (n, len) = (12, 0.3);
    let model = straight(&material, section, n, len, 0.0);
    let Ok(stub) = StubSpec::new(
        DVec3::new(len + 0.002, 0.0, 0.0),
        DVec3::X,
        0.030,
        0.028,
        0.6,
        0.4,
    ) else {
        return vec![Check::failed("stub", "stub spec", "rejected")];
    };
    let Ok(fit) = PressFit::new(&stub, &section, &material) else {
        return vec![Check::failed("stub", "press fit", "rejected")];
    };
    // hand calculation, SPEC L6
    let q2: f64 = (13.5f64 / 17.5).powi(2);
    let p_hand = 6.9442e6 * (0.5 / 14.0) * (1.0 - q2) / ((1.0 + q2) + 0.49 * (1.0 - q2));
    let site = StubSite {
        name: "stub".into(),
        fit: fit.into(),
        end_node: n,
        inner_node: n - 1,
        part: None,
    };
    let actions = vec![
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at: DVec3::new(len - 0.01, 0.0, 0.0),
        },
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::By(vec![DVec3::new(0.024, 0.0, 0.0)])),
            rotation: None,
            duration: 2.4,
            speed: None,
            spline: false,
            wait: true,
        },
        Action::ReleaseHand { hand: 0 },
        Action::Run { duration: 0.5 },
    ];
    let mut state = State::at_rest(&model);
    let mut trace = Trace::default();
    let summary = match Runner::new(&model).with_fasteners(vec![site], vec![]).run(
        &Timeline { actions },
        &mut state,
        &mut trace,
    ) {
        Ok(s) => s,
        Err(e) => return vec![Check::failed("stub", "push on", &e.to_string())],
    };
    let Some(&(_, f, end)) = trace.0.iter().find(|(t, ..)| *t >= 1.2) else {
        return vec![Check::failed("stub", "push on", "no hand samples")];
    };
    let depth = end.x - (len + 0.002);
    let expected = fit.axial_force(depth, Friction::Sliding);
    let fixed = summary.fasteners.first().is_some_and(|f| f.assembled);
    vec![
        Check::relative(
            "stub",
            "press-fit pressure hose 3 on 28 mm stub Pa",
            fit.pressure(),
            p_hand,
            1e-12,
        ),
        Check::relative(
            "stub",
            "hand force pushing on at 10 mm/s vs press-fit law N",
            f.x,
            expected,
            0.02,
        ),
        Check::with_error(
            "stub",
            "end fixed on the stub after release (1 = yes)",
            fixed as u8 as f64,
            1.0,
            (!fixed) as u8 as f64,
            0.0,
        ),
    ]
}

pub fn run_clip() -> Vec<Check> {
    // hose 1 (d_a 16 mm) into a clip with a 12 mm opening and a 17 mm seat, 20 N snap
    let (material, section) = crate::harness::hose1();
    let (n, len, k) = (20, 0.5, 20.0);
    let seat = DVec3::new(0.1625, 0.0, 0.0);
    let Ok(spec) = ClipSpec::new(seat, DVec3::Z, DVec3::X, 0.012, 0.017, k) else {
        return vec![Check::failed("clip", "clip spec", "rejected")];
    };
    let r = section.outer_radius();
    let nn = spec.opening_distance();
    let touch = spec.first_touch(r).unwrap_or(f64::NAN);
    let mut out = vec![
        Check::relative(
            "clip",
            "force at the opening (from outside) N",
            spec.force_along_opening(nn + 1e-12, r),
            k,
            1e-6,
        ),
        Check::scaled(
            "clip",
            "force at first touch N (of k)",
            spec.force_along_opening(touch - 1e-12, r),
            0.0,
            k,
            1e-3,
        ),
        Check::scaled(
            "clip",
            "force at the seat N (of k)",
            spec.force_along_opening(0.0, r),
            0.0,
            k,
            1e-12,
        ),
        Check::relative(
            "clip",
            "pull-in just past the opening N",
            -spec.force_along_opening(nn - 1e-12, r),
            k,
            1e-6,
        ),
    ];
    // the hose lies 5 mm above first touch; a hand presses it into the seat and lets go
    let lift = touch + 0.005;
    let model = straight(&material, section, n, len, lift);
    let mut state = State::at_rest(&model);
    let actions = vec![
        Action::Grab {
            grip: Default::default(),
            hand: 0,
            at: seat + DVec3::new(0.0, 0.0, lift),
        },
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::By(vec![DVec3::new(0.0, 0.0, -lift)])),
            rotation: None,
            duration: 1.0,
            speed: None,
            spline: false,
            wait: true,
        },
        Action::ReleaseHand { hand: 0 },
        Action::Run { duration: 0.5 },
    ];
    let site = ClipSite {
        name: "clip".into(),
        spec,
        hose: 0,
        part: None,
        by_hand: false,
    };
    match Runner::new(&model).with_fasteners(vec![], vec![site]).run(
        &Timeline { actions },
        &mut state,
        &mut Trace::default(),
    ) {
        Ok(summary) => {
            let c = &summary.fasteners[0];
            out.push(Check::with_error(
                "clip",
                "seated after release (1 = yes)",
                c.assembled as u8 as f64,
                1.0,
                (!c.assembled) as u8 as f64,
                0.0,
            ));
            out.push(Check::relative(
                "clip",
                "largest clip force on the way in N",
                c.max_force,
                k,
                0.01,
            ));
        }
        Err(e) => out.push(Check::failed("clip", "snap in", &e.to_string())),
    }
    out
}
