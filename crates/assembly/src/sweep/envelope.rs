//! The swept envelope of each hose over a range of motion (SPEC K2): the volume its tube
//! takes at some checked instant, as a voxel set ([`super::voxels`], conservative by
//! about one voxel) and its closed surface ([`super::voxel_surface`]), with the clearance
//! from the envelope to every part that stands still. (A moving part's clearance is
//! the per-instant one of `motion.csv`: an envelope of all instants against a part at
//! one pose says nothing.)
//!
//! A sweep adds each checked instant's centre-line samples to a set per hose
//! ([`SweptHoses`]); the voxels and the surface are made once, for the report.

use super::centreline_samples::SweptSamples;
use super::voxel_surface::{voxel_surface, TriangleMesh};
use super::voxels::VoxelGrid;
use glam::DVec3;
use pliant_core::contact::part_gap::hose_part_gap;
use pliant_core::{Model, State};
use serde::Serialize;

/// Largest voxel \[m\] (smaller for thin hoses: half the thinnest outer radius).
pub const MAX_VOXEL: f64 = 0.005;
/// Most centre-line samples kept over all hoses (≈ 40 bytes each in their sets).
pub const MAX_SAMPLES: usize = 5_000_000;

/// The voxel size of a sweep \[m\]: `chosen`, else the smaller of [`MAX_VOXEL`] and half
/// the thinnest hose's outer radius `thinnest`.
pub fn voxel_size(chosen: Option<f64>, thinnest: f64) -> f64 {
    chosen.unwrap_or(MAX_VOXEL.min(thinnest / 2.0))
}

/// The cells of the dense grid ([`VoxelGrid`]) over the box [lo, hi] \[m\] grown by the
/// voxels' reach for a tube of outer radius `radius`, at voxel size `h`: a lower bound on
/// the grid of any set of instants whose tubes span that box (as f64: it may be huge).
pub fn grid_cells(lo: DVec3, hi: DVec3, radius: f64, h: f64) -> f64 {
    let grow = super::voxels::reach(radius, h);
    let size = (hi - lo + DVec3::splat(2.0 * grow)) / h;
    size.x.ceil() * size.y.ceil() * size.z.ceil()
}

/// The centre-line samples of every hose over the checked instants so far.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweptHoses {
    /// Voxel size \[m\]: the scene's, else min([`MAX_VOXEL`], thinnest outer radius / 2),
    /// as the studies' ([`voxel_size`]).
    pub voxel: f64,
    /// Each hose's largest outer radius \[m\].
    pub radius: Vec<f64>,
    pub samples: Vec<SweptSamples>,
    /// Why the samples stopped being kept (too many, or a state no hose has), if so.
    pub refused: Option<String>,
}

impl SweptHoses {
    /// Empty sets for the hoses of `model`, voxels of size `voxel` \[m\] (None: the
    /// default of [`voxel_size`]).
    pub fn new(model: &Model, voxel: Option<f64>) -> SweptHoses {
        let radius: Vec<f64> = model
            .hoses
            .iter()
            .map(|h| model.radius[h.nodes()].iter().copied().fold(0.0, f64::max))
            .collect();
        let thinnest = radius.iter().copied().fold(f64::INFINITY, f64::min);
        SweptHoses {
            voxel: voxel_size(voxel, thinnest),
            samples: vec![SweptSamples::default(); radius.len()],
            radius,
            refused: None,
        }
    }

    /// Adds every hose's centre line in `state`.
    pub fn add(&mut self, model: &Model, state: &State) {
        if self.refused.is_some() {
            return;
        }
        for (info, samples) in model.hoses.iter().zip(&mut self.samples) {
            if let Err(e) = samples.add(&state.x[info.nodes()], self.voxel) {
                self.refused = Some(format!("at t = {:.3} s: {e}", state.time));
                return;
            }
        }
        let kept: usize = self.samples.iter().map(|s| s.keys.len()).sum();
        if kept > MAX_SAMPLES {
            self.refused = Some(format!(
                "more than {MAX_SAMPLES} centre-line samples of {:.1} mm voxels at t = {:.3} s",
                1e3 * self.voxel,
                state.time
            ));
            for s in &mut self.samples {
                *s = SweptSamples::default();
            }
        }
    }
}

/// The clearance between an envelope and a part \[m\].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PartClearance {
    pub part: String,
    /// Negative where the part reaches into the envelope.
    pub clearance_m: f64,
}

/// One hose's envelope (`summary.json` `envelopes.hoses[]`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HoseEnvelope {
    pub hose: String,
    /// Its surface's files, in the output folder: binary STL and GLB (binary glTF).
    pub stl: String,
    pub glb: String,
    pub voxels: usize,
    /// The enclosed volume: voxels · h³ \[m³\].
    pub volume_m3: f64,
    /// Its bounding box's corners \[m\].
    pub bounds_m: [[f64; 3]; 2],
    pub triangles: usize,
    /// Every edge taken once in each direction as often (a watertight surface).
    pub closed: bool,
    /// To every part that stands still.
    pub clearance: Vec<PartClearance>,
    #[serde(skip)]
    pub grid: VoxelGrid,
    #[serde(skip)]
    pub mesh: TriangleMesh,
}

/// The envelopes of a sweep (`summary.json` `envelopes`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweptEnvelopes {
    pub voxel_m: f64,
    pub method: &'static str,
    pub hoses: Vec<HoseEnvelope>,
    /// The parts that move, whose clearance `motion.csv` gives instant by instant.
    pub moving_parts: Vec<String>,
    /// Why there is no envelope, if there is none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub refused: Option<String>,
}

/// What [`SweptEnvelopes::method`] says.
pub const METHOD: &str = "voxels whose centre lies within r + (√3/2)(h + h/4) + h/4 of a centre-line sample (h/2 apart, on the h/4 grid); surface: the faces of the occupied voxels' cubes (contains every recorded tube, conservative by at most about 2.4 h)";

/// The envelopes of `swept` in `model`: voxels, surfaces, and the clearance to each part
/// that stands still, measured from every occupied voxel's circumscribed sphere (radius
/// √3/2·h: never more than the cube's own clearance, at most (√3−1)/2·h less).
pub fn swept_envelopes(model: &Model, swept: &SweptHoses) -> SweptEnvelopes {
    let parts = &model.environment.parts;
    let moving_parts = (0..parts.len())
        .filter(|&p| model.kinematics.moves(p))
        .map(|p| parts[p].name.clone())
        .collect();
    let mut out = SweptEnvelopes {
        voxel_m: swept.voxel,
        method: METHOD,
        hoses: Vec::new(),
        moving_parts,
        refused: swept.refused.clone(),
    };
    if out.refused.is_some() {
        return out;
    }
    let h = swept.voxel;
    for (k, info) in model.hoses.iter().enumerate() {
        let grid = match VoxelGrid::of_samples(&swept.samples[k].sorted(), swept.radius[k], h) {
            Ok(g) => g,
            Err(e) => {
                out.refused = Some(format!("hose '{}': {e}", info.name));
                out.hoses.clear();
                return out;
            }
        };
        if grid.count() == 0 {
            continue;
        }
        let mesh = voxel_surface(&grid);
        let centres: Vec<DVec3> = grid
            .voxels()
            .map(|v| DVec3::from_array(v.map(|x| x as f64 * h)))
            .collect();
        let sphere = vec![3f64.sqrt() / 2.0 * h; centres.len()];
        let clearance = (0..parts.len())
            .filter(|&p| !model.kinematics.moves(p))
            .map(|p| PartClearance {
                part: parts[p].name.clone(),
                clearance_m: hose_part_gap(&model.environment, p, None, &centres, &sphere).0,
            })
            .filter(|c| c.clearance_m.is_finite())
            .collect();
        let (lo, hi) = mesh.bounds();
        out.hoses.push(HoseEnvelope {
            hose: info.name.clone(),
            stl: format!("envelope-{}.stl", file_word(&info.name)),
            glb: format!("envelope-{}.glb", file_word(&info.name)),
            voxels: grid.count(),
            volume_m3: grid.count() as f64 * h.powi(3),
            bounds_m: [lo, hi],
            triangles: mesh.triangles.len(),
            closed: mesh.is_closed(),
            clearance,
            grid,
            mesh,
        });
    }
    out
}

/// `name` as a file name's word: letters, digits, `-` and `_`, the rest `_`.
fn file_word(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

impl SweptEnvelopes {
    /// Writes each envelope's surface as binary STL and as GLB into `out`; the error
    /// names the file.
    pub fn write_surfaces(&self, out: &std::path::Path) -> std::io::Result<()> {
        for e in &self.hoses {
            write_file(&out.join(&e.stl), |file| e.mesh.write_stl(file))?;
            write_file(&out.join(&e.glb), |file| {
                super::glb::write_glb(&e.mesh, &format!("envelope of {}", e.hose), file)
            })?;
        }
        Ok(())
    }
}

/// Creates `path` and writes it with `write`; the error names the file.
fn write_file(
    path: &std::path::Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let named = |err: std::io::Error| {
        std::io::Error::new(err.kind(), format!("writing {}: {err}", path.display()))
    };
    let mut file = std::io::BufWriter::new(std::fs::File::create(path).map_err(named)?);
    write(&mut file).map_err(named)?;
    std::io::Write::flush(&mut file).map_err(named)
}

#[cfg(test)]
mod tests {
    use super::super::centreline_samples::sample_keys;
    use super::*;
    use std::f64::consts::PI;

    /// A straight hose from a to b along x, turned about z through `theta` in `steps`
    /// steps (a hose on a hinged part): `steps + 1` frames of `nodes` nodes, flat.
    fn hinged_frames(a: f64, b: f64, nodes: usize, theta: f64, steps: usize) -> Vec<f64> {
        let mut frames = Vec::new();
        for s in 0..=steps {
            let (sin, cos) = (theta * s as f64 / steps as f64).sin_cos();
            for i in 0..nodes {
                let x = a + (b - a) * i as f64 / (nodes - 1) as f64;
                frames.extend([x * cos, x * sin, 0.0]);
            }
        }
        frames
    }

    /// The volume of the points within `r` of the annular sector a ≤ ρ ≤ b, 0 ≤ φ ≤ θ in
    /// the plane z = 0 — the tube of radius r around a radial segment turned through θ.
    /// Steiner's formula for a planar set whose reach exceeds r (here a > r):
    /// V = 2r·A + (π r²/2)·P + (4/3)π r³, A = θ(b² − a²)/2, P = θ(a + b) + 2(b − a).
    fn swept_capsule_volume(a: f64, b: f64, theta: f64, r: f64) -> f64 {
        let area = theta * (b * b - a * a) / 2.0;
        let perimeter = theta * (a + b) + 2.0 * (b - a);
        2.0 * r * area + PI * r * r / 2.0 * perimeter + 4.0 / 3.0 * PI * r.powi(3)
    }

    #[test]
    fn a_hose_turned_on_a_hinge_sweeps_the_tube_around_an_annular_sector_within_a_voxel() {
        let (a, b, r, theta) = (0.1, 0.3, 0.008, 70f64.to_radians());
        let h = MAX_VOXEL.min(r / 2.0);
        let (nodes, steps) = (21, 700);
        let frames = hinged_frames(a, b, nodes, theta, steps);
        let keys = sample_keys(&frames, steps + 1, nodes, h).unwrap();
        let grid = VoxelGrid::of_samples(&keys, r, h).unwrap();
        let volume = grid.count() as f64 * h.powi(3);
        let exact = swept_capsule_volume(a, b, theta, r);
        // conservative: the envelope holds the whole swept tube ...
        assert!(volume >= exact, "{volume} < exact {exact}");
        // ... and reaches at most r + 2.42 h from the centre lines (the module's bound)
        let widest = swept_capsule_volume(a, b, theta, r + 2.42 * h);
        assert!(volume <= widest, "{volume} > {widest}");
        // the thickness it adds, as the tube radius δ beyond r that gives its volume
        let (mut lo, mut hi) = (0.0, 2.42 * h);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if swept_capsule_volume(a, b, theta, r + mid) < volume {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        println!(
            "hinged sweep: {} voxels of {} mm, {volume:.4e} m³ against exact {exact:.4e} m³: \
             as a tube {:.2} voxels thicker",
            grid.count(),
            1e3 * h,
            lo / h
        );
        assert!(lo <= 1.5 * h, "{} voxels thicker", lo / h);
        let mesh = voxel_surface(&grid);
        assert!(mesh.is_closed());
        assert!((mesh.volume() - volume).abs() < 1e-9 * volume);
    }

    #[test]
    fn the_envelope_contains_every_recorded_tube() {
        let (a, b, r) = (0.05, 0.25, 0.006);
        let h = MAX_VOXEL.min(r / 2.0);
        let (nodes, steps) = (9, 12); // coarse steps: each frame's tube must be in
        let frames = hinged_frames(a, b, nodes, 40f64.to_radians(), steps);
        let keys = sample_keys(&frames, steps + 1, nodes, h).unwrap();
        let grid = VoxelGrid::of_samples(&keys, r, h).unwrap();
        let at = |f: usize, i: usize| DVec3::from_slice(&frames[3 * (f * nodes + i)..]);
        let mut tested = 0;
        for f in 0..=steps {
            for i in 1..nodes {
                let (p, q) = (at(f, i - 1), at(f, i));
                let axis = (q - p).normalize();
                let (u, w) = axis.any_orthonormal_pair();
                for s in 0..=16 {
                    let c = p + (q - p) * (s as f64 / 16.0);
                    for k in 0..24 {
                        let phi = 2.0 * PI * k as f64 / 24.0;
                        for rho in [r, 0.5 * r] {
                            let x = c + rho * (phi.cos() * u + phi.sin() * w);
                            assert!(grid.covers(x.to_array()), "frame {f} element {i}: {x}");
                            tested += 1;
                        }
                    }
                }
                // the caps: the tube is the union of balls around the centre line
                for e in [p - r * axis, q + r * axis] {
                    assert!(grid.covers(e.to_array()));
                }
            }
        }
        assert!(tested > 50_000);
    }
}
