//! Replaying an input log (SPEC W2): the inputs go into a fresh workcell of the same
//! scene at the ticks they were stamped with, and the workcell steps in between up to
//! the log's last tick. Since a step depends on nothing but the workcell (no clock, no
//! thread, no randomness), the replay reproduces the session bit for bit; a refused
//! input means the log does not belong to this scene or options, and is said so.

use super::input::StampedInput;
use super::observer::{NoObserver, Observer};
use super::Workcell;
use pliant_core::Divergence;

/// Why a replay stopped.
#[derive(Debug, thiserror::Error)]
pub enum ReplayError {
    #[error("input {index} ({name} at tick {tick}) was refused on replay: {reason} — the log does not match this scene or these options")]
    Refused {
        index: usize,
        tick: u64,
        name: &'static str,
        reason: String,
    },
    #[error("input {index} is stamped with tick {tick}, but the replay is already at tick {now}")]
    Late { index: usize, tick: u64, now: u64 },
    #[error("the replay diverged and the log does not reset it: {0}")]
    Diverged(Divergence),
}

/// Feeds `inputs` into `cell` at their ticks and steps until tick `end_tick` (or the
/// last input's tick, if later). A divergence the log answers with a reset (as a live
/// session does) is replayed too; one it does not answer ends the replay with an error.
pub fn replay(
    cell: &mut Workcell,
    inputs: &[StampedInput],
    end_tick: u64,
    obs: &mut dyn Observer,
) -> Result<(), ReplayError> {
    let end = end_tick.max(inputs.last().map_or(0, |i| i.tick));
    let mut next = 0;
    loop {
        while let Some(s) = inputs.get(next) {
            if s.tick > cell.tick() {
                break;
            }
            if s.tick < cell.tick() {
                return Err(ReplayError::Late {
                    index: next,
                    tick: s.tick,
                    now: cell.tick(),
                });
            }
            cell.apply(s.input.clone())
                .map_err(|r| ReplayError::Refused {
                    index: next,
                    tick: s.tick,
                    name: s.input.name(),
                    reason: r.to_string(),
                })?;
            next += 1;
        }
        if cell.tick() >= end {
            return cell.check().map_err(ReplayError::Diverged);
        }
        if let Err(d) = cell.step(obs) {
            let answered = inputs.get(next).is_some_and(|s| {
                s.tick == cell.tick()
                    && matches!(s.input, super::Input::Reset | super::Input::Rollback)
            });
            if !answered {
                return Err(ReplayError::Diverged(d));
            }
        }
    }
}

/// Replays `live`'s own log — every input it took, up to its present tick — into
/// `fresh`, a new workcell of the same scene and options: the workcell its session folder
/// would replay to.
pub fn replay_log_of(live: &Workcell, fresh: &mut Workcell) -> Result<(), ReplayError> {
    replay(fresh, &live.log().to_vec(), live.tick(), &mut NoObserver)
}
