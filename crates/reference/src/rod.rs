//! Rod data: stiffnesses, the polyline rest shape and its rest frames.
//!
//! The rest shape is a polyline `X_0 … X_K` (K ≥ 1 segments of arbitrary, non-zero
//! lengths). It is stress-free by definition: the intrinsic (rest) curvature is zero
//! on every straight segment and concentrated at the interior nodes, where the rest
//! frame turns by the *minimal* rotation (parallel transport) taking the previous
//! segment's direction to the next one's. The rest frames `R_rest,k` of the segments
//! are therefore
//!
//! ```text
//! R_rest,0 = base rest frame (d1 along X_1 − X_0),
//! R_rest,k = P(t_{k−1} → t_k) · R_rest,k−1,
//! ```
//!
//! with `P(a → b)` the rotation about `a × b` by the angle between the unit tangents.
//! In the material description the kink at node k is the constant rotation
//! `K_k = R_rest,k−1ᵀ · R_rest,k`, applied on the right of the current frame
//! (see [`crate::ode`]).

use nalgebra::{Rotation3, Vector3};

use crate::boundary::Pose;
use crate::error::{ReferenceError, Result};

/// Section stiffnesses of a bimodular, extensible, unshearable Kirchhoff rod (SI).
///
/// Constitutive law (Antman, *Nonlinear Problems of Elasticity*, 2nd ed., ch. 8,
/// linear special case): axial force `N = n·d1`, stretch `ν = 1 + N/EA` with
/// `EA = EA_t` for `N ≥ 0` and `EA = EA_c` for `N < 0`; body-frame moment
/// `m_b = (GJ κ₁, EI₂ κ₂, EI₃ κ₃)` (torsion about d1, bending about d2 and d3 — equal
/// unless set apart by [`Stiffness::with_bending`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stiffness {
    axial_tension: f64,
    axial_compression: f64,
    bending: f64,
    /// EI about d3 when it differs from `bending` (about d2).
    bending_d3: f64,
    torsion: f64,
}

impl Stiffness {
    /// Same axial stiffness in tension and compression: `EA` \[N\], `EI` \[N m²\],
    /// `GJ` \[N m²\]. All must be finite and positive.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidStiffness`] unless all values are finite and positive.
    pub fn new(axial: f64, bending: f64, torsion: f64) -> Result<Self> {
        Self::bimodular(axial, axial, bending, torsion)
    }

    /// Different axial stiffnesses in tension (`EA_t`) and compression (`EA_c`).
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidStiffness`] unless all values are finite and positive.
    pub fn bimodular(
        axial_tension: f64,
        axial_compression: f64,
        bending: f64,
        torsion: f64,
    ) -> Result<Self> {
        for (name, value) in [
            ("axial tension stiffness EA_t", axial_tension),
            ("axial compression stiffness EA_c", axial_compression),
            ("bending stiffness EI", bending),
            ("torsional stiffness GJ", torsion),
        ] {
            if !value.is_finite() || value <= 0.0 {
                return Err(ReferenceError::InvalidStiffness(format!(
                    "{name} must be finite and positive, got {value}"
                )));
            }
        }
        Ok(Self {
            axial_tension,
            axial_compression,
            bending,
            bending_d3: bending,
            torsion,
        })
    }

    /// Stiffnesses of a homogeneous circular tube: Young's modulus `E` \[Pa\],
    /// Poisson ratio `ν` (−1 < ν < 0.5), outer and inner diameters \[m\]
    /// (`0 ≤ d_i < d_a`). `A = π(d_a² − d_i²)/4`, `I = π(d_a⁴ − d_i⁴)/64`, `J = 2I`,
    /// `G = E / (2(1 + ν))`.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidStiffness`] for non-finite values, a Poisson ratio
    /// outside (−1, 0.5) or diameters not satisfying `0 ≤ d_i < d_a`.
    pub fn circular_tube(
        youngs_modulus: f64,
        poisson_ratio: f64,
        outer_diameter: f64,
        inner_diameter: f64,
    ) -> Result<Self> {
        let all_finite = [
            youngs_modulus,
            poisson_ratio,
            outer_diameter,
            inner_diameter,
        ]
        .iter()
        .all(|v| v.is_finite());
        if !all_finite {
            return Err(ReferenceError::InvalidStiffness(
                "tube parameters must be finite".to_string(),
            ));
        }
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(ReferenceError::InvalidStiffness(format!(
                "Poisson ratio must lie in (-1, 0.5), got {poisson_ratio}"
            )));
        }
        if !(inner_diameter >= 0.0 && outer_diameter > inner_diameter) {
            return Err(ReferenceError::InvalidStiffness(format!(
                "diameters must satisfy 0 <= d_i < d_a, got d_a = {outer_diameter}, \
                 d_i = {inner_diameter}"
            )));
        }
        let pi = std::f64::consts::PI;
        let area = pi * (outer_diameter.powi(2) - inner_diameter.powi(2)) / 4.0;
        let inertia = pi * (outer_diameter.powi(4) - inner_diameter.powi(4)) / 64.0;
        let shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
        Self::new(
            youngs_modulus * area,
            youngs_modulus * inertia,
            shear_modulus * 2.0 * inertia,
        )
    }

    /// Axial stiffness in tension, `EA_t` \[N\].
    pub fn axial_tension(&self) -> f64 {
        self.axial_tension
    }

    /// Axial stiffness in compression, `EA_c` \[N\].
    pub fn axial_compression(&self) -> f64 {
        self.axial_compression
    }

    /// Different bending stiffnesses about d2 (`EI₂`) and d3 (`EI₃`) \[N m²\]: a
    /// non-round section (ribbon, bundle).
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidStiffness`] unless both are finite and positive.
    pub fn with_bending(mut self, about_d2: f64, about_d3: f64) -> Result<Self> {
        for value in [about_d2, about_d3] {
            if !value.is_finite() || value <= 0.0 {
                return Err(ReferenceError::InvalidStiffness(format!(
                    "bending stiffness must be finite and positive, got {value}"
                )));
            }
        }
        self.bending = about_d2;
        self.bending_d3 = about_d3;
        Ok(self)
    }

    /// Bending stiffness `EI` \[N m²\] about d2 (and d3 for a round section).
    pub fn bending(&self) -> f64 {
        self.bending
    }

    /// Bending stiffness about d3 \[N m²\].
    pub fn bending_d3(&self) -> f64 {
        self.bending_d3
    }

    /// Torsional stiffness `GJ` \[N m²\] (about d1).
    pub fn torsion(&self) -> f64 {
        self.torsion
    }
}

/// A rod: stress-free polyline rest shape, rest frames, stiffnesses and an
/// optional distributed dead load.
#[derive(Debug, Clone, PartialEq)]
pub struct Rod {
    nodes: Vec<Vector3<f64>>,
    arc_lengths: Vec<f64>,
    rest_frames: Vec<Rotation3<f64>>,
    stiffness: Stiffness,
    distributed_load: Vector3<f64>,
}

/// Relative tolerance for the check that a user base frame's d1 follows the
/// first segment.
const FRAME_ALIGNMENT_TOLERANCE: f64 = 1e-9;

impl Rod {
    /// Rod with the default base rest frame: the minimal rotation taking the global
    /// x axis to the first segment's direction (the identity for a rod along +x).
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidRestShape`] for fewer than two nodes, non-finite
    /// coordinates, a zero-length segment, two consecutive segments pointing in
    /// opposite directions (the parallel transport is undefined), or a first
    /// segment along −x (give the base frame explicitly then).
    pub fn new(rest_nodes: Vec<Vector3<f64>>, stiffness: Stiffness) -> Result<Self> {
        let first = first_direction(&rest_nodes)?;
        let base_frame = minimal_rotation(&Vector3::x(), &first).ok_or_else(|| {
            ReferenceError::InvalidRestShape(
                "the first segment points along -x; give the base frame explicitly \
                 with Rod::with_base_frame"
                    .to_string(),
            )
        })?;
        Self::with_base_frame(rest_nodes, base_frame, stiffness)
    }

    /// Rod with an explicit base rest frame, whose first column (d1) must be the
    /// direction of the first segment (to 1e-9); its d2, d3 fix the roll of all rest
    /// frames.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidRestShape`] for an invalid polyline (see
    /// [`Rod::new`]) or a base frame that is non-finite or not along the first
    /// segment.
    pub fn with_base_frame(
        rest_nodes: Vec<Vector3<f64>>,
        base_frame: Rotation3<f64>,
        stiffness: Stiffness,
    ) -> Result<Self> {
        let first = first_direction(&rest_nodes)?;
        if !base_frame.matrix().iter().all(|v| v.is_finite()) {
            return Err(ReferenceError::InvalidRestShape(
                "base frame contains non-finite values".to_string(),
            ));
        }
        let d1: Vector3<f64> = base_frame.matrix().column(0).into();
        if (d1 - first).norm() > FRAME_ALIGNMENT_TOLERANCE {
            return Err(ReferenceError::InvalidRestShape(format!(
                "base frame d1 = {:?} is not along the first segment {:?}",
                d1.as_slice(),
                first.as_slice()
            )));
        }
        let mut arc_lengths = Vec::with_capacity(rest_nodes.len());
        arc_lengths.push(0.0);
        let mut rest_frames = Vec::with_capacity(rest_nodes.len() - 1);
        rest_frames.push(base_frame);
        let mut previous = first;
        for (k, pair) in rest_nodes.windows(2).enumerate() {
            let delta = pair[1] - pair[0];
            let length = delta.norm();
            let total = arc_lengths[k] + length;
            arc_lengths.push(total);
            if k == 0 {
                continue;
            }
            let direction = delta / length;
            let transport = minimal_rotation(&previous, &direction).ok_or_else(|| {
                ReferenceError::InvalidRestShape(format!(
                    "segments {} and {} point in opposite directions at node {k}",
                    k - 1,
                    k
                ))
            })?;
            rest_frames.push(transport * rest_frames[k - 1]);
            previous = direction;
        }
        Ok(Self {
            nodes: rest_nodes,
            arc_lengths,
            rest_frames,
            stiffness,
            distributed_load: Vector3::zeros(),
        })
    }

    /// Adds a distributed dead load `q` per unit reference length \[N/m\], global
    /// (e.g. gravity `ρ A g`).
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidBoundaryCondition`] if `load` is not finite.
    pub fn with_distributed_load(mut self, load: Vector3<f64>) -> Result<Self> {
        if !load.iter().all(|v| v.is_finite()) {
            return Err(ReferenceError::InvalidBoundaryCondition(
                "distributed load contains non-finite values".to_string(),
            ));
        }
        self.distributed_load = load;
        Ok(self)
    }

    /// Total reference length `L` (sum of the segment lengths).
    pub fn length(&self) -> f64 {
        self.arc_lengths[self.arc_lengths.len() - 1]
    }

    /// Number of segments `K`.
    pub fn segment_count(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Rest node positions `X_0 … X_K`.
    pub fn rest_nodes(&self) -> &[Vector3<f64>] {
        &self.nodes
    }

    /// Reference arc lengths of the rest nodes, `s_0 = 0 … s_K = L`.
    pub fn node_arc_lengths(&self) -> &[f64] {
        &self.arc_lengths
    }

    /// Rest frame of segment `k` (columns d1 = tangent, d2, d3), `None` if out of
    /// range.
    pub fn rest_frame(&self, segment: usize) -> Option<Rotation3<f64>> {
        self.rest_frames.get(segment).copied()
    }

    /// Material kink rotation at interior node `k` (1 ≤ k < K):
    /// `K_k = R_rest,k−1ᵀ R_rest,k`.
    pub fn kink(&self, node: usize) -> Option<Rotation3<f64>> {
        if node == 0 || node >= self.segment_count() {
            return None;
        }
        Some(self.rest_frames[node - 1].inverse() * self.rest_frames[node])
    }

    /// Stiffnesses.
    pub fn stiffness(&self) -> &Stiffness {
        &self.stiffness
    }

    /// Distributed dead load per unit reference length.
    pub fn distributed_load(&self) -> Vector3<f64> {
        self.distributed_load
    }

    /// Pose of the base (s = 0) in the rest state: `X_0` and the base rest frame.
    pub fn rest_base_pose(&self) -> Pose {
        Pose::new(self.nodes[0], self.rest_frames[0])
    }

    /// Pose of the end (s = L) in the rest state: `X_K` and the last segment's rest
    /// frame.
    pub fn rest_end_pose(&self) -> Pose {
        Pose::new(
            self.nodes[self.nodes.len() - 1],
            self.rest_frames[self.rest_frames.len() - 1],
        )
    }
}

/// Validates the node list and returns the unit direction of the first segment.
fn first_direction(nodes: &[Vector3<f64>]) -> Result<Vector3<f64>> {
    if nodes.len() < 2 {
        return Err(ReferenceError::InvalidRestShape(format!(
            "at least 2 rest nodes are needed, got {}",
            nodes.len()
        )));
    }
    if let Some(i) = nodes.iter().position(|x| !x.iter().all(|v| v.is_finite())) {
        return Err(ReferenceError::InvalidRestShape(format!(
            "rest node {i} has non-finite coordinates"
        )));
    }
    let scale = nodes
        .iter()
        .map(nalgebra::Matrix::amax)
        .fold(0.0_f64, f64::max)
        .max(f64::MIN_POSITIVE);
    for (k, pair) in nodes.windows(2).enumerate() {
        let length = (pair[1] - pair[0]).norm();
        if length <= 1e-12 * scale {
            return Err(ReferenceError::InvalidRestShape(format!(
                "segment {k} (nodes {k} and {}) has zero length",
                k + 1
            )));
        }
    }
    Ok((nodes[1] - nodes[0]).normalize())
}

/// The minimal rotation taking unit vector `a` to unit vector `b` (parallel
/// transport), `None` if they are (nearly) opposite. The angle comes from
/// `atan2(|a × b|, a · b)`, accurate for the tiny kinks of imperfections.
fn minimal_rotation(a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Rotation3<f64>> {
    let cos = a.dot(b);
    if cos < -1.0 + 1e-12 {
        return None;
    }
    let axis = a.cross(b);
    let sin = axis.norm();
    if sin == 0.0 {
        return Some(Rotation3::identity());
    }
    Some(Rotation3::new(axis * (sin.atan2(cos) / sin)))
}
