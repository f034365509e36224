//! The import report: counts, geometry checks, skipped items and warnings.

use std::fmt;
use std::path::PathBuf;

use serde::Serialize;

use crate::model::Harness;
use crate::scene::{held_nodes, SegmentOut};

/// Relative difference between a centre curve's arc length and `Virtual_length` above
/// which a warning is given (0.1 %).
pub const LENGTH_TOLERANCE: f64 = 1e-3;

/// What an import did.
#[derive(Debug, Clone, Serialize)]
pub struct ImportReport {
    pub source: String,
    pub kbl_version: String,
    pub nodes: usize,
    pub segments: usize,
    /// Nodes where two or more segments meet (each becomes a `[[junctions]]` entry).
    pub junctions: usize,
    /// Nodes where three or more meet.
    pub branch_points: usize,
    pub max_junction_degree: usize,
    pub total_length_m: f64,
    pub total_virtual_length_m: f64,
    pub wires: usize,
    pub max_wires_per_segment: usize,
    pub fixings: usize,
    pub protections: usize,
    pub connectors: usize,
    pub connectors_on_nodes: usize,
    pub fixes_in_timeline: usize,
    /// Segments whose centre curve was trimmed to its nodes.
    pub trimmed_segments: Vec<String>,
    /// Largest distance \[m\] of a (trimmed) curve end from its node.
    pub max_end_error_m: f64,
    /// Largest |arc length − Virtual_length| / Virtual_length and its segment.
    pub max_length_error: (f64, String),
    pub skipped: Vec<(String, String)>,
    pub warnings: Vec<String>,
    pub scene: PathBuf,
    pub harness_json: PathBuf,
    /// The installation by a worker (`install.toml`), or why none was written.
    pub install: Result<PathBuf, crate::install::NotInstalled>,
    /// What was imported of the file when a branch was asked for (`--branch`).
    pub branch: Option<String>,
}

impl ImportReport {
    pub fn new(
        h: &Harness,
        segs: &[SegmentOut],
        cut: Option<usize>,
        scene: PathBuf,
        harness_json: PathBuf,
    ) -> Self {
        let degree: Vec<usize> = h.segments_at_nodes().iter().map(Vec::len).collect();
        let mut max_length_error = (0.0, String::new());
        let mut max_end_error_m: f64 = 0.0;
        for (s, o) in h.segments.iter().zip(segs) {
            max_end_error_m = max_end_error_m
                .max(o.curve.start_error)
                .max(o.curve.end_error);
            if let Some(v) = s.virtual_length.filter(|v| *v > 0.0) {
                let rel = (o.curve.length - v).abs() / v;
                if rel > max_length_error.0 {
                    max_length_error = (rel, s.kbl_id.clone());
                }
            }
        }
        ImportReport {
            source: h.source.clone(),
            kbl_version: h.kbl_version.clone(),
            nodes: h.nodes.len(),
            segments: h.segments.len(),
            junctions: degree.iter().filter(|&&d| d >= 2).count(),
            branch_points: degree.iter().filter(|&&d| d >= 3).count(),
            max_junction_degree: degree.iter().copied().max().unwrap_or(0),
            total_length_m: segs.iter().map(|o| o.curve.length).sum(),
            total_virtual_length_m: h.total_virtual_length(),
            wires: h.wires.iter().filter(|w| !w.segments.is_empty()).count(),
            max_wires_per_segment: h.segments.iter().map(|s| s.wires.len()).max().unwrap_or(0),
            fixings: h.fixings.len(),
            protections: h.protections.len(),
            connectors: h.connectors.len(),
            connectors_on_nodes: h.connectors.iter().filter(|c| c.node.is_some()).count(),
            fixes_in_timeline: held_nodes(h, segs, cut).len(),
            trimmed_segments: h
                .segments
                .iter()
                .zip(segs)
                .filter(|(_, o)| o.curve.trimmed)
                .map(|(s, _)| s.kbl_id.clone())
                .collect(),
            max_end_error_m,
            max_length_error,
            skipped: h.skipped.clone(),
            warnings: h.warnings.clone(),
            scene,
            harness_json,
            install: Err(crate::install::NotInstalled::NoConnector),
            branch: None,
        }
    }
}

impl fmt::Display for ImportReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{} ({})",
            self.source,
            crate::model::format_version(&self.kbl_version)
        )?;
        if let Some(b) = &self.branch {
            writeln!(f, "  {b}")?;
        }
        writeln!(
            f,
            "  {} nodes, {} segments ({:.3} m of centre line; virtual length {:.3} m)",
            self.nodes, self.segments, self.total_length_m, self.total_virtual_length_m
        )?;
        writeln!(
            f,
            "  {} junctions ({} branch points of 3 or more segments, up to {} at one node)",
            self.junctions, self.branch_points, self.max_junction_degree
        )?;
        writeln!(
            f,
            "  {} routed wires/cables (up to {} in one segment)",
            self.wires, self.max_wires_per_segment
        )?;
        writeln!(
            f,
            "  {} fixings, {} protection areas",
            self.fixings, self.protections
        )?;
        writeln!(
            f,
            "  {} connectors, {} of them on a node",
            self.connectors, self.connectors_on_nodes
        )?;
        writeln!(
            f,
            "  timeline: {} fixes, then settle",
            self.fixes_in_timeline
        )?;
        writeln!(
            f,
            "  centre curves: ends within {:.2e} mm of their nodes; length vs Virtual_length up to {:.3} % ({}); {} trimmed: {}",
            self.max_end_error_m * 1e3,
            self.max_length_error.0 * 100.0,
            self.max_length_error.1,
            self.trimmed_segments.len(),
            self.trimmed_segments.join(", ")
        )?;
        if !self.skipped.is_empty() {
            writeln!(f, "  skipped {}:", self.skipped.len())?;
            for (id, why) in &self.skipped {
                writeln!(f, "    {id}: {why}")?;
            }
        }
        if !self.warnings.is_empty() {
            writeln!(f, "  warnings {}:", self.warnings.len())?;
            for w in &self.warnings {
                writeln!(f, "    {w}")?;
            }
        }
        writeln!(
            f,
            "  wrote {} and {}",
            self.scene.display(),
            self.harness_json.display()
        )?;
        match &self.install {
            Ok(p) => writeln!(
                f,
                "  wrote {}: the harness installed by a worker (connectors plugged, fixings pressed in)",
                p.display()
            ),
            Err(why) => writeln!(f, "  no install.toml: {why}"),
        }
    }
}
