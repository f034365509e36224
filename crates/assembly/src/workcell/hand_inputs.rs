//! The inputs on hands ([`Input::Grab`](super::Input::Grab), [`Input::MoveHand`](super::Input::MoveHand), [`Input::AimHand`](super::Input::AimHand),
//! [`Input::ReleaseHand`](super::Input::ReleaseHand)): a hand takes a beam, follows a scripted path or an aimed
//! pose, and lets go.

use super::{checked_motion, finite, Aim, Applied, HandNumber, HeldHand, Workcell};
use crate::hand::{nearest_beam, Hand};
use crate::workcell::hands::holder;
use crate::workcell::Refusal;
use crate::Grip;
use glam::{DQuat, DVec3};
use pliant_core::loads::LoadCase;

impl Workcell {
    /// [`Input::Grab`](super::Input::Grab): the hand takes the beam nearest to `at`, letting go of what it
    /// held.
    pub(super) fn grab(
        &mut self,
        hand: HandNumber,
        at: DVec3,
        grip: Grip,
    ) -> Result<Applied, Refusal> {
        let at = finite(at, "the grab point")?;
        let element = nearest_beam(&self.model, &self.state, at)
            .ok_or_else(|| Refusal::Invalid("there is no beam to grab".into()))?;
        let el = &self.model.elements[element];
        let nodes = [el.node_a, el.node_b];
        if let Some(other) = nodes
            .iter()
            .find_map(|&n| holder(&self.hands, n).filter(|k| *k != hand))
        {
            return Err(Refusal::Invalid(format!(
                "hand {other} already holds that beam; release it first"
            )));
        }
        // a grab or a release changes what holds the hoses: let them all move
        self.state.sleep.wake_all(&self.model);
        if let Some(old) = self.hands.remove(&hand) {
            self.let_go(old.hand);
        }
        for n in nodes {
            self.remove_user_loads(n, |c| !matches!(c, LoadCase::DeadLoad(_)));
        }
        let grabbed = Hand::grab_with(&self.model, &mut self.state, at, grip)
            .ok_or_else(|| Refusal::Invalid("there is no beam to grab".into()))?;
        let element = grabbed.element;
        self.hands.insert(
            hand,
            HeldHand {
                hand: grabbed,
                aim: None,
            },
        );
        self.tally.track_hand(hand);
        Ok(Applied::Grabbed { element })
    }

    /// [`Input::MoveHand`](super::Input::MoveHand): the hand moves through `waypoints` turning by `rotation` over
    /// `duration` \[s\] from now.
    pub(super) fn move_hand(
        &mut self,
        hand: HandNumber,
        waypoints: &[DVec3],
        rotation: DVec3,
        duration: f64,
    ) -> Result<Applied, Refusal> {
        let duration = checked_motion(waypoints, rotation, duration)?;
        self.hand(hand)?;
        let t = self.state.time;
        if let Some(h) = self.hands.get_mut(&hand) {
            h.aim = None;
            h.hand.move_along(waypoints, rotation, t, duration);
        }
        Ok(Applied::Done)
    }

    /// [`Input::AimHand`](super::Input::AimHand): the hand heads for `position` (and `orientation`, if given) at
    /// bounded speed.
    pub(super) fn aim_hand(
        &mut self,
        hand: HandNumber,
        position: DVec3,
        orientation: Option<DQuat>,
    ) -> Result<Applied, Refusal> {
        let position = finite(position, "the hand position")?;
        let orientation = match orientation {
            Some(q) if q.is_finite() && q.length() > 1e-9 => Some(q.normalize()),
            Some(q) => {
                return Err(Refusal::Invalid(format!(
                    "the hand orientation must be a finite non-zero quaternion, got {q}"
                )))
            }
            None => None,
        };
        self.hand(hand)?;
        let t = self.state.time;
        if let Some(h) = self.hands.get_mut(&hand) {
            let mut aim = h.aim.unwrap_or_else(|| {
                let pose = h.pose_at(t);
                Aim {
                    pose,
                    target: pose,
                    speed: 0.0,
                    at_strength: false,
                    feel: Default::default(),
                }
            });
            aim.target = (position, orientation.unwrap_or(aim.target.1));
            h.aim = Some(aim);
        }
        Ok(Applied::Done)
    }

    /// [`Input::ReleaseHand`](super::Input::ReleaseHand): the hand lets go.
    pub(super) fn release_hand(&mut self, hand: HandNumber) -> Result<Applied, Refusal> {
        let h = self
            .hands
            .remove(&hand)
            .ok_or_else(|| Refusal::Invalid(format!("hand {hand} holds nothing")))?;
        self.state.sleep.wake_all(&self.model);
        self.let_go(h.hand);
        Ok(Applied::Done)
    }
}
