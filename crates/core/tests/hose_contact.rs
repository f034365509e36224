//! Hose–hose and self contact (SPEC L5): no penetration, action = reaction, static
//! balance, no force between neighbouring beams, self contact of a U, broad phase against
//! brute force, and an unchanged stable time step.

use glam::{DQuat, DVec3};
use pliant_core::contact::hose_hose::closest_segment_segment;
use pliant_core::contact::{hose_contact_forces, BroadPhase};
use pliant_core::health::check;
use pliant_core::integrators::explicit::step;
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::math::exp_map;
use pliant_core::rod::forces::internal_loads;
use pliant_core::rod::node_view::NodeView;
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};
use std::f64::consts::PI;

use pliant_testkit::Lcg;

const R: f64 = 0.010; // outer radius [m]

fn material() -> Material {
    Material::isotropic(12e6, 0.45, 940.0)
}

fn hose(name: &str, nodes: Vec<DVec3>) -> HoseSpec {
    HoseSpec {
        name: name.into(),
        material: material(),
        nodes,
        sections: vec![Section::new(0.014, 2.0 * R)],
        normal_hint: None,
    }
}

fn straight(name: &str, from: DVec3, to: DVec3, elements: usize) -> HoseSpec {
    hose(
        name,
        (0..=elements)
            .map(|i| from.lerp(to, i as f64 / elements as f64))
            .collect(),
    )
}

fn settings(gravity: DVec3, damping_mass: f64) -> SimSettings {
    SimSettings {
        gravity,
        damping_mass,
        ..SimSettings::default()
    }
}

fn build(hoses: Vec<HoseSpec>, s: SimSettings) -> Model {
    Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![],
        settings: s,
    })
    .unwrap()
}

fn fix(state: &mut State, node: usize) {
    let (position, orientation) = (state.x[node], state.q[node]);
    state.loads.add(LoadCase::Fix(Fix {
        node,
        position,
        orientation,
    }));
}

fn dead_load(state: &mut State, node: usize, force: DVec3) {
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node,
        force,
        moment: DVec3::ZERO,
        ramp: None,
    }));
}

fn hose_sum(model: &Model, state: &State, h: usize) -> DVec3 {
    model.hoses[h]
        .nodes()
        .map(|i| state.hose_contact_force[i])
        .sum()
}

/// Largest penetration r₁ + r₂ − distance over all beam pairs of different hoses (brute force).
fn max_penetration_between(model: &Model, state: &State, h1: usize, h2: usize) -> f64 {
    let range = |h: usize| {
        let i = &model.hoses[h];
        i.first_element..i.first_element + i.element_count
    };
    let mut worst = f64::NEG_INFINITY;
    for i in range(h1) {
        for j in range(h2) {
            worst = worst.max(pair_penetration(model, state, i, j));
        }
    }
    worst
}

fn pair_penetration(model: &Model, state: &State, i: usize, j: usize) -> f64 {
    let (a, b) = (model.elements[i].node_a, model.elements[i].node_b);
    let (c, d) = (model.elements[j].node_a, model.elements[j].node_b);
    let x = &state.x;
    let (s, t) = closest_segment_segment(x[a], x[b], x[c], x[d]);
    let dist = (x[a].lerp(x[b], s) - x[c].lerp(x[d], t)).length();
    model.radius[a]
        + s * (model.radius[b] - model.radius[a])
        + model.radius[c]
        + t * (model.radius[d] - model.radius[c])
        - dist
}

#[test]
fn crossing_hoses_pressed_together() {
    // Two equal hoses crossing at right angles at their middle nodes, each fixed at both
    // ends, just touching; a dead load of 5 N presses the upper one's middle node down; no
    // gravity. (Frictionless, a free hose balanced on a crossing has no stable rest: a
    // slide along its axis moves the load off the support; so both are held at the ends.)
    // By symmetry the lower hose carries half the load: with bending stiffness k_b and
    // contact stiffness k_c, C = F/(2 + k_b/k_c) ≈ F/2.
    let l = 0.4;
    let n = 16;
    let z0 = 2.0 * R;
    let model = build(
        vec![
            straight(
                "lower",
                DVec3::new(-l / 2.0, 0.0, 0.0),
                DVec3::new(l / 2.0, 0.0, 0.0),
                n,
            ),
            straight(
                "upper",
                DVec3::new(0.0, -l / 2.0, z0),
                DVec3::new(0.0, l / 2.0, z0),
                n,
            ),
        ],
        settings(DVec3::ZERO, 20.0),
    );
    let mut state = State::at_rest(&model);
    assert!(model.hose_contact.active);
    for h in 0..2 {
        fix(&mut state, model.hoses[h].node(0));
        fix(&mut state, model.hoses[h].node(n));
    }
    let load = DVec3::new(0.0, 0.0, -5.0);
    dead_load(&mut state, model.hoses[1].node(n / 2), load);
    let steps = (2.0 / model.time_step) as usize;
    let mut worst_pen: f64 = 0.0;
    let mut worst_balance: f64 = 0.0;
    for k in 0..steps {
        step(&model, &mut state);
        worst_pen = worst_pen.max(state.hose_contact.max_penetration);
        let (s0, s1) = (hose_sum(&model, &state, 0), hose_sum(&model, &state, 1));
        if s1.length() > 0.0 {
            worst_balance = worst_balance.max((s0 + s1).length() / s1.length());
        }
        if k % 100 == 0 {
            check(&model, &state).unwrap();
        }
    }
    let pen_now = max_penetration_between(&model, &state, 0, 1);
    let (on_lower, on_upper) = (hose_sum(&model, &state, 0), hose_sum(&model, &state, 1));
    let half = 0.5 * load;
    let split = (on_lower - half).length() / half.length();
    let reaction = |h: usize| -> DVec3 {
        [model.hoses[h].node(0), model.hoses[h].node(n)]
            .iter()
            .map(|&i| state.reaction_force[i])
            .sum()
    };
    let lower_balance = (reaction(0) + on_lower).length() / on_lower.length();
    let upper_balance = (reaction(1) + on_upper + load).length() / load.length();
    println!(
        "crossing: dt {:.3e} s, {} steps; max penetration {:.4} mm ({:.2} % of r), at rest {:.4} mm; \
         pairs in contact {}; contact on lower {on_lower:?} N (F/2 = {half:?}), error {split:.2e}; \
         supports + contact on lower {lower_balance:.1e}, on upper (+ load) {upper_balance:.1e}; \
         action/reaction error {worst_balance:.1e}; KE {:.2e} J",
        model.time_step,
        steps,
        worst_pen * 1e3,
        100.0 * worst_pen / R,
        pen_now * 1e3,
        state.hose_contact.pairs_in_contact,
        state.kinetic_energy(&model)
    );
    assert!(worst_pen < 0.05 * R, "penetration {worst_pen} m");
    assert!(pen_now > 0.0, "the hoses should be in contact at rest");
    assert!(
        worst_balance < 1e-9,
        "contact forces not equal and opposite: {worst_balance}"
    );
    assert!(
        split < 0.01,
        "lower hose carries {on_lower:?}, expected {half:?}"
    );
    assert!(lower_balance < 0.01 && upper_balance < 0.01);
}

#[test]
fn hose_rests_in_the_groove_of_two_others() {
    // Two touching parallel hoses along x, fixed at both ends; a third one above their
    // groove (free, 2 mm up) falls under gravity plus dead loads of 0.2 N per node and
    // comes to rest. A free body: the contact force on it must balance its load.
    let l = 0.3;
    let n = 12;
    let g = DVec3::new(0.0, 0.0, -9.81);
    let d = 2.0 * R; // centre distance of the lower pair (just touching)
    let z = d * 3f64.sqrt() / 2.0 + 0.002;
    let model = build(
        vec![
            straight(
                "left",
                DVec3::new(0.0, -d / 2.0, 0.0),
                DVec3::new(l, -d / 2.0, 0.0),
                n,
            ),
            straight(
                "right",
                DVec3::new(0.0, d / 2.0, 0.0),
                DVec3::new(l, d / 2.0, 0.0),
                n,
            ),
            straight("top", DVec3::new(0.0, 0.0, z), DVec3::new(l, 0.0, z), n),
        ],
        settings(g, 20.0),
    );
    let mut state = State::at_rest(&model);
    for h in 0..2 {
        fix(&mut state, model.hoses[h].node(0));
        fix(&mut state, model.hoses[h].node(n));
    }
    let per_node = DVec3::new(0.0, 0.0, -0.2);
    for i in model.hoses[2].nodes() {
        dead_load(&mut state, i, per_node);
    }
    let load: DVec3 = model.hoses[2]
        .nodes()
        .map(|i| model.mass[i] * g + per_node)
        .sum();
    let steps = (2.0 / model.time_step) as usize;
    let mut worst_pen: f64 = 0.0;
    let mut worst_balance: f64 = 0.0;
    for k in 0..steps {
        step(&model, &mut state);
        worst_pen = worst_pen.max(state.hose_contact.max_penetration);
        let total: DVec3 = state.hose_contact_force.iter().sum();
        let scale: f64 = state.hose_contact_force.iter().map(|f| f.length()).sum();
        if scale > 0.0 {
            worst_balance = worst_balance.max(total.length() / scale);
        }
        if k % 100 == 0 {
            check(&model, &state).unwrap();
        }
    }
    let on_top = hose_sum(&model, &state, 2);
    let err = (on_top + load).length() / load.length();
    let lower = hose_sum(&model, &state, 0) + hose_sum(&model, &state, 1);
    let speed = state.v.iter().map(|v| v.length()).fold(0.0, f64::max);
    println!(
        "groove: max penetration {:.4} mm ({:.2} % of r); contact on top {on_top:?} N vs load \
         {load:?} N, error {err:.2e}; on the lower pair {lower:?} N; action/reaction error \
         {worst_balance:.1e}; pairs {}; max speed {speed:.1e} m/s",
        worst_pen * 1e3,
        100.0 * worst_pen / R,
        state.hose_contact.pairs_in_contact
    );
    assert!(worst_pen < 0.05 * R);
    assert!(worst_balance < 1e-9);
    assert!(err < 0.01, "contact {on_top:?} vs load {load:?}");
    assert!((lower + on_top).length() <= 1e-9 * on_top.length());
    assert!(speed < 1e-3);
}

#[test]
fn u_bend_touches_itself_and_stops() {
    // A U in the xy plane: leg A (0.25 m) along +x at y = +3r, leg B (0.2 m) at y = −3r
    // (surfaces 4r apart), joined by a half circle of centre-line radius 3r whose middle
    // node is clamped. A's node at x = 0.2 m and B's tip are pulled towards each other:
    // B's end meets A's side. (Frictionless capsules pressed together are unstable
    // sideways by f/(r₁+r₂); the loads are kept small against the legs' bending stiffness.)
    let bend_r = 3.0 * R;
    let (leg_a_len, leg_b_len) = (0.25, 0.2);
    let (n_a, n_b, n_bend) = (25, 20, 12);
    let mut nodes = Vec::new();
    for i in 0..=n_a {
        nodes.push(DVec3::new(
            leg_a_len * (1.0 - i as f64 / n_a as f64),
            bend_r,
            0.0,
        ));
    }
    for i in 1..n_bend {
        let a = PI / 2.0 + PI * i as f64 / n_bend as f64;
        nodes.push(DVec3::new(bend_r * a.cos(), bend_r * a.sin(), 0.0));
    }
    for i in 0..=n_b {
        nodes.push(DVec3::new(leg_b_len * i as f64 / n_b as f64, -bend_r, 0.0));
    }
    let model = build(vec![hose("u", nodes)], settings(DVec3::ZERO, 20.0));
    let mut state = State::at_rest(&model);
    assert!(model.hose_contact.active);
    let tip_b = model.node_count() - 1;
    let facing = n_a - n_b; // node of leg A at x = 0.2 m
    assert!((state.x[facing].x - leg_b_len).abs() < 1e-12);
    fix(&mut state, n_a + n_bend / 2);
    let f = 0.4;
    dead_load(&mut state, facing, DVec3::new(0.0, -f, 0.0));
    dead_load(&mut state, tip_b, DVec3::new(0.0, f, 0.0));
    let leg_a = 0..n_a; // elements of leg A
    let leg_b = model.elements.len() - n_b..model.elements.len();
    let steps = (3.0 / model.time_step) as usize;
    let mut worst_pen: f64 = 0.0;
    let mut first_touch = None;
    for k in 0..steps {
        step(&model, &mut state);
        worst_pen = worst_pen.max(state.hose_contact.max_penetration);
        if first_touch.is_none() && state.hose_contact.pairs_in_contact > 0 {
            first_touch = Some(state.time);
        }
        if k % 100 == 0 {
            check(&model, &state).unwrap();
        }
    }
    let mut pen_legs = f64::NEG_INFINITY;
    for i in leg_a.clone() {
        for j in leg_b.clone() {
            pen_legs = pen_legs.max(pair_penetration(&model, &state, i, j));
        }
    }
    let on_a: DVec3 = (0..=n_a).map(|i| state.hose_contact_force[i]).sum();
    let max_speed = state.v.iter().map(|v| v.length()).fold(0.0, f64::max);
    let total: DVec3 = state.hose_contact_force.iter().sum();
    let off_plane = state.x.iter().map(|x| x.z.abs()).fold(0.0, f64::max);
    println!(
        "U: first touch at {:?} s; max penetration {:.4} mm; at rest: legs' penetration {:.4} mm, \
         contact force on leg A {on_a:?} N (loads ±{f} N); pairs {}; max speed {max_speed:.2e} m/s; \
         largest |z| {off_plane:.1e} m",
        first_touch,
        worst_pen * 1e3,
        pen_legs * 1e3,
        state.hose_contact.pairs_in_contact
    );
    assert!(first_touch.is_some(), "the legs never touched");
    assert!(pen_legs > 0.0 && pen_legs < 0.05 * R, "legs: {pen_legs}");
    assert!(worst_pen < 0.05 * R);
    assert!(on_a.y > 0.1 * f, "leg A pushed back towards +y: {on_a:?}");
    assert!(total.length() < 1e-9 * on_a.length());
    assert!(max_speed < 1e-3, "still moving: {max_speed} m/s");
}

#[test]
fn bundle_runs_one_second_without_divergence() {
    // Three hoses side by side, fixed at both ends, two more in their grooves, and a sixth
    // dropped across the top at 60°; gravity; one second of contact everywhere.
    let l = 0.3;
    let n = 12;
    let d = 2.0 * R * 1.001; // 0.1 % apart at the start
    let h = d * 3f64.sqrt() / 2.0;
    let mut hoses = Vec::new();
    for col in 0..3 {
        let y = (col as f64 - 1.0) * d;
        hoses.push(straight(
            &format!("bottom {col}"),
            DVec3::new(0.0, y, 0.0),
            DVec3::new(l, y, 0.0),
            n,
        ));
    }
    for col in 0..2 {
        let y = (col as f64 - 0.5) * d;
        hoses.push(straight(
            &format!("middle {col}"),
            DVec3::new(0.0, y, h),
            DVec3::new(l, y, h),
            n,
        ));
    }
    let c = DVec3::new(l / 2.0, 0.0, 2.0 * h + 0.01);
    let dir = DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0);
    hoses.push(straight("top", c - 0.12 * dir, c + 0.12 * dir, 10));
    let model = build(hoses, settings(DVec3::new(0.0, 0.0, -9.81), 1.0));
    let mut state = State::at_rest(&model);
    for h in 0..3 {
        fix(&mut state, model.hoses[h].node(0));
        fix(&mut state, model.hoses[h].node(n));
    }
    let mut worst_pen: f64 = 0.0;
    let mut max_pairs = 0;
    // no energy from nowhere: kinetic + strain + gravity + contact springs (all at the
    // same positions) never exceeds its start
    let mut probe = state.hose_contact.clone();
    let mut out = vec![DVec3::ZERO; model.node_count()];
    let mut energy = |s: &State| {
        hose_contact_forces(&model, &s.x, &s.v, &mut probe, &mut out);
        s.kinetic_energy(&model) + s.strain_energy(&model) + s.gravity_energy(&model) + probe.energy
    };
    let e0 = energy(&state);
    let mut excess: f64 = f64::NEG_INFINITY;
    for k in 0..(1.0 / model.time_step) as usize {
        step(&model, &mut state);
        worst_pen = worst_pen.max(state.hose_contact.max_penetration);
        max_pairs = max_pairs.max(state.hose_contact.pairs_in_contact);
        if k % 20 == 0 {
            excess = excess.max(energy(&state) - e0);
        }
        if k % 50 == 0 {
            check(&model, &state).unwrap();
        }
    }
    check(&model, &state).unwrap();
    let total: DVec3 = state.hose_contact_force.iter().sum();
    println!(
        "bundle: up to {max_pairs} pairs in contact, max penetration {:.4} mm, \
         KE at 1 s {:.2e} J, largest energy gain {excess:.2e} J",
        worst_pen * 1e3,
        state.kinetic_energy(&model)
    );
    assert!(max_pairs > 20);
    assert!(worst_pen < 0.05 * R);
    assert!(excess < 1e-3, "energy grew by {excess} J");
    assert!(
        total.length()
            < 1e-9
                * state
                    .hose_contact_force
                    .iter()
                    .map(|f| f.length())
                    .sum::<f64>()
    );
}

#[test]
fn neighbouring_beams_of_one_hose_give_no_force_at_rest() {
    // Short beams (l₀ = r/2, so up to ~6 neighbours' capsules overlap) on a straight and on
    // a tightly curved hose (rest radius 2 r): no contact force at rest, nor after 0.2 s.
    let straight_hose = straight("straight", DVec3::ZERO, DVec3::new(0.3, 0.0, 0.0), 60);
    let arc_nodes: Vec<DVec3> = (0..=80)
        .map(|i| {
            let a = 1.5 * PI * i as f64 / 80.0;
            DVec3::new(2.0 * R * a.cos(), 2.0 * R * a.sin(), 0.5)
        })
        .collect();
    let model = build(
        vec![straight_hose, hose("arc", arc_nodes)],
        settings(DVec3::ZERO, 1.0),
    );
    let mut state = State::at_rest(&model);
    // the rule excludes every pair whose capsules overlap at rest
    let mut overlapping_at_rest = 0;
    for i in 0..model.elements.len() {
        for j in i + 1..model.elements.len() {
            if pair_penetration(&model, &state, i, j) > 0.0 {
                overlapping_at_rest += 1;
                assert!(model.hose_contact.excluded(i, j), "pair {i}, {j}");
            }
        }
    }
    assert!(overlapping_at_rest > 100);
    // on the straight hose (l₀ = r/2): gap (j−i−1)·l₀ < π r ⇔ j − i ≤ 7 is excluded
    assert!(model.hose_contact.excluded(0, 7));
    assert!(!model.hose_contact.excluded(0, 8));
    for _ in 0..(0.2 / model.time_step) as usize {
        step(&model, &mut state);
        assert_eq!(state.hose_contact.pairs_in_contact, 0);
        assert!(state.hose_contact_force.iter().all(|f| *f == DVec3::ZERO));
    }
}

#[test]
fn broad_phase_finds_exactly_the_brute_force_pairs() {
    let mut rng = Lcg(42);
    // random boxes of very different sizes around the origin (negative cells too)
    let n = 700;
    let mut bp = BroadPhase::new(n);
    for i in 0..n {
        let c = (rng.vec() - 0.5) * 0.3;
        let ext = rng.vec() * if i % 50 == 0 { 0.2 } else { 0.06 };
        bp.lo[i] = c - 0.5 * ext;
        bp.hi[i] = c + 0.5 * ext;
    }
    bp.rebuild();
    let mut found = Vec::new();
    bp.for_each_pair(|i, j| found.push((i.min(j), i.max(j))));
    let mut sorted = found.clone();
    sorted.sort();
    sorted.dedup();
    assert_eq!(sorted.len(), found.len(), "a pair was reported twice");
    let mut brute = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if bp.lo[i].cmple(bp.hi[j]).all() && bp.lo[j].cmple(bp.hi[i]).all() {
                brute.push((i, j));
            }
        }
    }
    println!("random boxes: {} overlapping pairs", brute.len());
    assert!(brute.len() > 500);
    assert_eq!(sorted, brute);

    // random hoses (random walks in a 0.2 m box): contacts found through the broad phase
    // are exactly the brute-force ones
    let mut hoses = Vec::new();
    for h in 0..12 {
        let mut p = (rng.vec() - 0.5) * 0.2;
        let mut nodes = vec![p];
        for _ in 0..20 {
            let d = (rng.vec() - 0.5).normalize() * 0.015;
            p += d;
            nodes.push(p);
        }
        hoses.push(hose(&format!("h{h}"), nodes));
    }
    let model = build(hoses, settings(DVec3::ZERO, 1.0));
    let mut state = State::at_rest(&model);
    let mut out = vec![DVec3::ZERO; model.node_count()];
    hose_contact_forces(
        &model,
        &state.x,
        &state.v,
        &mut state.hose_contact,
        &mut out,
    );
    let ne = model.elements.len();
    let mut brute_contacts = 0;
    for i in 0..ne {
        for j in i + 1..ne {
            if !model.hose_contact.excluded(i, j) && pair_penetration(&model, &state, i, j) > 0.0 {
                brute_contacts += 1;
            }
        }
    }
    println!(
        "random hoses: {} contacts (brute force {}), cell size {:?} m",
        state.hose_contact.pairs_in_contact, brute_contacts, state.hose_contact.broad.cell_size
    );
    assert!(brute_contacts > 10);
    assert_eq!(state.hose_contact.pairs_in_contact, brute_contacts);
    let total: DVec3 = out.iter().sum();
    let scale: f64 = out.iter().map(|f| f.length()).sum();
    assert!(total.length() <= 1e-9 * scale);
}

/// Highest natural frequency of M⁻¹(K_internal + K_contact) linearised at `x0`, by power
/// iteration with central differences (as `pliant_core::rod::timestep::max_frequency`).
fn max_frequency_with_contact(model: &Model, x0: &[DVec3], with_contact: bool) -> f64 {
    let n = model.node_count();
    let mut scratch = State::at_rest(model).hose_contact;
    let zero = vec![DVec3::ZERO; n];
    let mut rng = Lcg(7);
    let mut ux: Vec<DVec3> = (0..n).map(|_| rng.vec() - 0.5).collect();
    let mut ur: Vec<DVec3> = (0..n).map(|_| rng.vec() - 0.5).collect();
    let (mut fp, mut mp, mut fm, mut mm, mut c) = (
        zero.clone(),
        zero.clone(),
        zero.clone(),
        zero.clone(),
        zero.clone(),
    );
    let h = 1e-8;
    let mut lambda = 0.0;
    for _ in 0..300 {
        let norm = ux
            .iter()
            .chain(&ur)
            .map(|v| v.length_squared())
            .sum::<f64>()
            .sqrt();
        for v in ux.iter_mut().chain(ur.iter_mut()) {
            *v /= norm;
        }
        for (sign, f, m) in [(1.0, &mut fp, &mut mp), (-1.0, &mut fm, &mut mm)] {
            let x: Vec<DVec3> = (0..n).map(|i| x0[i] + sign * h * ux[i]).collect();
            let q: Vec<DQuat> = (0..n)
                .map(|i| exp_map(sign * h * ur[i]) * model.rest_q[i])
                .collect();
            internal_loads(
                model,
                &NodeView {
                    x: &x,
                    q: &q,
                    v: &zero,
                    w: &zero,
                    inelastic_history: pliant_core::rod::inelastic::HistoryView::NONE,
                },
                0.0,
                f,
                m,
            );
            if with_contact {
                hose_contact_forces(model, &x, &zero, &mut scratch, &mut c);
                for i in 0..n {
                    f[i] += c[i];
                }
            }
        }
        for i in 0..n {
            ux[i] = -(fp[i] - fm[i]) / (2.0 * h * model.mass[i]);
            ur[i] = -(mp[i] - mm[i]) / (2.0 * h * model.inertia[i]);
        }
        lambda = ux
            .iter()
            .chain(&ur)
            .map(|v| v.length_squared())
            .sum::<f64>()
            .sqrt();
    }
    lambda.sqrt()
}

#[test]
fn contact_keeps_the_stable_time_step() {
    // Worst cases for the contact frequency: crossings at interior nodes (4 beam pairs on
    // one node pair), at end nodes (half masses), and a hose lying along another; all
    // pressed 2 % of r into each other (the hoses are straight: rest shapes, so the
    // internal loads vanish and only the contact is loaded).
    let l = 0.2;
    let n = 8;
    let pen = 0.02 * R;
    let z = 2.0 * R - pen;
    let configs: [(&str, Vec<HoseSpec>); 3] = [
        (
            "crossing at middle nodes",
            vec![
                straight(
                    "a",
                    DVec3::new(-l / 2.0, 0.0, 0.0),
                    DVec3::new(l / 2.0, 0.0, 0.0),
                    n,
                ),
                straight(
                    "b",
                    DVec3::new(0.0, -l / 2.0, z),
                    DVec3::new(0.0, l / 2.0, z),
                    n,
                ),
            ],
        ),
        (
            "crossing at end nodes",
            vec![
                straight("a", DVec3::ZERO, DVec3::new(l, 0.0, 0.0), n),
                straight("b", DVec3::new(0.0, 0.0, z), DVec3::new(0.0, l, z), n),
            ],
        ),
        (
            "lying along",
            vec![
                straight("a", DVec3::ZERO, DVec3::new(l, 0.0, 0.0), n),
                straight("b", DVec3::new(0.0, 0.0, z), DVec3::new(l, 0.0, z), n),
            ],
        ),
    ];
    for (name, hoses) in configs {
        let model = build(hoses, SimSettings::default());
        let report = &model.time_step_report;
        let omega_lim = 2.0 / report.axial_bound.min(report.eigen_bound);
        let x0 = model.rest_x.clone();
        let w0 = max_frequency_with_contact(&model, &x0, false);
        let w1 = max_frequency_with_contact(&model, &x0, true);
        // the contact pair frequency alone: ω_c² = k Σ w²/m ≤ (ω_lim/2)²
        let k = model
            .hose_contact
            .stiffness(&model, 0, model.hoses[1].first_element);
        let m = model.mass[0].min(model.mass[model.hoses[1].first_node]);
        let omega_c = (2.0 * k / m).sqrt();
        let xi = 0.5 * report.damping_stiffness * w1;
        let limit = 2.0 / w1 * ((1.0 + xi * xi).sqrt() - xi);
        println!(
            "{name}: ω_max without contact {w0:.0} rad/s, with {w1:.0} rad/s (ratio {:.3}); \
             ω_lim {omega_lim:.0}; node-node contact ω_c {omega_c:.0} (≤ ω_lim/2 = {:.0}); \
             Δt {:.3e} s vs limit with contact {limit:.3e} s",
            w1 / w0,
            omega_lim / 2.0,
            model.time_step
        );
        assert!(omega_c <= 0.5 * omega_lim * (1.0 + 1e-12));
        assert!(w1 <= omega_lim * 2f64.sqrt(), "{name}: {w1} vs {omega_lim}");
        assert!(
            model.time_step < limit,
            "{name}: step {} above {limit}",
            model.time_step
        );
    }
}

#[test]
#[ignore = "timing report, run with --ignored --nocapture"]
fn cost_per_step_30_hoses_of_30_beams() {
    use std::time::Instant;
    let l = 0.6;
    let n = 30;
    let make = |spacing: f64| {
        let mut hoses = Vec::new();
        for k in 0..30 {
            let (y, z) = ((k % 6) as f64 * spacing, (k / 6) as f64 * spacing);
            hoses.push(straight(
                &format!("h{k}"),
                DVec3::new(0.0, y, z),
                DVec3::new(l, y, z),
                n,
            ));
        }
        build(hoses, settings(DVec3::new(0.0, 0.0, -9.81), 1.0))
    };
    for (name, spacing) in [("bundle, touching", 2.0 * R * 1.001), ("apart", 6.0 * R)] {
        let model = make(spacing);
        let mut state = State::at_rest(&model);
        for h in 0..6 {
            fix(&mut state, model.hoses[h].node(0));
            fix(&mut state, model.hoses[h].node(n));
        }
        for _ in 0..200 {
            step(&model, &mut state);
        }
        let reps = 3000;
        let t = Instant::now();
        for _ in 0..reps {
            step(&model, &mut state);
        }
        let full = t.elapsed().as_secs_f64() / reps as f64;
        let mut out = vec![DVec3::ZERO; model.node_count()];
        let t = Instant::now();
        for _ in 0..reps {
            hose_contact_forces(
                &model,
                &state.x,
                &state.v,
                &mut state.hose_contact,
                &mut out,
            );
        }
        let contact = t.elapsed().as_secs_f64() / reps as f64;
        check(&model, &state).unwrap();
        println!(
            "{name}: 900 beams, step {:.1} µs, of which hose contact {:.1} µs ({} pairs in contact); \
             step without contact ≈ {:.1} µs, ratio {:.2}; dt {:.2e} s → {:.1} simulated s per wall s",
            full * 1e6,
            contact * 1e6,
            state.hose_contact.pairs_in_contact,
            (full - contact) * 1e6,
            full / (full - contact),
            model.time_step,
            model.time_step / full
        );
    }
}
