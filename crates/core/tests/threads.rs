//! The explicit step gives the same bits on 1, 2 or 3 threads: hoses that
//! fall onto each other (hose–hose contact), a stiffened span, fixed and loaded nodes,
//! with and without a rigid floor (the step's split velocity/position update), and the
//! vectorised kernels against the reference element loop.

use glam::{DQuat, DVec3};
use pliant_core::integrators::explicit::step;
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::rod::forces::{add_reference_loads, internal_loads};
use pliant_core::rod::node_view::NodeView;
use pliant_core::rod::stiffened::StiffenedSpan;
use pliant_core::{HoseSpec, Model, RigidPartSpec, SimSettings, State, WorldSpec};

fn world(floor: bool) -> WorldSpec {
    let material = pliant_testkit::hose1_material();
    let hoses = (0..7)
        .map(|h| {
            // wavy hoses stacked closely: they fall onto each other and touch
            let n = 18 + 5 * h; // not multiples of four
            let nodes = (0..=n)
                .map(|i| {
                    let s = i as f64 * 0.024;
                    DVec3::new(
                        s,
                        0.3 * (s * 7.0 + h as f64).sin() * 0.05,
                        0.0155 * h as f64,
                    )
                })
                .collect();
            HoseSpec {
                name: format!("h{h}"),
                material: material.clone(),
                nodes,
                sections: vec![pliant_testkit::hose1_section()],
                normal_hint: Some(DVec3::Z),
            }
        })
        .collect();
    let rigid_parts = if floor {
        vec![RigidPartSpec {
            name: "floor".into(),
            vertices: vec![
                DVec3::new(-1.0, -1.0, -0.05),
                DVec3::new(2.0, -1.0, -0.05),
                DVec3::new(2.0, 1.0, -0.05),
                DVec3::new(-1.0, 1.0, -0.05),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            friction_static: 0.5,
            friction_sliding: 0.4,
            motion: None,
            parent: None,
            movable: false,
        }]
    } else {
        Vec::new()
    };
    WorldSpec {
        hoses,
        rigid_parts,
        settings: SimSettings::default(),
    }
}

fn setup(floor: bool, threads: usize) -> (Model, State) {
    let model = Model::build(&world(floor))
        .unwrap()
        .with_stiffened_spans(&[StiffenedSpan {
            hose: 2,
            first: 4,
            last: 9,
        }])
        .unwrap();
    let mut model = model;
    model.threads = threads;
    let mut state = State::at_rest(&model);
    // bend the hoses out of their rest shape, as the benchmark does
    for h in &model.hoses {
        for (k, i) in h.nodes().enumerate() {
            state.x[i].y += 0.01 * (k as f64 * 0.7).sin();
            state.w[i] = DVec3::new(0.0, 0.0, 3.0 * (k as f64 * 0.3).cos());
        }
        let first = h.first_node;
        state.loads.add(LoadCase::Fix(Fix {
            node: first,
            position: state.x[first],
            orientation: state.q[first],
        }));
        state.loads.add(LoadCase::DeadLoad(DeadLoad {
            node: first + h.node_count - 1,
            force: DVec3::new(0.0, 0.5, 0.0),
            moment: DVec3::new(0.01, 0.0, 0.0),
            ramp: None,
        }));
    }
    (model, state)
}

fn bits(state: &State) -> Vec<u64> {
    let v3 = |v: &[DVec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
    let q4 = |q: &[DQuat]| q.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
    [
        v3(&state.x),
        q4(&state.q),
        v3(&state.v),
        v3(&state.w),
        v3(&state.force),
        v3(&state.moment),
        v3(&state.reaction_force),
        v3(&state.hose_contact_force),
        v3(&state.contact_force),
    ]
    .concat()
    .iter()
    .map(|f| f.to_bits())
    .collect()
}

#[test]
fn one_two_and_three_threads_give_the_same_bits() {
    for floor in [false, true] {
        let mut results = Vec::new();
        for threads in [1, 2, 3] {
            let (model, mut state) = setup(floor, threads);
            assert!(model.hose_chunks.len() > 1, "{:?}", model.hose_chunks);
            for _ in 0..400 {
                step(&model, &mut state);
            }
            assert!(
                state.hose_contact.pairs_in_contact > 0 || floor,
                "the hoses must touch"
            );
            results.push(bits(&state));
        }
        assert!(results[0] == results[1], "1 vs 2 threads (floor {floor})");
        assert!(results[0] == results[2], "1 vs 3 threads (floor {floor})");
    }
}

/// The default: one thread for one hose, the logical cores for several.
#[test]
fn default_thread_count() {
    if std::env::var(pliant_core::model::THREADS_ENV).is_ok() {
        return; // overridden for this run
    }
    let mut w = world(false);
    let many = Model::build(&w).unwrap();
    assert_eq!(many.threads, pliant_core::parallel::available_cores());
    w.hoses.truncate(1);
    assert_eq!(Model::build(&w).unwrap().threads, 1);
    w.settings.threads = Some(3);
    assert_eq!(Model::build(&w).unwrap().threads, 3);
}

/// The internal loads of a whole deformed, moving model (blocks of four with a partial
/// last block per hose, a stiffened span) agree with the reference element loop.
#[test]
fn model_loads_match_the_reference_loop() {
    let (model, mut state) = setup(false, 1);
    for _ in 0..300 {
        step(&model, &mut state);
    }
    let c = NodeView {
        x: &state.x,
        q: &state.q,
        v: &state.v,
        w: &state.w,
        inelastic_history: state.inelastic_view(),
    };
    let n = model.node_count();
    let beta = model.damping_stiffness;
    let (mut f, mut m) = (vec![DVec3::ZERO; n], vec![DVec3::ZERO; n]);
    internal_loads(&model, &c, beta, &mut f, &mut m);
    let (mut fr, mut mr) = (vec![DVec3::ZERO; n], vec![DVec3::ZERO; n]);
    add_reference_loads(&model, &c, beta, &mut fr, &mut mr, |_| false);
    let f_scale = fr.iter().map(|v| v.length()).fold(0.0, f64::max);
    let m_scale = mr.iter().map(|v| v.length()).fold(0.0, f64::max);
    for i in 0..n {
        assert!((f[i] - fr[i]).length() <= 1e-12 * f_scale, "force {i}");
        assert!((m[i] - mr[i]).length() <= 1e-12 * m_scale, "moment {i}");
    }
}
