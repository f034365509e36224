//! The tree solver against the chain solver, symmetry, global equilibrium and the
//! closed-form small-load T; malformed trees rejected with typed errors.

use nalgebra::Vector3;
use pliant_reference::{
    EndCondition, ReferenceError, Rod, ShootingSolver, Stiffness, Tree, TreeSolution, TreeSolver,
    Wrench,
};

const EA: f64 = 2.0e3;
const EI: f64 = 0.05;
const GJ: f64 = 0.04;

fn stiffness() -> Stiffness {
    Stiffness::new(EA, EI, GJ).unwrap()
}

fn rod(nodes: &[Vector3<f64>]) -> Rod {
    Rod::new(nodes.to_vec(), stiffness()).unwrap()
}

fn force(f: Vector3<f64>) -> Wrench {
    Wrench {
        force: f,
        moment: Vector3::zeros(),
    }
}

/// A T: a stem of `stem` along x from the origin, arms of `arm` along +y (branch 1) and
/// −y (branch 2) from its end.
fn t_tree(stem: f64, arm: f64) -> TreeSolver {
    let joint = Vector3::new(stem, 0.0, 0.0);
    let tree = Tree::new(vec![
        (rod(&[Vector3::zeros(), joint]), None),
        (rod(&[joint, joint + Vector3::new(0.0, arm, 0.0)]), Some(0)),
        (rod(&[joint, joint - Vector3::new(0.0, arm, 0.0)]), Some(0)),
    ])
    .unwrap();
    let base = tree.rod(0).unwrap().rest_base_pose();
    TreeSolver::new(tree, base).unwrap()
}

fn solve(solver: &TreeSolver, loads: Vec<Wrench>) -> TreeSolution {
    solver.solve_path(&[loads]).unwrap().pop().unwrap()
}

fn tip(solution: &TreeSolution, branch: usize) -> Vector3<f64> {
    solution.end_state(branch).unwrap().position
}

/// An unloaded side branch carries nothing: the T with one arm unloaded is the chain
/// of the stem and the loaded arm (one rod with a 90° rest kink), here far from the
/// linear range (tip load Pb²/EI = 1 across the frame's plane, twisting the stem).
#[test]
fn t_with_an_unloaded_arm_is_the_kinked_chain() {
    let (stem, arm) = (0.7, 0.5);
    let p = EI / (arm * arm);
    let load = Vector3::new(0.0, 0.0, p);
    let solver = t_tree(stem, arm);
    let zero = force(Vector3::zeros());
    let tree = solve(&solver, vec![zero, force(load), zero]);

    let joint = Vector3::new(stem, 0.0, 0.0);
    let chain_rod = rod(&[Vector3::zeros(), joint, joint + Vector3::new(0.0, arm, 0.0)]);
    let chain = ShootingSolver::new(chain_rod.clone(), chain_rod.rest_base_pose())
        .unwrap()
        .solve_path(&[EndCondition::loaded(load, Vector3::zeros())])
        .unwrap()
        .pop()
        .unwrap();

    let tip_error = (tip(&tree, 1) - chain.end_state().position).norm();
    assert!(
        tip_error < 1e-9,
        "tip differs from the chain's by {tip_error:e} m"
    );
    assert!((tip(&tree, 1) - chain_rod.rest_end_pose().position).norm() > 0.3 * arm);
    let moment_error = (tree.base_reaction().moment - chain.base_reaction().moment).norm();
    assert!(
        moment_error < 1e-9 * p,
        "base moment differs by {moment_error:e} N m"
    );
    // the unloaded arm: no force or moment at its root, carried rigidly
    let root = tree.base_state(2).unwrap();
    assert!(root.force.norm() < 1e-12 * p && root.moment.norm() < 1e-12 * p);
    let carried = root.position + root.frame * Vector3::new(arm, 0.0, 0.0);
    assert!((tip(&tree, 2) - carried).norm() < 1e-12);
}

/// Equal loads on the arms of a symmetric T: the tips are mirror images in the stem's
/// plane, the stem is not twisted, and the base reaction balances the loads about the
/// deformed tips (global equilibrium).
#[test]
fn symmetric_t_is_symmetric_and_in_equilibrium() {
    let (stem, arm) = (0.6, 0.4);
    let p = 2.0 * EI / (stem * stem);
    let load = Vector3::new(0.0, 0.0, -p);
    let solver = t_tree(stem, arm);
    let solution = solve(
        &solver,
        vec![force(Vector3::zeros()), force(load), force(load)],
    );
    let (left, right) = (tip(&solution, 1), tip(&solution, 2));
    let mirrored = Vector3::new(right.x, -right.y, right.z);
    assert!((left - mirrored).norm() < 1e-10, "{left:?} vs {right:?}");
    assert!(left.z < -0.3 * stem, "large deflection: tip z = {}", left.z);
    let reaction = solution.base_reaction();
    assert!(
        reaction.moment.x.abs() < 1e-10 * p,
        "stem twisted: {}",
        reaction.moment.x
    );
    assert!((reaction.force + 2.0 * load).norm() < 1e-12 * p);
    let balance = reaction.moment + left.cross(&load) + right.cross(&load);
    assert!(balance.norm() < 1e-9 * p, "moment balance {balance:?}");
}

/// Small loads: an asymmetric T loaded across its plane, P₁ on one arm, P₂ on the
/// other — tip deflections δ₁,₂ = (P₁ + P₂)L_s³/3EI + P₁,₂ L_a³/3EI ± (P₁ − P₂) L_a² L_s/GJ
/// (stem bent by both loads, twisted by their difference) — the closed form `frames`
/// checks Pliant against, to 1e-6 (nonlinear terms are of order λ² = 1e-8 relative).
#[test]
fn small_loads_match_the_closed_form_t() {
    let (stem, arm) = (0.6, 0.4);
    let (p1, p2) = (1e-4 * EI, 0.5e-4 * EI);
    let solver = t_tree(stem, arm);
    let solution = solve(
        &solver,
        vec![
            force(Vector3::zeros()),
            force(Vector3::new(0.0, 0.0, p1)),
            force(Vector3::new(0.0, 0.0, p2)),
        ],
    );
    let bending = (p1 + p2) * stem.powi(3) / (3.0 * EI);
    let twist = (p1 - p2) * arm * arm * stem / GJ;
    for (branch, p, sign) in [(1, p1, 1.0), (2, p2, -1.0)] {
        let exact = bending + p * arm.powi(3) / (3.0 * EI) + sign * twist;
        let computed = tip(&solution, branch).z;
        let error = (computed - exact).abs() / exact;
        assert!(
            error < 1e-6,
            "arm {branch}: {computed:e} vs {exact:e} ({error:e})"
        );
    }
}

/// A path of several targets reaches the same solution as one target.
#[test]
fn path_of_targets_ends_where_one_target_does() {
    let solver = t_tree(0.6, 0.4);
    let target = |s: f64| {
        vec![
            force(Vector3::new(0.0, 0.05 * s, 0.0)),
            force(Vector3::new(0.0, 0.0, 0.3 * s)),
            force(Vector3::new(0.1 * s, 0.0, -0.1 * s)),
        ]
    };
    let path = solver.solve_path(&[target(0.5), target(1.0)]).unwrap();
    let once = solve(&solver, target(1.0));
    for branch in 0..3 {
        let d = (tip(&path[1], branch) - tip(&once, branch)).norm();
        assert!(d < 1e-10, "branch {branch}: {d:e}");
    }
}

fn expect<T: std::fmt::Debug>(
    result: Result<T, ReferenceError>,
    matches: fn(&ReferenceError) -> bool,
) {
    let error = result.expect_err("malformed input must be rejected");
    assert!(matches(&error), "unexpected error: {error}");
    assert!(!error.to_string().is_empty());
}

#[test]
fn malformed_trees_are_rejected() {
    let a = rod(&[Vector3::zeros(), Vector3::x()]);
    let b = rod(&[Vector3::x(), Vector3::new(1.0, 1.0, 0.0)]);
    let c = rod(&[Vector3::new(1.0, 1.0, 0.0), Vector3::new(2.0, 1.0, 0.0)]);
    expect(Tree::new(vec![]), |e| {
        matches!(e, ReferenceError::InvalidTree(_))
    });
    expect(
        Tree::new(vec![(a.clone(), None), (b.clone(), Some(5))]),
        |e| {
            matches!(
                e,
                ReferenceError::UnknownParent {
                    branch: 1,
                    parent: 5,
                    count: 2
                }
            )
        },
    );
    // b and c are each other's parents: a cycle hanging off nothing
    expect(
        Tree::new(vec![
            (a.clone(), None),
            (b.clone(), Some(2)),
            (c.clone(), Some(1)),
        ]),
        |e| matches!(e, ReferenceError::TreeCycle { .. }),
    );
    expect(Tree::new(vec![(a.clone(), Some(0))]), |e| {
        matches!(e, ReferenceError::TreeCycle { branch: 0 })
    });
    expect(Tree::new(vec![(a.clone(), None), (c.clone(), None)]), |e| {
        matches!(e, ReferenceError::InvalidTree(_))
    });
    // c starts at (1, 1, 0), a ends at (1, 0, 0)
    expect(
        Tree::new(vec![(a.clone(), None), (c, Some(0))]),
        |e| matches!(e, ReferenceError::DanglingBranch { branch: 1, parent: 0, gap } if (gap - 1.0).abs() < 1e-12),
    );
    let tree = Tree::new(vec![(a.clone(), None), (b, Some(0))]).unwrap();
    let solver = TreeSolver::new(tree, a.rest_base_pose()).unwrap();
    expect(solver.solve_path(&[vec![force(Vector3::zeros())]]), |e| {
        matches!(e, ReferenceError::InvalidBoundaryCondition(_))
    });
    expect(
        solver.solve_path(&[vec![
            force(Vector3::zeros()),
            force(Vector3::new(f64::NAN, 0.0, 0.0)),
        ]]),
        |e| matches!(e, ReferenceError::InvalidBoundaryCondition(_)),
    );
}

/// A tree three levels deep (a branch on a branch, with a rest kink) under large end
/// loads and moments on every branch, junctions included: the clamp balances all the
/// loads about the deformed end points (global equilibrium), and the unknown moment at
/// each branch point closes its own balance.
#[test]
fn deep_tree_is_in_global_equilibrium() {
    let joint = Vector3::new(0.5, 0.0, 0.0);
    let fork = joint + Vector3::new(0.2, 0.4, 0.0);
    let tree = Tree::new(vec![
        (rod(&[Vector3::zeros(), joint]), None),
        (
            rod(&[joint, joint + Vector3::new(0.0, 0.2, 0.0), fork]),
            Some(0),
        ),
        (rod(&[joint, joint + Vector3::new(0.4, -0.1, 0.1)]), Some(0)),
        (rod(&[fork, fork + Vector3::new(0.0, 0.0, 0.3)]), Some(1)),
    ])
    .unwrap();
    let base = tree.rod(0).unwrap().rest_base_pose();
    let solver = TreeSolver::new(tree, base).unwrap();
    let loads: Vec<Wrench> = (0..4)
        .map(|b| Wrench {
            force: Vector3::new(0.02, -0.05, 0.08) * (b as f64 + 1.0),
            moment: Vector3::new(-0.01, 0.005, 0.01) * b as f64,
        })
        .collect();
    let solution = solve(&solver, loads.clone());
    let reaction = solution.base_reaction();
    let mut force = reaction.force;
    let mut moment = reaction.moment;
    for (b, load) in loads.iter().enumerate() {
        force += load.force;
        moment += tip(&solution, b).cross(&load.force) + load.moment;
    }
    let scale = loads.iter().map(|w| w.force.norm()).sum::<f64>();
    assert!(force.norm() < 1e-12 * scale, "force balance {force:?}");
    assert!(moment.norm() < 1e-9 * scale, "moment balance {moment:?}");
    // the loads deform it far from the rest shape
    let rest_tip = solver.tree().rod(3).unwrap().rest_end_pose().position;
    assert!((tip(&solution, 3) - rest_tip).norm() > 0.1);
}
