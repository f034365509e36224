//! The hose-contact pair list built by sort and sweep is the uniform grid's list
//! pair for pair — same pairs, same order, same orientation — so that stepping gives the
//! same bits as with the grid: random boxes, random motions of random hoses, and
//! contact-rich runs (one and two threads), with the sweep in use and with the grid as its
//! fallback.

use glam::DVec3;
use pliant_core::contact::sweep::SweepAndPrune;
use pliant_core::contact::{hose_contact_forces, BroadPhase};
use pliant_core::integrators::explicit::step;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};

use pliant_testkit::Lcg;

const R: f64 = 0.010; // outer radius [m]

/// `count` hoses of 20 beams of 15 mm, each a random walk that turns by up to ~30° a step, starting at random points of the box
/// `origin + [0, size]`.
fn random_hoses(rng: &mut Lcg, count: usize, origin: DVec3, size: DVec3) -> Model {
    let mut hoses = Vec::new();
    for h in 0..count {
        let mut p = origin + rng.vec() * size;
        let mut nodes = vec![p];
        let mut d = (rng.vec() - 0.5).normalize();
        for _ in 0..20 {
            d = (d + (rng.vec() - 0.5)).normalize();
            p += d * 0.015;
            nodes.push(p);
        }
        hoses.push(HoseSpec {
            name: format!("h{h}"),
            material: Material::isotropic(12e6, 0.45, 940.0),
            nodes,
            sections: vec![Section::new(0.014, 2.0 * R)],
            normal_hint: None,
        });
    }
    Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![],
        settings: SimSettings {
            gravity: DVec3::new(0.0, 0.0, -9.81),
            damping_mass: 1.0,
            ..SimSettings::default()
        },
    })
    .unwrap()
}

/// Hoses spread along x (the sweep is used) and piled in a 0.2 m box (the grid is).
fn spread(rng: &mut Lcg) -> Model {
    random_hoses(rng, 12, DVec3::ZERO, DVec3::new(2.0, 0.05, 0.05))
}
fn piled(rng: &mut Lcg) -> Model {
    random_hoses(rng, 12, DVec3::splat(-0.1), DVec3::splat(0.2))
}

#[test]
fn sweep_sorted_by_visit_rank_is_the_grids_pair_sequence() {
    let mut rng = Lcg(7);
    for (n, length) in [(700, 3.0), (700, 0.3), (50, 0.1)] {
        let mut bp = BroadPhase::new(n);
        for i in 0..n {
            let c = (rng.vec() - 0.5) * DVec3::new(length, 0.3, 0.3);
            let ext = rng.vec() * if i % 50 == 0 { 0.2 } else { 0.06 };
            bp.lo[i] = c - 0.5 * ext;
            bp.hi[i] = c + 0.5 * ext;
        }
        bp.rebuild();
        let mut grid = Vec::new();
        bp.for_each_pair(|i, j| grid.push((i, j)));
        let mut sweep = SweepAndPrune::new(n);
        let mut ranked = Vec::new();
        let (lo, hi) = (bp.lo.clone(), bp.hi.clone());
        sweep
            .for_each_pair(&lo, &hi, usize::MAX, |i, j| {
                ranked.push(
                    bp.visit_rank(i, j)
                        .expect("overlapping boxes are neighbours"),
                )
            })
            .unwrap();
        ranked.sort_by_key(|r| r.0);
        let swept: Vec<_> = ranked.iter().map(|&(_, a, b)| (a, b)).collect();
        println!("{n} boxes along {length} m: {} pairs", grid.len());
        assert!(grid.len() > n / 10);
        assert_eq!(swept, grid);
        // a budget too small gives up
        assert!(sweep.for_each_pair(&lo, &hi, 0, |_, _| {}).is_err());
    }
}

/// Pair lists and forces of the sweep and of the grid after `motions` random motions of
/// the hoses from their rest positions (each moved by up to 3 cm, its nodes by up to
/// 0.1 mm, 2 mm or 5 mm more); returns the rebuilds, the largest list seen and the sweep's
/// fallbacks to the grid.
fn compare_after_random_motions(model: &Model, rng: &mut Lcg, motions: usize) -> (u64, usize, u64) {
    let state = State::at_rest(model);
    let mut x = state.x.clone();
    let v: Vec<DVec3> = x.iter().map(|_| (rng.vec() - 0.5) * 0.1).collect();
    let mut sweep = state.hose_contact.clone();
    let mut grid = state.hose_contact.clone();
    grid.grid_only = true;
    let (mut out_sweep, mut out_grid) = (vec![DVec3::ZERO; x.len()], vec![DVec3::ZERO; x.len()]);
    let mut largest = 0;
    for k in 0..motions {
        let amplitude = [1e-4, 2e-3, 5e-3][k % 3];
        for h in &model.hoses {
            let shift = (rng.vec() - 0.5) * 0.06;
            for n in h.nodes() {
                x[n] = state.x[n] + shift + (rng.vec() - 0.5) * amplitude;
            }
        }
        hose_contact_forces(model, &x, &v, &mut sweep, &mut out_sweep);
        hose_contact_forces(model, &x, &v, &mut grid, &mut out_grid);
        assert_eq!(sweep.candidates, grid.candidates, "motion {k}");
        for (a, b) in out_sweep.iter().zip(&out_grid) {
            assert_eq!(
                a.to_array().map(f64::to_bits),
                b.to_array().map(f64::to_bits)
            );
        }
        assert_eq!(sweep.pairs_in_contact, grid.pairs_in_contact);
        largest = largest.max(sweep.candidates.len());
    }
    assert_eq!(sweep.rebuilds, grid.rebuilds);
    (sweep.rebuilds, largest, sweep.grid_fallbacks)
}

#[test]
fn sweep_list_is_the_grid_list_after_random_motions() {
    let mut rng = Lcg(42);
    let model = spread(&mut rng);
    let (rebuilds, largest, fallbacks) = compare_after_random_motions(&model, &mut rng, 60);
    println!("spread: {rebuilds} rebuilds, up to {largest} pairs, {fallbacks} grid fallbacks");
    assert!(rebuilds > 20 && largest > 20 && fallbacks == 0);

    let model = piled(&mut rng);
    let (rebuilds, largest, fallbacks) = compare_after_random_motions(&model, &mut rng, 30);
    println!("piled: {rebuilds} rebuilds, up to {largest} pairs, {fallbacks} grid fallbacks");
    assert!(rebuilds > 10 && largest > 100 && fallbacks > 0);
}

/// Positions, velocities and orientations after `steps` steps (first node of every hose
/// fixed), with the list from the sweep or from the grid alone; the sweep's fallbacks.
fn run(model: &Model, grid_only: bool, steps: usize) -> (Vec<u64>, u64, usize) {
    let mut state = State::at_rest(model);
    state.hose_contact.grid_only = grid_only;
    for h in &model.hoses {
        let node = h.first_node;
        let (position, orientation) = (state.x[node], state.q[node]);
        state.loads.add(LoadCase::Fix(Fix {
            node,
            position,
            orientation,
        }));
    }
    let mut contacts = 0;
    for _ in 0..steps {
        step(model, &mut state);
        contacts += state.hose_contact.pairs_in_contact;
    }
    let bits = state
        .x
        .iter()
        .chain(&state.v)
        .chain(&state.w)
        .flat_map(|p| p.to_array())
        .chain(state.q.iter().flat_map(|q| q.to_array()))
        .map(f64::to_bits)
        .collect();
    (bits, state.hose_contact.grid_fallbacks, contacts)
}

#[test]
fn stepping_with_the_sweep_gives_the_grids_bits() {
    let mut rng = Lcg(3);
    for (name, mut model, sweep_used) in [
        ("spread", spread(&mut rng), true),
        ("piled", piled(&mut rng), false),
    ] {
        for threads in [1, 2] {
            model.threads = threads;
            let (bits_grid, _, contacts) = run(&model, true, 1500);
            let (bits_sweep, fallbacks, _) = run(&model, false, 1500);
            println!("{name}, {threads} threads: {contacts} pair-steps in contact, {fallbacks} grid fallbacks");
            assert!(contacts > 1000, "{name}: too little contact to test");
            assert_eq!(fallbacks == 0, sweep_used, "{name}");
            assert!(
                bits_sweep == bits_grid,
                "{name}, {threads} threads: results differ"
            );
        }
    }
}

/// Hose–hose contact pairs that build up during a run are capped at the model's
/// `max_contact_pairs`: hoses laid apart list few pairs; moved onto one line, where every
/// beam of every hose overlaps every other (the grid builds that list), the list stops
/// at the cap and the health check declares the run diverged, with the count and the cap.
#[test]
fn contact_pairs_that_build_up_beyond_the_cap_stop_the_run_as_diverged() {
    const CAP: usize = 200;
    let hoses = (0..40)
        .map(|k| {
            let y = 0.1 * k as f64;
            pliant_testkit::straight_hose1(
                &format!("h{k}"),
                DVec3::new(0.0, y, 0.0),
                DVec3::new(0.2, y, 0.0),
                4,
            )
        })
        .collect();
    let model = Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![],
        settings: SimSettings {
            gravity: DVec3::ZERO,
            max_contact_pairs: CAP,
            ..SimSettings::default()
        },
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    step(&model, &mut state);
    assert!(pliant_core::health::check(&model, &state).is_ok());
    assert!(state.hose_contact.candidates.len() < CAP);

    // every hose moved onto the line y = 0
    for h in &model.hoses {
        for i in h.nodes() {
            state.x[i].y = 0.0;
        }
    }
    step(&model, &mut state);
    assert_eq!(state.hose_contact.candidates.len(), CAP);
    let d = pliant_core::health::check(&model, &state).unwrap_err();
    assert_eq!(
        d.kind,
        pliant_core::health::DivergenceKind::ContactPairs {
            pairs: CAP + 1,
            limit: CAP
        }
    );
    assert!(
        d.to_string()
            .contains("more than 200 hose–hose contact pairs"),
        "{d}"
    );
}
