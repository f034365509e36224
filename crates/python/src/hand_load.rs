//! `pliant.HandLoad`: the force and torque a hand applied in the last step, and how they
//! compare with the ergonomic limits (SPEC I2–I4).

use crate::arrays::vector;
use glam::DVec3;
use numpy::PyArray1;
use pliant_assembly::ergonomics::HandAssessment;
use pliant_assembly::HandLoad as RustHandLoad;
use pyo3::prelude::*;

/// The load one hand applied to the hose in the last step (global axes, SI units), judged
/// against the simulation's ergonomic profile.
///
/// Attributes: ``hand``, ``hose`` (name), ``position`` \[m\], ``force`` \[N\], ``torque``
/// \[N·m\] about the hand position, ``direction`` (unit push direction: along the held
/// beam towards the nearer hose end) as numpy arrays; the force split into
/// ``axial_force`` (signed, > 0 push) and ``lateral_force`` \[N\], the torque into
/// ``twist`` (about the hose axis) and ``bending`` (across it) \[N·m\]; ``kind`` of the
/// worst load that decides feasibility (``"push"``, ``"pull"``; ``"twist"`` or
/// ``"bending"`` only with ``moments_decide=true``; None if not assessed), its ``ratio``
/// to the ``limit`` value, and the ``colour`` value min(ratio, 1).
#[pyclass(module = "pliant", name = "HandLoad", frozen)]
pub struct HandLoad {
    #[pyo3(get)]
    hand: u32,
    #[pyo3(get)]
    hose: String,
    position: DVec3,
    force: DVec3,
    torque: DVec3,
    direction: DVec3,
    #[pyo3(get)]
    kind: Option<String>,
    #[pyo3(get)]
    ratio: f64,
    #[pyo3(get)]
    limit: f64,
    #[pyo3(get)]
    colour: f64,
    #[pyo3(get)]
    axial_force: f64,
    #[pyo3(get)]
    lateral_force: f64,
    #[pyo3(get)]
    twist: f64,
    #[pyo3(get)]
    bending: f64,
}

impl HandLoad {
    pub fn new(
        hand: u32,
        hose: String,
        load: &RustHandLoad,
        assessment: Option<&HandAssessment>,
    ) -> Self {
        let worst = assessment.map(|a| *a.worst());
        HandLoad {
            hand,
            hose,
            position: load.position,
            force: load.force,
            torque: load.torque,
            direction: load.direction,
            kind: worst.map(|w| w.kind.name().to_string()),
            ratio: worst.map_or(0.0, |w| w.ratio),
            limit: worst.map_or(0.0, |w| w.limit),
            colour: assessment.map_or(0.0, |a| a.colour_value()),
            axial_force: assessment.map_or(0.0, |a| a.axial_force),
            lateral_force: assessment.map_or(0.0, |a| a.lateral_force),
            twist: assessment.map_or(0.0, |a| a.twist.magnitude),
            bending: assessment.map_or(0.0, |a| a.bending.magnitude),
        }
    }
}

#[pymethods]
impl HandLoad {
    /// Hand position \[m\], shape (3,).
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.position)
    }
    /// Force the hand applies to the hose \[N\], shape (3,).
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.force)
    }
    /// Torque the hand applies about its position \[N·m\], shape (3,).
    #[getter]
    fn torque<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.torque)
    }
    /// Unit push direction, shape (3,).
    #[getter]
    fn direction<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vector(py, self.direction)
    }

    fn __repr__(&self) -> String {
        format!(
            "<pliant.HandLoad hand {} on '{}': |F| = {:.3} N, |T| = {:.4} N·m, {} at {:.0} % of its limit>",
            self.hand,
            self.hose,
            self.force.length(),
            self.torque.length(),
            self.kind.as_deref().unwrap_or("not assessed"),
            100.0 * self.ratio
        )
    }
}
