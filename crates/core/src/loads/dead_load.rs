//! Dead load: a constant force and moment at a node, fixed in global axes (it does not
//! turn with the hose), as used by the tip-load and roll-up validation cases.

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct DeadLoad {
    pub node: usize,
    /// Force [N], global axes.
    pub force: DVec3,
    /// Moment [N·m], global axes.
    pub moment: DVec3,
}
