//! `pliant bench --harness`: the main harness of `data/harness/` (183 segments, 51
//! junctions, 1605 elements) in a quasi-static session. It is imported from its KBL file
//! and settled in its installed state by its own timeline (the first equilibrium: the
//! drawn route springing out between its fixings); then a hand grabs the middle of its
//! longest segment and moves it as a person does in a session: back and forth across the
//! segment, ±10 mm in 2 mm steps ([`hand_offset`]). The segment is held by fixings on
//! both sides, so the hand bends it between them without stretching it much: its forces
//! stay those of a harness being handled (newtons), and the solver's tolerance, relative
//! to the load scale, stays as tight as a user's session needs. One update is one step of
//! the workcell — the equilibrium, fasteners, checks and hand loads a user waits for.
//! Beside it, the same motion on one chain of as many elements (held every 40 elements,
//! the hand in the middle of a span): the cost per element of a network against a chain.
//! A secondary row, "pulled hard" (the bench's headline before): the hand lets go, grabs
//! the middle of the longest segment — a span held by fixings on both sides — and drags
//! it 2 mm per update in one direction (60 mm in 30 updates): the span is stretched by
//! centimetres and its forces grow to meganewtons — not a hand's motion, kept to show the cost of updates
//! far from the settled state. Nothing here asserts a time.

use crate::bench::{median, thread_cpu_seconds};
use anyhow::{anyhow, Context, Result};
use glam::DVec3;
use pliant_assembly::{run_timeline, Grip, Input, NoObserver, Runner, Workcell, WorkcellOptions};
use pliant_scene::LoadedScene;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The main harness's KBL file, in the repository's `data/harness/`.
pub const MAIN_HARNESS: &str = "kblxml_2.4sr-1_tab016120_modulare_ltgs._160718.kbl";
/// How far the hand moves per update \[m\].
pub const HAND_STEP: f64 = 0.002;
/// How far the hand goes to either side of where it grabbed \[m\].
pub const HAND_REACH: f64 = 0.010;
/// The goal for one update \[ms\]: interactive on one core.
pub const GOAL_MS: f64 = 10.0;

/// What `pliant bench --harness` measures.
#[derive(Clone, Debug, Serialize)]
pub struct HarnessBench {
    pub segments: usize,
    pub junctions: usize,
    pub elements: usize,
    /// Wall time of the imported timeline (hold the fixings and connectors, settle) \[s\].
    pub settle_s: f64,
    /// Median wall time of one update after the hand moved \[ms\] (the hand's motion:
    /// back and forth, [`hand_offset`]).
    pub update_ms: f64,
    /// Median CPU time of the simulating thread for one update \[ms\]: the cost on one
    /// core, without the waits of a shared machine.
    pub update_cpu_ms: f64,
    /// Newton iterations of the update whose CPU time is the median, and the fewest and
    /// most of any update: the median's cost depends on which iteration count it falls
    /// on (the bench's first updates take more iterations than its later ones).
    pub update_iterations: usize,
    pub update_iterations_range: [usize; 2],
    /// The largest force the hand exerted after any of these updates \[N\]: how gently
    /// it moves the harness.
    pub hand_force_n: f64,
    pub goal_ms: f64,
    /// The same update on one chain of as many elements \[ms\] (wall, CPU).
    pub chain_update_ms: f64,
    pub chain_update_cpu_ms: f64,
    pub chain_update_iterations: usize,
    /// CPU cost per element of an update, network and chain \[µs\].
    pub update_us_per_element: f64,
    pub chain_update_us_per_element: f64,
    /// The harness pulled hard: after the back-and-forth motion, the hand drags the
    /// grabbed point [`HAND_STEP`] per update in one direction (wall, CPU \[ms\], Newton
    /// iterations at the CPU median and their range).
    pub pulled_update_ms: f64,
    pub pulled_update_cpu_ms: f64,
    pub pulled_update_iterations: usize,
    pub pulled_update_iterations_range: [usize; 2],
    pub pulled_hand_force_n: f64,
    pub updates: usize,
}

/// Where the hand is after update `k` (1, 2, …), along its direction from where it
/// grabbed \[m\]: a triangle wave of amplitude [`HAND_REACH`] in steps of
/// [`HAND_STEP`] — out to +10 mm, across to −10 mm, back — the small back-and-forth
/// moves a person makes while placing a segment.
pub fn hand_offset(k: usize) -> f64 {
    let steps = (HAND_REACH / HAND_STEP).round() as i64; // a quarter period
    let phase = (k as i64 + steps).rem_euclid(4 * steps); // 0 at −reach
    let up = (phase - 2 * steps).abs(); // 2·steps at −reach, 0 at +reach
    (steps - up) as f64 * HAND_STEP
}

/// The pulled-hard row's hand after update `k`: [`HAND_STEP`] further each update \[m\].
pub fn pulled_offset(k: usize) -> f64 {
    HAND_STEP * k as f64
}

/// The repository's copy of the main harness (this binary was built from the clone).
fn main_harness() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/harness")
        .join(MAIN_HARNESS)
}

/// Imports the main harness into a scratch folder and loads the scene written there.
pub(crate) fn import_main_harness() -> Result<LoadedScene> {
    let kbl = main_harness();
    let dir = std::env::temp_dir().join(format!("pliant-bench-harness-{}", std::process::id()));
    pliant_harness::import_kbl(&kbl, &dir)
        .with_context(|| format!("importing {}", kbl.display()))?;
    let scene = pliant_scene::load_scene_file(&dir.join("scene.toml"));
    let _ = std::fs::remove_dir_all(&dir);
    Ok(scene?)
}

/// One chain of `elements` elements as long as the harness's segments together, held
/// every 40 elements, under the static solver.
pub(crate) fn chain(elements: usize, length_m: f64) -> Result<LoadedScene> {
    let mut text = format!(
        r#"format = "pliant-scene"
version = 1
name = "chain benchmark"
length_unit = "m"

[simulation]
solver = "static"

[[hoses]]
name = "chain"
material = "hose1"
start = [0, 0, 0]
path = [{{ line = {{ to = [{length_m}, 0, 0] }} }}]
elements = {elements}
"#
    );
    for node in (0..=elements).step_by(40).chain([elements]) {
        text.push_str(&format!(
            "\n[[timeline]]\naction = \"fix\"\nhose = \"chain\"\nnode = {node}\n"
        ));
    }
    text.push_str("\n[[timeline]]\naction = \"settle\"\n");
    pliant_scene::load_scene_str_in(&text, "chain-bench.toml", Path::new("."))
        .map_err(|e| anyhow!("{e}"))
}

/// Runs the scene's timeline; returns the workcell and the wall time \[s\].
pub(crate) fn settled(scene: &LoadedScene) -> Result<(Workcell, f64)> {
    let setup = scene.workcell_setup().map_err(|e| anyhow!(e))?;
    let mut cell = Runner::from_setup(setup, WorkcellOptions::default())
        .workcell()
        .map_err(|e| anyhow!(e))?;
    let start = Instant::now();
    run_timeline(&mut cell, &scene.timeline, &mut NoObserver)
        .map_err(|e| anyhow!("settling '{}': {}", scene.name, e.reason))?;
    Ok((cell, start.elapsed().as_secs_f64()))
}

/// What [`updates`] measured: median wall and CPU time \[ms\], the Newton iterations of
/// the update at the CPU median, and the fewest and most iterations of any update.
struct Updates {
    wall_ms: f64,
    cpu_ms: f64,
    iterations_at_median: usize,
    iterations_range: [usize; 2],
    /// The largest force the hand exerted after any update \[N\].
    hand_force_n: f64,
}

/// A hand grabs `at` firmly.
fn grab(cell: &mut Workcell, at: DVec3) -> Result<()> {
    cell.apply(Input::Grab {
        hand: 1,
        at,
        grip: Grip::Firm,
    })
    .map_err(|r| anyhow!("the benchmark hand was refused: {r:?}"))?;
    Ok(())
}

/// Times `updates` updates of the hand that holds `at`: before update `k` it moves to
/// `offset(k)` from `at` along `direction`.
fn updates(
    cell: &mut Workcell,
    at: DVec3,
    direction: DVec3,
    updates: usize,
    offset: fn(usize) -> f64,
) -> Result<Updates> {
    let refused = |r| anyhow!("the benchmark hand was refused: {r:?}");
    let step = cell.time_step();
    let mut times = Vec::with_capacity(updates);
    let mut cpu_times = Vec::with_capacity(updates);
    let mut iterations = Vec::with_capacity(updates);
    let mut hand_force_n: f64 = 0.0;
    for k in 1..=updates {
        cell.apply(Input::MoveHand {
            hand: 1,
            waypoints: vec![at + direction * offset(k)],
            rotation: DVec3::ZERO,
            duration: step,
        })
        .map_err(refused)?;
        let (start, cpu) = (Instant::now(), thread_cpu_seconds());
        cell.step(&mut NoObserver)
            .map_err(|d| anyhow!("update {k} diverged: {d}"))?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        cpu_times.push((thread_cpu_seconds() - cpu) * 1e3);
        iterations.push(cell.solver().last.iterations);
        let load = cell.hand_record(1).map_err(refused)?.load;
        hand_force_n = hand_force_n.max(load.force.length());
    }
    // the update at the (upper) middle of the CPU times
    let mut by_cpu: Vec<usize> = (0..updates).collect();
    by_cpu.sort_by(|&a, &b| cpu_times[a].total_cmp(&cpu_times[b]));
    let fewest = iterations.iter().copied().min().unwrap_or(0);
    let most = iterations.iter().copied().max().unwrap_or(0);
    Ok(Updates {
        wall_ms: median(&times),
        cpu_ms: median(&cpu_times),
        iterations_at_median: by_cpu.get(updates / 2).map_or(0, |&k| iterations[k]),
        iterations_range: [fewest, most],
        hand_force_n,
    })
}

/// Where the hand grabs and a direction across the harness there: the middle node of
/// the longest stretch of a segment that nothing holds (no fixing, fixed or driven
/// node, mount), so that the hand's back-and-forth moves bend the stretch between the
/// points that hold it rather than stretch a short span between two fixings.
pub(crate) fn grab_point(cell: &Workcell) -> (DVec3, DVec3) {
    use pliant_core::loads::LoadCase;
    let model = cell.model();
    let state = cell.state();
    let x = &state.x;
    let mut held = vec![false; x.len()];
    for (_, case) in state.loads.iter() {
        if !matches!(case, LoadCase::DeadLoad(_)) {
            held[case.node()] = true;
        }
    }
    // (rest length, first node, last node) of the longest unheld stretch
    let mut best = (0.0, 0, 0);
    for hose in &model.hoses {
        let nodes = hose.nodes();
        let mut first = nodes.start;
        let mut length = 0.0;
        for i in nodes.start..nodes.end {
            if held[i] {
                first = i + 1;
                length = 0.0;
                continue;
            }
            if i > first {
                length += model.rest_x[i].distance(model.rest_x[i - 1]);
            }
            if length > best.0 {
                best = (length, first, i);
            }
        }
    }
    let mid = ((best.1 + best.2) / 2).clamp(1, x.len() - 2);
    let along = (x[mid + 1] - x[mid - 1]).normalize_or(DVec3::X);
    (x[mid], along.any_orthonormal_vector())
}

/// The middle node of the longest segment and a direction across it: where the pulled
/// row's hand grabs (a span held by fixings on both sides).
pub(crate) fn middle_of_longest(cell: &Workcell) -> (DVec3, DVec3) {
    let model = cell.model();
    let x = &cell.state().x;
    let longest = model
        .hoses
        .iter()
        .max_by_key(|h| h.element_count)
        .expect("a scene has a hose");
    let nodes = longest.nodes();
    let mid = nodes.start + (nodes.end - nodes.start) / 2;
    let along = (x[mid + 1] - x[mid - 1]).normalize_or(DVec3::X);
    (x[mid], along.any_orthonormal_vector())
}

/// Measures the rows (`quick`: 3 updates each instead of 30).
pub fn run(quick: bool) -> Result<HarnessBench> {
    let count = if quick { 3 } else { 30 };
    let scene = import_main_harness()?;
    let (mut cell, settle_s) = settled(&scene)?;
    let model = cell.model().clone();
    let length: f64 = model.elements.iter().map(|e| e.rest_length).sum();
    let (at, across) = grab_point(&cell);
    grab(&mut cell, at)?;
    let network = updates(&mut cell, at, across, count, hand_offset)?;
    // the hand is back where it grabbed (the wave ends on a whole period); it lets go
    // and pulls the middle of the longest segment, between its fixings
    cell.apply(Input::ReleaseHand { hand: 1 })
        .map_err(|r| anyhow!("the benchmark hand could not let go: {r:?}"))?;
    let (at, across) = middle_of_longest(&cell);
    grab(&mut cell, at)?;
    let pulled = updates(&mut cell, at, across, count, pulled_offset)?;
    let elements = model.elements.len();
    let (mut line, _) = settled(&chain(elements, length)?)?;
    let span_middle = line.state().x[20];
    grab(&mut line, span_middle)?;
    let chain = updates(&mut line, span_middle, DVec3::Y, count, hand_offset)?;
    Ok(HarnessBench {
        segments: model.hoses.len(),
        junctions: model.junctions.len(),
        elements,
        settle_s,
        update_ms: network.wall_ms,
        update_cpu_ms: network.cpu_ms,
        update_iterations: network.iterations_at_median,
        update_iterations_range: network.iterations_range,
        hand_force_n: network.hand_force_n,
        goal_ms: GOAL_MS,
        chain_update_ms: chain.wall_ms,
        chain_update_cpu_ms: chain.cpu_ms,
        chain_update_iterations: chain.iterations_at_median,
        update_us_per_element: network.cpu_ms * 1e3 / elements as f64,
        chain_update_us_per_element: chain.cpu_ms * 1e3 / elements as f64,
        pulled_update_ms: pulled.wall_ms,
        pulled_update_cpu_ms: pulled.cpu_ms,
        pulled_update_iterations: pulled.iterations_at_median,
        pulled_update_iterations_range: pulled.iterations_range,
        pulled_hand_force_n: pulled.hand_force_n,
        updates: count,
    })
}

/// The rows as lines of text.
pub fn render(b: &HarnessBench) -> String {
    format!(
        "main harness: {} segments, {} junctions, {} elements (static solver, one core)\n\
         \x20 settled in its installed state in {:.2} s\n\
         \x20 one update after the hand moves {} mm (back and forth, ±{} mm): {:.2} ms CPU, {:.2} ms wall (goal {} ms), \
         {:.2} µs CPU per element; {} Newton iterations at the median ({}–{} over the updates); hand force ≤ {:.3} N\n\
         \x20 one chain of as many elements, the same motion: {:.2} ms CPU, {:.2} ms wall, {:.2} µs CPU per element \
         (network / chain {:.2}); {} Newton iterations at the median\n\
         \x20 the harness pulled hard ({} mm further each update): {:.2} ms CPU, {:.2} ms wall; \
         {} Newton iterations at the median ({}–{}); hand force ≤ {:.3e} N\n",
        b.segments,
        b.junctions,
        b.elements,
        b.settle_s,
        HAND_STEP * 1e3,
        HAND_REACH * 1e3,
        b.update_cpu_ms,
        b.update_ms,
        b.goal_ms,
        b.update_us_per_element,
        b.update_iterations,
        b.update_iterations_range[0],
        b.update_iterations_range[1],
        b.hand_force_n,
        b.chain_update_cpu_ms,
        b.chain_update_ms,
        b.chain_update_us_per_element,
        b.update_cpu_ms / b.chain_update_cpu_ms,
        b.chain_update_iterations,
        HAND_STEP * 1e3,
        b.pulled_update_cpu_ms,
        b.pulled_update_ms,
        b.pulled_update_iterations,
        b.pulled_update_iterations_range[0],
        b.pulled_update_iterations_range[1],
        b.pulled_hand_force_n,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hand's wave: every move is one step, it never leaves ±reach, reaches both
    /// sides, and the bench's 30 updates end where the hand grabbed.
    #[test]
    fn the_hand_goes_back_and_forth_in_steps() {
        let offsets: Vec<f64> = (0..=30).map(hand_offset).collect();
        assert_eq!(offsets[0], 0.0);
        for pair in offsets.windows(2) {
            assert!(
                ((pair[1] - pair[0]).abs() - HAND_STEP).abs() < 1e-15,
                "{pair:?}"
            );
        }
        assert!(offsets.iter().all(|o| o.abs() <= HAND_REACH + 1e-15));
        let (lo, hi) = offsets
            .iter()
            .fold((0.0_f64, 0.0_f64), |(l, h), &o| (l.min(o), h.max(o)));
        assert!((hi - HAND_REACH).abs() < 1e-15 && (lo + HAND_REACH).abs() < 1e-15);
        assert!(offsets[30].abs() < 1e-15);
    }
}
