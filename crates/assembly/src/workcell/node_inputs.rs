//! The inputs on nodes ([`Input::Fix`](super::Input::Fix), [`Input::Mount`](super::Input::Mount), [`Input::Drive`](super::Input::Drive),
//! [`Input::Load`](super::Input::Load), [`Input::Unload`](super::Input::Unload), [`Input::Release`](super::Input::Release), [`Input::Tie`](super::Input::Tie),
//! [`Input::RemoveLoad`](super::Input::RemoveLoad)): each checked and turned into load cases of the state, which
//! the workcell remembers as its inputs' own (a later fix or release on the node
//! replaces them).

use super::{checked_motion, finite, part_inputs, Applied, Workcell};
use crate::timeline::NodeRef;
use crate::workcell::Refusal;
use glam::DVec3;
use pliant_core::loads::{DeadLoad, Drive, Fix, LoadCase, LoadCaseId, LoadRamp, Mount, Tie};

impl Workcell {
    /// [`Input::Fix`](super::Input::Fix): holds the node where it is now.
    pub(super) fn fix(&mut self, node: NodeRef) -> Result<Applied, Refusal> {
        let i = self.global(node)?;
        self.take_node(i)?;
        let id = self.add_user_load(LoadCase::Fix(Fix {
            node: i,
            position: self.state.x[i],
            orientation: self.state.q[i],
        }));
        self.tally.track_node(i, node);
        Ok(Applied::Load(id))
    }

    /// [`Input::Mount`](super::Input::Mount): holds the node to the part called `part` where it is now.
    pub(super) fn mount(&mut self, node: NodeRef, part: &str) -> Result<Applied, Refusal> {
        let i = self.global(node)?;
        let k = part_inputs::part_named(&self.model, part, "mount")?;
        self.take_node(i)?;
        // the node's pose now, in the part's reference placement
        let pose = self
            .model
            .kinematics
            .placement_at(k, self.state.time, &self.state.part_moves)
            .pose;
        let id = self.add_user_load(LoadCase::Mount(Mount {
            node: i,
            part: k,
            position: pose.inverse_apply(self.state.x[i]),
            orientation: (pose.rotation.conjugate() * self.state.q[i]).normalize(),
        }));
        self.tally.track_node(i, node);
        Ok(Applied::Load(id))
    }

    /// [`Input::Drive`](super::Input::Drive): drives the node through `waypoints` turning by `rotation` over
    /// `duration` \[s\] from now.
    pub(super) fn drive(
        &mut self,
        node: NodeRef,
        waypoints: &[DVec3],
        rotation: DVec3,
        duration: f64,
    ) -> Result<Applied, Refusal> {
        let i = self.global(node)?;
        let duration = checked_motion(waypoints, rotation, duration)?;
        self.take_node(i)?;
        let start = (self.state.x[i], self.state.q[i]);
        let drive = Drive::new(i, start, waypoints, rotation, self.state.time, duration);
        let id = self.add_user_load(LoadCase::Drive(drive));
        self.tally.track_node(i, node);
        Ok(Applied::Load(id))
    }

    /// [`Input::Load`](super::Input::Load): a dead force and moment at the node, rising over `ramp` \[s\].
    pub(super) fn load(
        &mut self,
        node: NodeRef,
        force: DVec3,
        moment: DVec3,
        ramp: f64,
        name: Option<&str>,
    ) -> Result<Applied, Refusal> {
        let i = self.global(node)?;
        let (force, moment) = (finite(force, "force")?, finite(moment, "moment")?);
        if !(ramp.is_finite() && ramp >= 0.0) {
            return Err(Refusal::Invalid(format!(
                "a load's ramp must be finite and ≥ 0 s, got {ramp}"
            )));
        }
        if let Some(name) = name {
            if name.is_empty() {
                return Err(Refusal::Invalid("a load's name must not be empty".into()));
            }
            if self.named_loads.contains_key(name) {
                return Err(Refusal::Invalid(format!(
                    "a load named '{name}' is already acting; unload it first"
                )));
            }
        }
        let ramp = (ramp > 0.0).then_some(LoadRamp::rise(self.state.time, ramp));
        let id = self.add_user_load(LoadCase::DeadLoad(DeadLoad {
            node: i,
            force,
            moment,
            ramp,
        }));
        if let Some(name) = name {
            self.named_loads.insert(name.to_string(), id);
        }
        Ok(Applied::Load(id))
    }

    /// [`Input::Unload`](super::Input::Unload): removes the dead load called `name` from the node, or all of
    /// them.
    pub(super) fn unload(&mut self, node: NodeRef, name: Option<&str>) -> Result<Applied, Refusal> {
        let i = self.global(node)?;
        match name {
            None => self.remove_user_loads(i, |c| matches!(c, LoadCase::DeadLoad(_))),
            Some(name) => {
                let id = *self
                    .named_loads
                    .get(name)
                    .ok_or_else(|| Refusal::Invalid(format!("no load named '{name}' is acting")))?;
                let on_node = self
                    .state
                    .loads
                    .iter()
                    .any(|(k, c)| *k == id && c.node() == i);
                if !on_node {
                    return Err(Refusal::Invalid(format!(
                        "the load named '{name}' acts on another node"
                    )));
                }
                self.state.loads.remove(id);
                self.user_loads.remove(&id);
                self.named_loads.remove(name);
            }
        }
        Ok(Applied::Done)
    }

    /// [`Input::Release`](super::Input::Release): the node moves freely again.
    pub(super) fn release(&mut self, node: NodeRef) -> Result<Applied, Refusal> {
        let i = self.global(node)?;
        self.take_node(i)?;
        Ok(Applied::Done)
    }

    /// [`Input::Tie`](super::Input::Tie): holds two nodes at the distance they have now.
    pub(super) fn tie(&mut self, node: NodeRef, to: NodeRef) -> Result<Applied, Refusal> {
        let (a, b) = (self.global(node)?, self.global(to)?);
        let length = (self.state.x[b] - self.state.x[a]).length();
        if a == b || length.is_nan() || length <= 0.0 {
            return Err(Refusal::Invalid(format!(
                "a tie needs two nodes apart (hose {} node {}, hose {} node {}: {length:.3e} m)",
                node.hose, node.node, to.hose, to.node
            )));
        }
        for n in [a, b] {
            if let Some(h) = self.model.hoses.iter().position(|h| h.nodes().contains(&n)) {
                self.state.sleep.wake(&self.model, h);
            }
        }
        let tie = Tie {
            nodes: [a, b],
            length,
        };
        Ok(Applied::Load(self.add_user_load(LoadCase::Tie(tie))))
    }

    /// [`Input::RemoveLoad`](super::Input::RemoveLoad): removes one load case an input added.
    pub(super) fn remove_load(&mut self, id: LoadCaseId) -> Result<Applied, Refusal> {
        if !self.user_loads.remove(&id) || self.state.loads.remove(id).is_none() {
            return Err(Refusal::Missing(format!(
                "load case {} is not active (removed, replaced by a later fix or drive on its node, or reset)",
                id.0
            )));
        }
        self.forget_removed_names();
        Ok(Applied::Done)
    }
}
