//! Temporal coherence of rigid contact: the candidate triangles kept from step
//! to step give exactly the contacts of fresh BVH queries — same forces, same positions,
//! to the last bit — over a run where hoses fall onto a fine bumpy floor, lie on it and
//! are dragged across it.

use glam::DVec3;
use pliant_core::integrators::explicit::step;
use pliant_core::loads::{Fix, LoadCase, LoadCaseId};
use pliant_core::{
    HoseSpec, Material, Model, RigidPartSpec, Section, SimSettings, State, WorldSpec,
};

/// A floor of `2·quads²` triangles over [−0.3, 1.0] × [−0.4, 0.6] m, bumps ±2 mm.
fn bumpy_floor(quads: usize) -> RigidPartSpec {
    let mut vertices = Vec::new();
    for j in 0..=quads {
        for i in 0..=quads {
            let x = -0.3 + 1.3 * i as f64 / quads as f64;
            let y = -0.4 + 1.0 * j as f64 / quads as f64;
            let z = -0.02 + 0.002 * (17.0 * x).sin() * (13.0 * y).cos();
            vertices.push(DVec3::new(x, y, z));
        }
    }
    let idx = |i: usize, j: usize| (j * (quads + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..quads {
        for i in 0..quads {
            triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    RigidPartSpec {
        name: "floor".into(),
        vertices,
        triangles,
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion: None,
        parent: None,
        movable: false,
    }
}

/// A horizontal cylinder of radius `r` along y through (0.2, 0, −0.02 − r) m (its top 2 mm
/// below the hoses), as a prism of `n` facets 0.8 m long: long, thin triangles, dozens of
/// them within reach of a beam that lies on it — more than a slot keeps.
fn fine_cylinder(r: f64, n: usize) -> RigidPartSpec {
    let mut vertices = Vec::new();
    for y in [-0.4, 0.4] {
        for k in 0..n {
            let phi = std::f64::consts::TAU * k as f64 / n as f64;
            vertices.push(DVec3::new(
                0.2 + r * phi.cos(),
                y,
                -0.02 - r + r * phi.sin(),
            ));
        }
    }
    let mut triangles = Vec::new();
    for k in 0..n {
        let (a, b) = (k as u32, ((k + 1) % n) as u32);
        let (c, d) = (a + n as u32, b + n as u32);
        triangles.push([a, b, d]);
        triangles.push([a, d, c]);
    }
    RigidPartSpec {
        name: "cylinder".into(),
        vertices,
        triangles,
        friction_static: 0.5,
        friction_sliding: 0.5,
        motion: None,
        parent: None,
        movable: false,
    }
}

/// Three hoses of 20 beams (24 mm, d_a 16 mm) 1 cm above the floor, the last node of
/// each held by a hand (returned) that drags it across the floor.
fn world(quads: usize) -> (Model, State, Vec<LoadCaseId>) {
    world_on(bumpy_floor(quads))
}

/// The hoses of [`world`] above `part`.
fn world_on(part: RigidPartSpec) -> (Model, State, Vec<LoadCaseId>) {
    let hoses = (0..3)
        .map(|h| HoseSpec {
            name: format!("h{h}"),
            material: Material::isotropic(12e6, 0.49, 940.0),
            nodes: (0..=20)
                .map(|i| DVec3::new(0.024 * i as f64, 0.15 * h as f64, -0.01))
                .collect(),
            sections: vec![Section::new(0.010, 0.016)],
            normal_hint: Some(DVec3::Z),
        })
        .collect();
    let model = Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![part],
        settings: SimSettings::default(),
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    let mut hands = Vec::new();
    for h in &model.hoses {
        let n = h.first_node + h.element_count;
        hands.push(state.loads.add(LoadCase::Fix(Fix {
            node: n,
            position: state.x[n],
            orientation: state.q[n],
        })));
    }
    (model, state, hands)
}

/// Moves every hand sideways (0.32 m/s), dragging its hose across the floor.
fn move_hands(model: &Model, state: &mut State, hands: &[LoadCaseId]) {
    let t = state.time;
    for (k, &hand) in hands.iter().enumerate() {
        let h = &model.hoses[k];
        let start = model.rest_x[h.first_node + h.element_count];
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(hand) {
            f.position = start + DVec3::new(-0.1 * t, 0.3 * t, 0.0);
        }
    }
}

#[test]
fn kept_candidates_give_the_same_contacts_as_fresh_queries() {
    let (model, kept, hands) = world(120);
    same_contacts_as_fresh_queries(&model, kept, &hands, 3 * 3000);
}

/// On a finely faceted cylinder a beam has more triangles within reach than a slot
/// keeps: the nearest are kept (and refreshed sooner), and a search the dropped ones could
/// affect falls back to a fresh query — still the same contacts, bit for bit.
#[test]
fn truncated_lists_on_a_fine_mesh_give_the_same_contacts() {
    let (model, kept, hands) = world_on(fine_cylinder(0.05, 512));
    // the hoses hang over the cylinder: fewer, but steady, contacts
    let kept = same_contacts_as_fresh_queries(&model, kept, &hands, 2 * 3000);
    let truncations = kept.contact.candidates.truncations;
    assert!(truncations > 0, "no list was ever truncated");
}

/// Steps `kept` and a copy without kept lists 3000 steps, dragging the hands, and checks
/// that their contacts, forces and motions agree to the last bit, with more than
/// `min_touching` contact points in all; returns `kept`.
fn same_contacts_as_fresh_queries(
    model: &Model,
    mut kept: State,
    hands: &[LoadCaseId],
    min_touching: u64,
) -> State {
    let mut fresh = kept.clone();
    fresh.contact.candidates.enabled = false;
    let (mut touching, mut queries) = (0, 0u64);
    for _ in 0..3000 {
        move_hands(model, &mut kept, hands);
        move_hands(model, &mut fresh, hands);
        step(model, &mut kept);
        step(model, &mut fresh);
        assert_eq!(
            kept.contact.points, fresh.contact.points,
            "step {}",
            kept.step
        );
        assert_eq!(
            kept.contact_force, fresh.contact_force,
            "step {}",
            kept.step
        );
        assert_eq!(kept.x, fresh.x, "step {}", kept.step);
        assert_eq!(kept.v, fresh.v, "step {}", kept.step);
        touching += kept.contact.points.len() as u64;
        queries += (model.node_count() + model.elements.len()) as u64;
    }
    // the run exercised contact, and the lists were really kept
    assert!(
        touching > min_touching,
        "{touching} contact points in 3000 steps"
    );
    let refreshes = kept.contact.candidates.refreshes;
    assert!(
        refreshes > 0 && refreshes * 10 < queries,
        "{refreshes} of {queries}"
    );
    assert!(kept.contact_force.iter().any(|f| f.length() > 0.0));
    kept
}

/// A state moved elsewhere by hand (a reset, a restored snapshot) re-queries.
#[test]
fn teleported_nodes_refresh_their_candidates() {
    let (model, mut kept, _) = world(60);
    kept.loads = Default::default(); // free hoses: they fall and lie on the floor
    let mut fresh = kept.clone();
    fresh.contact.candidates.enabled = false;
    for k in 0..400 {
        if k == 200 {
            for s in [&mut kept, &mut fresh] {
                for x in s.x.iter_mut() {
                    x.y += 0.2;
                    x.x += 0.1;
                }
            }
        }
        step(&model, &mut kept);
        step(&model, &mut fresh);
        assert_eq!(kept.x, fresh.x, "step {}", kept.step);
    }
}
