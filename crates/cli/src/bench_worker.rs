//! `pliant bench --only worker`: what one posed instant of the worker costs (inverse
//! kinematics, posture scores, body collisions; SPEC E1–E2) with hoses across the body,
//! as a ratio to the same instant in the same scene without hoses near the body — the cost of the
//! capsule–tube checks. Nothing here asserts a time.

use anyhow::{Context, Result};
use glam::DVec3;
use pliant_assembly::worker::{BodyPose, WorkerTrack};
use pliant_core::State;
use serde::Serialize;
use std::time::Instant;

/// Hoses across the worker's body and their elements.
pub const HOSES: usize = 5;
pub const ELEMENTS: usize = 30;

/// The cost of a posed instant with and without the hoses.
#[derive(Clone, Debug, Serialize)]
pub struct WorkerCost {
    pub hoses: usize,
    pub elements: usize,
    pub instants: u32,
    pub us_per_instant_without: f64,
    pub us_per_instant_with: f64,
    /// With over without.
    pub ratio: f64,
}

/// The 50th-percentile man standing at the origin facing +x and `hoses` hoses of
/// [`ELEMENTS`] elements along y in front of him, 150 mm apart from hip to chest height,
/// beside one hose 5 m behind him (a scene needs a hose; that one is never near the body).
fn scene(hoses: usize) -> Result<pliant_scene::LoadedScene> {
    let mut text = String::from(
        r#"
format = "pliant-scene"
version = 1
name = "worker benchmark"
length_unit = "mm"

[worker]
population = "male 50"
position = [0, 0, 0]
facing = [1, 0, 0]

[[hoses]]
name = "away"
material = "hose1"
elements = 4
start = [-5000, -400, 900]
path = [{ line = { to = [-5000, 400, 900] } }]
"#,
    );
    for i in 0..hoses {
        let z = 900 + 150 * i;
        text += &format!(
            r#"
[[hoses]]
name = "h{i}"
material = "hose1"
elements = {ELEMENTS}
start = [250, -400, {z}]
path = [{{ line = {{ to = [250, 400, {z}] }} }}]
"#
        );
    }
    pliant_scene::load_scene_str_in(&text, "worker-bench.toml", std::path::Path::new("."))
        .map_err(|e| anyhow::anyhow!("{e}"))
}

/// The mean time of one posed instant \[µs\] over `instants`, both hands reaching over
/// the hoses.
fn per_instant(hoses: usize, instants: u32) -> Result<f64> {
    let scene = scene(hoses)?;
    let setup = scene.workcell_setup().map_err(anyhow::Error::msg)?;
    let mut settings = setup.worker.context("the benchmark scene has a worker")?;
    settings.interval = 0.0;
    let mut track = WorkerTrack::new(settings)?;
    track.set_body_pose(BodyPose {
        head: None,
        hands: [
            Some(DVec3::new(0.45, -0.2, 1.2)),
            Some(DVec3::new(0.45, 0.2, 1.2)),
        ],
    });
    let state = State::at_rest(&setup.model);
    for _ in 0..instants / 10 + 1 {
        track.observe(&setup.model, &state, &[], false);
    }
    let started = Instant::now();
    for _ in 0..instants {
        track.observe(&setup.model, &state, &[], false);
    }
    Ok(started.elapsed().as_secs_f64() * 1e6 / instants as f64)
}

/// Measures both rows.
pub fn measure(quick: bool) -> Result<WorkerCost> {
    let instants = if quick { 20 } else { 1000 };
    let without = per_instant(0, instants).context("the worker without hoses")?;
    let with = per_instant(HOSES, instants).context("the worker with hoses")?;
    Ok(WorkerCost {
        hoses: HOSES,
        elements: ELEMENTS,
        instants,
        us_per_instant_without: without,
        us_per_instant_with: with,
        ratio: with / without,
    })
}

/// The rows as text.
pub fn render(c: &WorkerCost) -> String {
    format!(
        "worker, one posed instant (mean of {}): {:.1} µs without hoses near the body, {:.1} µs with {} hoses × {} elements across the body: ×{:.2}\n",
        c.instants, c.us_per_instant_without, c.us_per_instant_with, c.hoses, c.elements, c.ratio
    )
}
