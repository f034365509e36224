//! Circular tube cross-section (SPEC M2).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Circular tube cross-section, diameters in metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// Inner diameter d_i [m] (0 for a solid rod).
    pub d_inner: f64,
    /// Outer diameter d_a [m].
    pub d_outer: f64,
}

impl Section {
    pub fn new(d_inner: f64, d_outer: f64) -> Self {
        Self { d_inner, d_outer }
    }

    /// Area A = π/4 (d_a² − d_i²) [m²].
    pub fn area(&self) -> f64 {
        PI / 4.0 * (self.d_outer.powi(2) - self.d_inner.powi(2))
    }

    /// Second moment of area I = π/64 (d_a⁴ − d_i⁴) [m⁴].
    pub fn second_moment(&self) -> f64 {
        PI / 64.0 * (self.d_outer.powi(4) - self.d_inner.powi(4))
    }

    /// Polar moment J = 2 I [m⁴].
    pub fn polar_moment(&self) -> f64 {
        2.0 * self.second_moment()
    }

    /// Outer radius [m].
    pub fn outer_radius(&self) -> f64 {
        0.5 * self.d_outer
    }

    /// Mean of two sections (used for an element between two nodes of different section).
    pub fn mean(a: &Section, b: &Section) -> Section {
        Section {
            d_inner: 0.5 * (a.d_inner + b.d_inner),
            d_outer: 0.5 * (a.d_outer + b.d_outer),
        }
    }
}
