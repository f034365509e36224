//! L1 Fix: a node held in all six degrees of freedom (dissertation table 5.1).

use glam::{DQuat, DVec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Fix {
    pub node: usize,
    /// Held position \[m\].
    pub position: DVec3,
    /// Held orientation.
    pub orientation: DQuat,
}
