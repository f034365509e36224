//! `pliant bench --only snapshot`: what one live snapshot costs the simulation thread of
//! `pliant serve` (it publishes up to 240 a second besides stepping), for the same hose
//! beside a part of few and of many vertices. The snapshot carries live state only
//! (positions, hand loads, fasteners, checks, the verdict so far); presentation data
//! such as the report's part outlines are made once per report, so the two costs should
//! match whatever the part's vertex count. Nothing here asserts a time.

use anyhow::{Context, Result};
use pliant_assembly::report::part_outline::part_outlines;
use pliant_scene::mesh::sphere_triangles;
use serde::Serialize;

/// Subdivisions of the icosphere part: 42 vertices (1) and 163 842 vertices (7).
pub const SUBDIVISIONS: [u32; 2] = [1, 7];

/// One row: the part's size, the mean cost of a snapshot, and for comparison what the
/// part outlines cost, which the report writer makes once per report (a snapshot that
/// made them would pay this every time).
#[derive(Clone, Debug, Serialize)]
pub struct SnapshotCost {
    pub part_vertices: usize,
    pub part_triangles: usize,
    pub snapshots: u32,
    pub us_per_snapshot: f64,
    pub us_part_outlines: f64,
}

/// A 20-element hose above a sphere of `subdivisions` (an icosphere: 10·4ⁿ + 2 vertices).
fn scene(subdivisions: u32) -> Result<pliant_scene::LoadedScene> {
    let text = format!(
        r#"
format = "pliant-scene"
version = 1
name = "snapshot benchmark"
length_unit = "mm"

[[parts]]
name = "ball"
sphere = {{ radius = 100, subdivisions = {subdivisions} }}
position = [250, 0, -200]

[[hoses]]
name = "hose"
material = "hose1"
start = [0, 0, 0]
path = [{{ line = {{ to = [500, 0, 0] }} }}]
elements = 20
"#
    );
    pliant_scene::load_scene_str_in(&text, "snapshot-bench.toml", std::path::Path::new("."))
        .map_err(|e| anyhow::anyhow!("{e}"))
}

/// Measures every row of [`SUBDIVISIONS`].
pub fn measure(quick: bool) -> Result<Vec<SnapshotCost>> {
    let snapshots = if quick { 50 } else { 1000 };
    SUBDIVISIONS
        .iter()
        .map(|&n| {
            let scene = scene(n)?;
            let cost = pliant_server::session::snapshot_cost(&scene, snapshots)
                .with_context(|| format!("starting the session on a sphere of {n} subdivisions"))?;
            let setup = scene.workcell_setup().map_err(anyhow::Error::msg)?;
            let started = std::time::Instant::now();
            std::hint::black_box(part_outlines(&setup.model.environment));
            let outlines = started.elapsed();
            let triangles = sphere_triangles(n).unwrap_or(0);
            Ok(SnapshotCost {
                part_vertices: triangles / 2 + 2,
                part_triangles: triangles,
                snapshots,
                us_per_snapshot: cost.as_secs_f64() * 1e6,
                us_part_outlines: outlines.as_secs_f64() * 1e6,
            })
        })
        .collect()
}

/// The rows as lines of text, with the ratio large / small.
pub fn render(rows: &[SnapshotCost]) -> String {
    let mut s = String::new();
    for r in rows {
        s.push_str(&format!(
            "snapshot beside a part of {:>7} vertices ({:>7} triangles): {:>8.1} µs (mean of {}); the report's part outlines, made once per report: {:>9.1} µs\n",
            r.part_vertices, r.part_triangles, r.us_per_snapshot, r.snapshots, r.us_part_outlines
        ));
    }
    if let (Some(small), Some(large)) = (rows.first(), rows.last()) {
        s.push_str(&format!(
            "snapshot, large part / small part: ×{:.2}\n",
            large.us_per_snapshot / small.us_per_snapshot
        ));
    }
    s
}
