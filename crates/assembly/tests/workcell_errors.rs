//! Building a workcell: the scene's initial load cases are applied as the inputs of the
//! same name (a fix holds its node, a dead load acts), and a workcell that cannot be
//! built says why with a typed error whose text names the node, the part or the worker.

use glam::DVec3;
use pliant_assembly::{
    Action, InitialLoad, NodeRef, Refusal, Workcell, WorkcellError, WorkcellOptions, WorkcellSetup,
};
use pliant_core::loads::LoadCase;
use pliant_core::SimSettings;
use pliant_testkit::hose3_along_x;
use std::sync::Arc;

fn setup(initial: Vec<InitialLoad>) -> WorkcellSetup {
    WorkcellSetup {
        initial,
        ..WorkcellSetup::bare(Arc::new(hose3_along_x(4, SimSettings::default())))
    }
}

/// The error of a workcell built with `initial`.
fn refused(initial: Vec<InitialLoad>) -> WorkcellError {
    match Workcell::new(setup(initial), WorkcellOptions::default()) {
        Ok(_) => panic!("built, though it should be refused"),
        Err(e) => e,
    }
}

fn node(node: usize) -> NodeRef {
    NodeRef { hose: 0, node }
}

#[test]
fn initial_load_cases_act_from_the_start_and_after_a_reset() {
    let force = DVec3::new(0.0, 0.0, -2.0);
    let load = Action::Load {
        node: node(4),
        force,
        moment: DVec3::ZERO,
        ramp: 0.0,
        name: Some("weight".into()),
    };
    let initial = vec![
        InitialLoad::fix(node(0)),
        InitialLoad::from_action(&load).unwrap(),
    ];
    // a timeline's other actions are no initial load cases
    assert_eq!(
        InitialLoad::from_action(&Action::Run { duration: 1.0 }),
        None
    );
    let mut cell = Workcell::new(setup(initial), WorkcellOptions::default()).unwrap();
    for round in ["built", "reset"] {
        let cases: Vec<&LoadCase> = cell.state().loads.iter().map(|(_, c)| c).collect();
        assert!(
            cases
                .iter()
                .any(|c| matches!(c, LoadCase::Fix(f) if f.node == 0)),
            "{round}: node 0 fixed"
        );
        assert!(
            cases
                .iter()
                .any(|c| matches!(c, LoadCase::DeadLoad(d) if d.node == 4 && d.force == force)),
            "{round}: the dead load on node 4"
        );
        cell.apply(pliant_assembly::Input::Reset).unwrap();
    }
    // without initial loads, nothing acts
    let bare = Workcell::new(
        setup(vec![InitialLoad::fix(node(0))]),
        WorkcellOptions {
            initial_loads: false,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(bare.state().loads.iter().count(), 0);
}

#[test]
fn a_workcell_that_cannot_be_built_says_why() {
    let far = InitialLoad::fix(NodeRef { hose: 3, node: 0 });
    let err = refused(vec![far]);
    assert!(
        matches!(err, WorkcellError::InitialLoad(Refusal::Invalid(_))),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        "initial load case: hose 3 does not exist (the scene has 1)"
    );

    let mount = InitialLoad::from_action(&Action::Mount {
        node: node(0),
        part: "door".into(),
    })
    .unwrap();
    let err = refused(vec![mount]);
    assert_eq!(
        err.to_string(),
        "initial load case: mount: no part named \"door\" (parts: none)"
    );
}
