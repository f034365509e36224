use std::f64::consts::PI;
use nalgebra::Vector3;
use pliant_reference::{EndCondition, Rod, Solver, Stiffness};
#[test]
fn probe() {
    let ei = 1.0;
    let nodes = vec![Vector3::zeros(), Vector3::new(0.5, 0.0, 1e-4), Vector3::new(1.0, 0.0, 0.0)];
    let stiffness = Stiffness::new(1e9 * ei, ei, 0.8 * ei).unwrap();
    let rod = Rod::new(nodes, stiffness).unwrap();
    let l = rod.length();
    let solver = Solver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let rest = solver.unloaded_end_pose();
    eprintln!("rest end {:?} frame {:?}", rest.position, rest.frame);
    let shortenings: Vec<f64> = [1e-7, 1e-6, 1e-5].to_vec();
    let targets: Vec<_> = shortenings.iter().map(|d| EndCondition::clamped(rest.translated(&Vector3::new(-d * l, 0.0, 0.0)))).collect();
    let t = std::time::Instant::now();
    let sols = solver.solve_path(&targets).unwrap();
    eprintln!("{:?}", t.elapsed());
    let pcr = 4.0 * PI * PI * ei / (l * l);
    for (d, s) in shortenings.iter().zip(&sols) {
        let mid = s.sample(&[0.5 * l]).unwrap()[0].position;
        eprintln!("d {d:e} P/Pcr {:.6} mid z {:.5e} iters {}", -s.end_reaction().force.x / pcr, mid.z, s.iterations());
    }
}
