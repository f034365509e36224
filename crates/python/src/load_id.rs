//! `pliant.LoadId`: the handle of a load case added with `Simulation.fix`, `drive` or
//! `add_dead_load`, for removing it again.

use pyo3::prelude::*;

/// Handle of a load case the user added; pass it to :meth:`Simulation.remove_load`.
///
/// Attributes: ``id`` (unique within its simulation), ``kind`` (``"fix"``, ``"drive"``
/// or ``"dead_load"``), ``hose`` (name) and ``node`` (index on that hose).
#[pyclass(module = "pliant", name = "LoadId", frozen, eq, hash)]
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct LoadId {
    #[pyo3(get)]
    pub id: u64,
    #[pyo3(get)]
    pub kind: String,
    #[pyo3(get)]
    pub hose: String,
    #[pyo3(get)]
    pub node: usize,
}

#[pymethods]
impl LoadId {
    fn __repr__(&self) -> String {
        format!(
            "LoadId({}, kind='{}', hose='{}', node={})",
            self.id, self.kind, self.hose, self.node
        )
    }
}
