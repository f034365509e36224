//! A live session under the static solver that runs paused and advances only by `step`
//! commands, waited for by condition (the step count reached), with a hang guard only —
//! shared by the tests of what the static solver reports live.

use pliant_core::SolverKind;
use pliant_scene::LoadedScene;
use pliant_server::session::{Command, Session, SessionOptions};
use pliant_server::snapshot::Snapshot;
use std::sync::Arc;
use std::time::Duration;

/// Not a performance expectation: only keeps a broken test from hanging forever.
const HANG_GUARD: Duration = Duration::from_secs(600);

/// The session, paused, under the static solver.
pub fn start(scene: &LoadedScene) -> Session {
    Session::start(
        scene,
        SessionOptions {
            paused: true,
            solver: Some(SolverKind::Static),
            ..Default::default()
        },
    )
    .unwrap()
}

/// Takes `steps` input steps and returns the first snapshot that has them all.
pub async fn step(session: &Session, steps: u32) -> Arc<Snapshot> {
    session.send(Command::Step(steps)).unwrap();
    let mut rx = session.subscribe();
    tokio::time::timeout(HANG_GUARD, async {
        loop {
            let s = rx.borrow_and_update().clone();
            if s.step >= steps as u64 {
                return s;
            }
            rx.changed().await.expect("the simulation thread runs");
        }
    })
    .await
    .expect("the session reaches the step (hang guard)")
}
