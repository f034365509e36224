use glam::{DQuat, DVec3};
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::relax::{relax, RelaxOptions};
use pliant_core::*;

#[test]
fn tip_load_lambda_1() {
    let n = 40;
    let len = 1.0;
    let nodes: Vec<DVec3> = (0..=n)
        .map(|i| DVec3::new(len * i as f64 / n as f64, 0.0, 0.0))
        .collect();
    let mat = Material::isotropic(12e6, 0.49, 940.0);
    let sec = Section::new(0.010, 0.016);
    let spec = WorldSpec {
        hoses: vec![HoseSpec {
            name: "c".into(),
            material: mat.clone(),
            nodes,
            sections: vec![sec],
            normal_hint: None,
        }],
        settings: SimSettings {
            gravity: DVec3::ZERO,
            damping_mass: 0.0,
            damping_stiffness: None,
            ..Default::default()
        },
    };
    let model = Model::build(&spec).unwrap();
    println!("{:?}", model.time_step_report);
    let mut state = State::at_rest(&model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
    }));
    let ei = mat.bending_modulus() * sec.second_moment();
    let p = 1.0 * ei / (len * len);
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node: n,
        force: DVec3::new(0.0, -p, 0.0),
        moment: DVec3::ZERO,
    }));
    let t = std::time::Instant::now();
    let rep = relax(
        &model,
        &mut state,
        &RelaxOptions {
            force_tolerance: 1e-7 * p,
            moment_tolerance: 1e-7 * p * len,
            max_steps: 2_000_000,
        },
    )
    .unwrap();
    println!("{rep:?} in {:?}", t.elapsed());
    let tip = state.x[n];
    println!(
        "w/L = {} (0.301721), -u/L = {} (0.056433)",
        -tip.y / len,
        (len - tip.x) / len
    );
    println!("reaction {:?}", state.reaction_force[0]);
}
