//! SPEC W1: the same inputs through the timeline runner, the live server's simulation
//! thread and a bare workcell give the same numbers bit for bit, for each solver; and the
//! live session's input log replays into the same state. The server session runs paused
//! and advances only by `step` commands, so nothing here depends on the machine's speed;
//! waits are for conditions (the snapshot of the last step), with a hang guard only.

use glam::DVec3;
use pliant_assembly::workcell::replay::replay;
use pliant_assembly::{
    run_timeline, Action, Input, NoObserver, Runner, Timeline, Workcell, WorkcellOptions,
};
use pliant_core::SolverKind;
use pliant_server::session::{Command, Session, SessionOptions};
use pliant_server::Snapshot;
use std::sync::Arc;
use std::time::Duration;

/// Not a performance expectation: only keeps a broken test from hanging forever.
const HANG_GUARD: Duration = Duration::from_secs(300);

/// (steps before the input, the input): grab the lower hose's free end, aim it up and
/// sideways, let go, let it swing.
fn script() -> Vec<(u64, Input)> {
    let end = DVec3::new(-0.17, -0.6, 0.25);
    vec![
        (
            0,
            Input::Grab {
                grip: Default::default(),
                hand: 7,
                at: end,
            },
        ),
        (
            40,
            Input::AimHand {
                hand: 7,
                position: end + DVec3::new(0.0, 0.02, 0.06),
                orientation: None,
            },
        ),
        (60, Input::ReleaseHand { hand: 7 }),
        (30, Input::Reset),
        (
            0,
            Input::Grab {
                grip: Default::default(),
                hand: 7,
                at: end,
            },
        ),
    ]
}
const TAIL: u64 = 20;

async fn snapshot_at_step(session: &Session, step: u64) -> Arc<Snapshot> {
    let mut rx = session.subscribe();
    tokio::time::timeout(HANG_GUARD, async {
        loop {
            let s = rx.borrow_and_update().clone();
            // after the reset the hand grabs again: the last snapshot is the only one
            // at this step with a hand
            if s.step == step && !s.hands.is_empty() {
                return s;
            }
            rx.changed().await.expect("the simulation thread runs");
        }
    })
    .await
    .expect("the session reaches the step (hang guard)")
}

fn bits(v: DVec3) -> [u64; 3] {
    v.to_array().map(f64::to_bits)
}

fn assert_positions(snapshot: &Snapshot, cell: &Workcell, what: &str) {
    let model = cell.model();
    for (k, h) in model.hoses.iter().enumerate() {
        for (j, g) in h.nodes().enumerate() {
            let live = DVec3::from_array(snapshot.hoses[k].positions[j]);
            assert_eq!(
                bits(live),
                bits(cell.state().x[g]),
                "{what}: hose {k} node {j}"
            );
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn runner_server_and_workcell_agree_bit_for_bit_for_each_solver() {
    let scene = pliant_scene::demo_scene().unwrap();
    for solver in SolverKind::ALL {
        let options = WorkcellOptions {
            solver: Some(solver),
            sleeping: true, // as pliant serve runs
            ..Default::default()
        };
        // a bare workcell
        let mut cell = scene.workcell(options).unwrap();
        for (steps, input) in script() {
            cell.steps(steps, &mut NoObserver).unwrap();
            cell.apply(input).unwrap();
        }
        cell.steps(TAIL, &mut NoObserver).unwrap();

        // the live server, paused and stepped
        let session = Session::start(
            &scene,
            SessionOptions {
                paused: true,
                solver: Some(solver),
                ..Default::default()
            },
        )
        .unwrap();
        for (steps, input) in script() {
            if steps > 0 {
                session.send(Command::Step(steps as u32)).unwrap();
            }
            session
                .send(match input {
                    Input::Grab { hand, at, .. } => Command::Grab {
                        hand,
                        position: at,
                        grip: Default::default(),
                    },
                    Input::AimHand {
                        hand,
                        position,
                        orientation,
                    } => Command::Move {
                        hand,
                        position,
                        orientation,
                    },
                    Input::ReleaseHand { hand } => Command::Release { hand },
                    Input::Reset => Command::Reset,
                    other => panic!("no command for {other:?}"),
                })
                .unwrap();
        }
        session.send(Command::Step(TAIL as u32)).unwrap();
        let live = snapshot_at_step(&session, cell.state().step).await;
        assert_positions(&live, &cell, &format!("{solver}: server"));
        let log = session.input_log().unwrap();
        assert_eq!(
            log.inputs,
            cell.log().to_vec(),
            "{solver}: the same inputs at the same ticks"
        );

        // the live session's log replayed
        let mut again = scene.workcell(options).unwrap();
        replay(&mut again, &log.inputs, log.end_tick, &mut NoObserver).unwrap();
        assert_positions(&live, &again, &format!("{solver}: replay of the live log"));

        // the timeline runner (without the reset: a timeline has none)
        let mut actions = scene.initial_actions();
        let mut direct = scene.workcell(options).unwrap();
        let dt = direct.time_step();
        for (steps, input) in script().into_iter().take(3) {
            direct.steps(steps, &mut NoObserver).unwrap();
            direct.apply(input.clone()).unwrap();
            if steps > 0 {
                actions.push(Action::Run {
                    duration: steps as f64 * dt,
                });
            }
            actions.push(match input {
                Input::Grab { hand, at, grip } => Action::Grab {
                    grip,
                    hand: hand as usize,
                    at,
                },
                Input::AimHand {
                    hand,
                    position,
                    orientation,
                } => Action::AimHand {
                    hand: hand as usize,
                    position,
                    orientation,
                },
                Input::ReleaseHand { hand } => Action::ReleaseHand {
                    hand: hand as usize,
                },
                other => panic!("no action for {other:?}"),
            });
        }
        direct.steps(TAIL, &mut NoObserver).unwrap();
        actions.push(Action::Run {
            duration: TAIL as f64 * dt,
        });
        let mut timeline_cell = Runner::from_setup(scene.workcell_setup().unwrap(), options)
            .workcell()
            .unwrap();
        run_timeline(&mut timeline_cell, &Timeline { actions }, &mut NoObserver).unwrap();
        assert_eq!(timeline_cell.tick(), direct.tick());
        for i in 0..direct.state().x.len() {
            assert_eq!(
                bits(timeline_cell.state().x[i]),
                bits(direct.state().x[i]),
                "{solver}: runner node {i}"
            );
        }
        assert_eq!(
            timeline_cell.summary(),
            direct.summary(),
            "{solver}: runner peaks"
        );
    }
}
