//! `pliant bench [--json] [--quick]`: the performance benchmark (SPEC §6, docs/performance.md).
//!
//! Every case runs the real explicit step (`pliant_core::integrators::explicit::step`) with the model's
//! automatic stable time step (never overridden: the point is the physically correct step,
//! SPEC P4), gravity on, default damping, one end of every hose fixed and the rest hanging
//! free from a horizontal start, so that the hoses fall and swing with large rotations.
//! Hose: library material 1 (oil return hose, SPEC M4: d_i 10 mm, d_a 16 mm,
//! E_t 11.583 MPa, E_c 13.1363 MPa, ρ 940 kg/m³, ν 0.49), element length 24 mm (1.5 d_a).
//!
//! For each case: a warm-up, then several repeats each long enough to average out timer
//! resolution; the median over the repeats is reported. Only ratios, medians and scaling
//! are meant to be compared between machines; nothing here asserts an absolute time.

use anyhow::{bail, Context, Result};
use comfy_table::{presets, CellAlignment, Table};
use glam::DVec3;
use pliant_core::kinematics::{Oscillation, PartMotion, Periodic};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::rod::frames::node_frames;
use pliant_core::RigidPartSpec;
use pliant_core::{
    health, integrators::explicit, HoseSpec, Material, Model, Section, SimSettings, State,
    WorldSpec,
};
use serde::Serialize;
use std::time::{Duration, Instant};

/// Command-line options of `pliant bench`.
#[derive(Clone, Copy, Debug, Default)]
pub struct BenchOptions {
    /// Print one JSON object on stdout instead of the human table.
    pub json: bool,
    /// Shrink the measuring time (CI smoke test); every row is still measured.
    pub quick: bool,
    /// Only the engine-bay section ([`crate::bench_engine_bay`]).
    pub engine_bay_only: bool,
    /// Only the harness section ([`crate::bench_harness`]).
    pub harness_only: bool,
    /// Measure only one group of rows (for working on one part of the engine).
    pub only: Option<BenchOnly>,
}

/// A group of rows `pliant bench --only` measures on its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchOnly {
    /// 5 hoses × 30 without and with the 100 352-triangle floor, back to back.
    Contact,
    /// The Newton solvers' rows (quasi-static updates, implicit steps).
    Newton,
    /// One live snapshot of `pliant serve` beside a part of 42 and of 163 842 vertices.
    Snapshot,
    /// One posed instant of the worker without and with 5 hoses × 30 across the body.
    Worker,
    /// The contact-free single-hose rows (10 … 10 000 elements): the explicit step alone.
    Explicit,
}

/// Element length of the benchmark hoses \[m\]: 1.5 × d_a.
pub const ELEMENT_LENGTH: f64 = 0.024;
/// Single-hose sizes, fitted for the scaling slope; 2 500 is the single hose issue 40
/// asks to run in real time on one core.
pub const SINGLE_HOSE_ELEMENTS: [usize; 6] = [10, 30, 100, 1000, 2500, 10_000];
/// Hose counts of the multi-hose cases (30 elements each).
pub const HOSE_COUNTS: [usize; 3] = [1, 5, 30];
/// The single-hose size whose cost is the headline number.
pub const HEADLINE_ELEMENTS: usize = 100;

/// Floating-point operations per step, counted by hand from the source of
/// `BeamElement::loads`, `forces::{internal_loads, add_body_loads}` and `explicit::step`
/// (glam 0.30 scalar f64 code; +, −, ×, ÷ and √ count one each; sin, cos and atan2 are
/// libm calls, counted separately and not included). docs/performance.md has the
/// breakdown. Rust does not contract a·b + c into FMA, so each operation is one instruction.
pub mod flops {
    /// `BeamElement::loads` (628, on the usual branch θ² ≥ 1e-6 of the Jacobian) plus the
    /// four vector additions of the assembly in `internal_loads` (12).
    pub const PER_ELEMENT: u64 = 640;
    /// Gravity and mass-proportional damping per node (`add_body_loads`).
    pub const PER_NODE_BODY: u64 = 19;
    /// Leapfrog update of a free node: velocity, position, angular velocity, and
    /// q ← normalize(exp(ω Δt) q).
    pub const PER_FREE_NODE: u64 = 76;
    /// A held (fixed) node: prescribed velocity, angular velocity and the two reactions.
    pub const PER_HELD_NODE: u64 = 72;
    /// libm calls (not in the flop count): 2 atan2 (log map), 2 sin + 2 cos (Jacobian).
    pub const TRANSCENDENTAL_PER_ELEMENT: u64 = 6;
    /// sin + cos of the exponential map.
    pub const TRANSCENDENTAL_PER_FREE_NODE: u64 = 2;
    /// atan2 of the log map.
    pub const TRANSCENDENTAL_PER_HELD_NODE: u64 = 1;

    /// Flops of one step of a world of `elements` elements, `nodes` nodes of which `held`
    /// are held by a fix.
    pub fn per_step(elements: usize, nodes: usize, held: usize) -> u64 {
        let (e, n, h) = (elements as u64, nodes as u64, held as u64);
        e * PER_ELEMENT + n * PER_NODE_BODY + (n - h) * PER_FREE_NODE + h * PER_HELD_NODE
    }

    /// libm calls of one step.
    pub fn transcendental_per_step(elements: usize, nodes: usize, held: usize) -> u64 {
        let (e, n, h) = (elements as u64, nodes as u64, held as u64);
        e * TRANSCENDENTAL_PER_ELEMENT
            + (n - h) * TRANSCENDENTAL_PER_FREE_NODE
            + h * TRANSCENDENTAL_PER_HELD_NODE
    }
}

/// The dissertation's measurement (ch. 6.1, eq. 6.1): g(x) = 0.5805·x + 2.0629 ms per
/// update for x beams on a 1999 SGI Octane (R10000), real time meaning every update within
/// 100 ms, with a time step √1000 ≈ 31.6× too large (SPEC P4).
pub mod dissertation {
    pub const MS_PER_BEAM: f64 = 0.5805;
    pub const MS_FIXED: f64 = 2.0629;
    pub const CRITERION_MS: f64 = 100.0;
    /// √1000: the factor by which the thesis's time step was too large.
    pub const TIME_STEP_ERROR: f64 = 31.622_776_601_683_793;

    /// Beams the thesis kept within its 100 ms criterion (≈ 168.7, "about 170").
    pub fn beams_in_real_time() -> f64 {
        (CRITERION_MS - MS_FIXED) / MS_PER_BEAM
    }
}

/// One measured case.
#[derive(Clone, Debug, Serialize)]
pub struct BenchRow {
    /// Case name, e.g. "1 hose × 100" or "5 hoses × 30, 2 threads".
    pub name: String,
    /// Threads the step used (results are the same for any number).
    pub threads: usize,
    pub hoses: usize,
    pub elements_per_hose: usize,
    /// Elements in the world.
    pub elements: usize,
    pub nodes: usize,
    /// The automatic stable time step used \[s\].
    pub time_step_s: f64,
    /// Axial (thesis) bound l_min/c and the eigenvalue bound 2/ω_max \[s\], before damping
    /// reduction and safety factor.
    pub axial_bound_s: f64,
    pub eigen_bound_s: f64,
    /// Steps timed per repeat, and the repeats.
    pub steps_per_repeat: u64,
    pub repeats: usize,
    /// Median wall time of one step \[ns\].
    pub ns_per_step: f64,
    /// Median wall time per element and step \[ns\] (= ns_per_step / elements).
    pub ns_per_element_step: f64,
    /// Fastest and slowest repeat, per element-step \[ns\] (noise indicator).
    pub ns_per_element_step_min: f64,
    pub ns_per_element_step_max: f64,
    /// Simulated seconds per wall second at the median cost.
    pub realtime_factor: f64,
    /// Elements that would run in real time at this per-element cost:
    /// 1 / (ns_per_element_step·1e-9 / Δt).
    pub elements_in_real_time: f64,
    /// Hand-counted flops per element-step of this world (see [`flops`]).
    pub flops_per_element_step: f64,
    /// Achieved arithmetic rate [GFLOP/s] (flops / ns).
    pub gflops: f64,
    /// `gflops` over the peak of the cores used (`threads` × [`Peak::gflops_per_core`]).
    pub peak_fraction: f64,
    /// Simulated time covered by warm-up and repeats \[s\].
    pub simulated_s: f64,
    /// Triangles of the rigid environment (0: no contact).
    pub contact_triangles: usize,
    /// Active contact points in the last step measured.
    pub contact_points: usize,
}

/// The cost of contact with a large rigid environment.
#[derive(Clone, Debug, Serialize)]
pub struct ContactCost {
    pub triangles: usize,
    /// ns per step of 5 hoses × 30 without and with the environment.
    pub ns_per_step_free: f64,
    pub ns_per_step_contact: f64,
    /// ns_per_step_contact / ns_per_step_free.
    pub ratio: f64,
    /// Simulated seconds per wall second with contact.
    pub realtime_factor: f64,
    /// Active contact points at the end of the measurement.
    pub contact_points: usize,
    /// ns per step with the floor moving ([`floor_sway`]), and that over the floor at
    /// rest (None when not measured).
    pub ns_per_step_moving: Option<f64>,
    pub moving_ratio: Option<f64>,
}

/// The moving floor of the contact rows: a gentle periodic sway (±2 mm vertically at
/// 1 Hz, ±0.5° roll at 1 Hz about the floor's middle), so the hoses stay on it.
pub fn floor_sway() -> PartMotion {
    let swing = |amplitude: f64| Oscillation {
        amplitude,
        frequency: 1.0,
        phase: 0.0,
    };
    PartMotion::Periodic(Periodic {
        centre: DVec3::new(0.35, 0.2, -0.03),
        translation: [Oscillation::default(), Oscillation::default(), swing(0.002)],
        rotation: [
            swing(0.5f64.to_radians()),
            Oscillation::default(),
            Oscillation::default(),
        ],
    })
}

/// Least-squares straight line y = slope·x + intercept with its coefficient of
/// determination.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct LineFit {
    pub slope: f64,
    pub intercept: f64,
    pub r_squared: f64,
}

/// Scaling of the cost per step with the number of elements (single hoses).
#[derive(Clone, Debug, Serialize)]
pub struct Scaling {
    /// Slope of ln(ns per step) against ln(elements); 1 means linear cost.
    pub loglog_slope: f64,
    pub loglog_intercept: f64,
    pub r_squared: f64,
    /// The element counts fitted.
    pub elements: Vec<usize>,
}

/// Arithmetic intensity summary (headline case).
#[derive(Clone, Debug, Serialize)]
pub struct FlopSummary {
    pub per_element: u64,
    pub per_node_body: u64,
    pub per_free_node: u64,
    pub per_held_node: u64,
    /// Flops per element-step of the headline (100-element) hose.
    pub per_element_step: f64,
    /// libm calls (sin, cos, atan2) per element-step, not included in the flops.
    pub transcendental_per_element_step: f64,
    /// Achieved GFLOP/s on the headline hose.
    pub gflops: f64,
    pub method: &'static str,
}

/// Comparison with the dissertation's real-time capacity.
#[derive(Clone, Debug, Serialize)]
pub struct DissertationComparison {
    /// g(x) = ms_per_beam·x + ms_fixed per update, criterion 100 ms.
    pub ms_per_beam: f64,
    pub ms_fixed: f64,
    pub criterion_ms: f64,
    /// Beams within the thesis criterion (≈ 168.7) — with its 31.6× too large step.
    pub thesis_beams_in_real_time: f64,
    pub thesis_time_step_error: f64,
    /// The thesis's capacity had it used the correct step and one step per update
    /// (an assumption: 168.7 / 31.6 ≈ 5.3 beams).
    pub thesis_beams_with_correct_step: f64,
    /// Beams Pliant keeps in real time with the correct step (headline per-element cost).
    pub pliant_beams_in_real_time: f64,
    /// Pliant's beams in real time / the thesis's 168.7.
    pub ratio: f64,
    /// Pliant's beams in real time / the thesis's step-corrected 5.3.
    pub ratio_step_corrected: f64,
    /// Cost of one beam update: 0.5805 ms / Pliant's ns per element-step.
    pub per_beam_update_speedup: f64,
}

/// A core's peak double-precision rate: FMA units × lanes × 2 flops × clock.
#[derive(Clone, Debug, Serialize)]
pub struct Peak {
    pub gflops_per_core: f64,
    /// Clock used \[GHz\] (the first `cpu MHz` of /proc/cpuinfo; 1 GHz if unknown).
    pub clock_ghz: f64,
    /// Flops per cycle: 2 FMA units × 4 lanes × 2 with AVX2 + FMA (AMD Zen 2/3, Intel
    /// Haswell and later), else 2 units × 2 SSE2 lanes.
    pub flops_per_cycle: f64,
    pub method: String,
}

impl Peak {
    pub fn detect() -> Peak {
        let clock_ghz = cpuinfo("cpu MHz")
            .and_then(|m| m.parse::<f64>().ok())
            .map_or(1.0, |mhz| mhz / 1000.0);
        let fma = pliant_core::rod::element_block::Kernel::detect()
            == pliant_core::rod::element_block::Kernel::Avx2Fma;
        let flops_per_cycle = if fma { 16.0 } else { 4.0 };
        Peak {
            gflops_per_core: flops_per_cycle * clock_ghz,
            clock_ghz,
            flops_per_cycle,
            method: format!(
                "{} flops/cycle ({}) × {clock_ghz:.2} GHz (/proc/cpuinfo)",
                flops_per_cycle,
                if fma {
                    "2 FMA units × 4 lanes × 2"
                } else {
                    "2 units × 2 lanes"
                }
            ),
        }
    }
}

/// What the machine is (for reading the numbers, not for comparing them).
#[derive(Clone, Debug, Serialize)]
pub struct MachineInfo {
    pub cpu: String,
    pub logical_cores: usize,
    pub os: &'static str,
    pub arch: &'static str,
    pub debug_build: bool,
}

/// The whole benchmark result.
#[derive(Clone, Debug, Serialize)]
pub struct BenchReport {
    /// The Newton solvers' rows.
    pub newton: Option<crate::bench_newton::NewtonBench>,
    /// The full engine bay per solver, with and without sleeping.
    pub engine_bay: Option<crate::bench_engine_bay::EngineBayBench>,
    /// Headline: median ns per element per step on the 100-element hose.
    pub ns_per_element_step: f64,
    /// Simulated seconds per wall second for 5 hoses × 30 elements.
    pub realtime_factor_5x30: f64,
    pub quick: bool,
    pub machine: MachineInfo,
    pub rows: Vec<BenchRow>,
    /// The core's peak arithmetic rate the rows are compared with.
    pub peak: Peak,
    /// The element kernel the step ran ("avx2+fma" or "portable").
    pub kernel: &'static str,
    pub scaling: Scaling,
    pub flops: FlopSummary,
    pub dissertation: DissertationComparison,
    pub material: &'static str,
    pub element_length_m: f64,
    pub contact: ContactCost,
}

/// How long to measure.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    pub warmup: Duration,
    pub repeat: Duration,
    pub repeats: usize,
}

impl Budget {
    pub fn new(quick: bool) -> Self {
        if quick {
            Budget {
                warmup: Duration::from_millis(5),
                repeat: Duration::from_millis(10),
                repeats: 3,
            }
        } else {
            Budget {
                warmup: Duration::from_millis(150),
                repeat: Duration::from_millis(150),
                repeats: 11,
            }
        }
    }
}

/// Library material 1 (SPEC M4, tables 3.2–3.4): oil return hose, chloroprene/NBR, read
/// from the built-in material library.
pub fn material_1() -> Result<(Material, Section)> {
    let library = pliant_scene::Library::builtin()?;
    let entry = library.get("hose1").context("library hose1 is missing")?;
    Ok((entry.material.clone(), entry.section))
}

/// Quads per side of the contact benchmark's floor: 224² quads = 100 352 triangles.
pub const FLOOR_QUADS: usize = 224;

/// A bumpy floor of `2·quads²` triangles 3 cm below the hoses (bumps ±1 cm), covering
/// them and the area they can fall onto — the hoses land on it within the warm-up.
pub fn bumpy_floor(quads: usize) -> RigidPartSpec {
    grid_floor(quads, |x, y| {
        -0.03 + 0.01 * (17.0 * x).sin() * (13.0 * y).cos()
    })
}

/// A floor of `2·quads²` triangles over the area of [`bumpy_floor`], at height
/// `height(x, y)`.
pub fn grid_floor(quads: usize, height: impl Fn(f64, f64) -> f64) -> RigidPartSpec {
    let (x0, x1, y0, y1) = (-0.3, 1.0, -0.8, 1.2);
    let mut vertices = Vec::with_capacity((quads + 1) * (quads + 1));
    for j in 0..=quads {
        for i in 0..=quads {
            let x = x0 + (x1 - x0) * i as f64 / quads as f64;
            let y = y0 + (y1 - y0) * j as f64 / quads as f64;
            vertices.push(DVec3::new(x, y, height(x, y)));
        }
    }
    let mut triangles = Vec::with_capacity(2 * quads * quads);
    let idx = |i: usize, j: usize| (j * (quads + 1) + i) as u32;
    for j in 0..quads {
        for i in 0..quads {
            triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    RigidPartSpec {
        name: "floor".into(),
        vertices,
        triangles,
        friction_static: 0.5,
        friction_sliding: 0.4,
        motion: None,
        parent: None,
        movable: false,
    }
}

/// `hoses` straight horizontal hoses of `elements` elements each along x, 0.1 m apart in y,
/// above a bumpy floor of `2·floor_quads²` triangles (no floor for 0).
pub fn world_with_floor(hoses: usize, elements: usize, floor_quads: usize) -> Result<WorldSpec> {
    let (material, section) = material_1()?;
    Ok(WorldSpec {
        hoses: (0..hoses)
            .map(|h| HoseSpec {
                name: format!("hose{h}"),
                material: material.clone(),
                nodes: (0..=elements)
                    .map(|i| DVec3::new(i as f64 * ELEMENT_LENGTH, 0.1 * h as f64, 0.0))
                    .collect(),
                sections: vec![section],
                normal_hint: Some(DVec3::Z),
            })
            .collect(),
        rigid_parts: if floor_quads > 0 {
            vec![bumpy_floor(floor_quads)]
        } else {
            Vec::new()
        },
        settings: SimSettings::default(),
    })
}

/// Amplitude \[rad\] and wavelength \[m\] of the tangent angle of the initial bend,
/// φ(s) = φ₀ sin(2π s / λ): curvature up to φ₀·2π/λ ≈ 7.9 1/m (bend radius ≈ 127 mm ≈ 8 d_a,
/// a routed hose), about 0.09 rad of bending per element end.
pub const BEND_AMPLITUDE: f64 = 0.6;
pub const BEND_WAVELENGTH: f64 = 0.48;

/// Node positions of a hose of `elements` elements laid as a horizontal wave of tangent
/// angle φ(s) = φ₀ sin(2π s/λ), starting at `origin` along +x; every element keeps its
/// rest length, so the initial deformation is pure bending.
pub fn bent_shape(origin: DVec3, elements: usize) -> Vec<DVec3> {
    let mut p = origin;
    let mut nodes = Vec::with_capacity(elements + 1);
    nodes.push(p);
    for i in 0..elements {
        let s = (i as f64 + 0.5) * ELEMENT_LENGTH;
        let phi = BEND_AMPLITUDE * (std::f64::consts::TAU * s / BEND_WAVELENGTH).sin();
        p += ELEMENT_LENGTH * DVec3::new(phi.cos(), phi.sin(), 0.0);
        nodes.push(p);
    }
    nodes
}

/// The model (straight, stress-free rest shape) and its initial state: every hose bent
/// into the wave of [`bent_shape`], at rest, its first node fixed where it lies. Released,
/// the hoses spring back, fall and swing under gravity — every element deforms, as in use.
///
/// (Starting from the stress-free straight shape instead would leave most of a long hose
/// in undeformed free fall during the measurement, where the element takes its cheap
/// small-angle branches and the cost per element looks lower than it is in use.)
///
/// The floor moves by `floor_motion` (None: it stands still).
pub fn setup_moving(
    hoses: usize,
    elements: usize,
    floor_quads: usize,
    floor_motion: Option<PartMotion>,
) -> Result<(Model, State)> {
    let mut world = world_with_floor(hoses, elements, floor_quads)?;
    for part in &mut world.rigid_parts {
        part.motion = floor_motion.clone();
    }
    let model = Model::build(&world).context("building the benchmark model")?;
    let mut state = State::at_rest(&model);
    for h in &model.hoses {
        let origin = model.rest_x[h.first_node];
        let shape = bent_shape(origin, h.element_count);
        let frames = node_frames(&shape, Some(DVec3::Z));
        for (k, n) in h.nodes().enumerate() {
            state.x[n] = shape[k];
            state.q[n] = frames[k];
        }
        let n = h.first_node;
        state.loads.add(LoadCase::Fix(Fix {
            node: n,
            position: state.x[n],
            orientation: state.q[n],
        }));
    }
    Ok((model, state))
}

/// `n` explicit steps of `state`.
pub(crate) fn run_steps(model: &Model, state: &mut State, n: u64) {
    for _ in 0..n {
        explicit::step(model, state);
    }
    std::hint::black_box(&state.x);
}

/// Measures one case: warm-up, then `budget.repeats` timed repeats of a fixed number of
/// steps sized to last about `budget.repeat`; median over the repeats.
pub fn measure(
    hoses: usize,
    elements_per_hose: usize,
    floor_quads: usize,
    threads: usize,
    budget: Budget,
) -> Result<BenchRow> {
    measure_moving(hoses, elements_per_hose, floor_quads, threads, budget, None)
}

/// [`measure`] with the floor moving by `floor_motion`.
pub fn measure_moving(
    hoses: usize,
    elements_per_hose: usize,
    floor_quads: usize,
    threads: usize,
    budget: Budget,
    floor_motion: Option<PartMotion>,
) -> Result<BenchRow> {
    let moving = floor_motion.is_some();
    let (mut model, mut state) = setup_moving(hoses, elements_per_hose, floor_quads, floor_motion)?;
    model.threads = threads;
    let elements = model.elements.len();
    let nodes = model.node_count();
    let dt = model.time_step;

    // Warm-up (caches, branch predictors, CPU clock) and a first estimate of the cost.
    let t0 = Instant::now();
    let mut warm_steps = 0u64;
    while warm_steps < 2 || t0.elapsed() < budget.warmup {
        run_steps(&model, &mut state, 1);
        warm_steps += 1;
    }
    let est = t0.elapsed().as_secs_f64() / warm_steps as f64;
    let steps_per_repeat = ((budget.repeat.as_secs_f64() / est).ceil() as u64).max(2);

    let mut per_step_ns = Vec::with_capacity(budget.repeats);
    for _ in 0..budget.repeats.max(1) {
        let t = Instant::now();
        run_steps(&model, &mut state, steps_per_repeat);
        per_step_ns.push(t.elapsed().as_nanos() as f64 / steps_per_repeat as f64);
        if let Err(d) = health::check(&model, &state) {
            bail!("benchmark case {hoses} × {elements_per_hose} diverged: {d}");
        }
    }
    let ns_per_step = median(&per_step_ns);
    let per_elem = |ns: f64| ns / elements as f64;
    let ns_per_element_step = per_elem(ns_per_step);
    let flops_per_element_step =
        flops::per_step(elements, nodes, model.hoses.len()) as f64 / elements as f64;
    let r = &model.time_step_report;
    let gflops = flops_per_element_step / ns_per_element_step;
    let name = match (hoses, floor_quads) {
        (1, _) => format!("1 hose × {elements_per_hose}"),
        (_, 0) => format!("{hoses} hoses × {elements_per_hose}"),
        _ => format!(
            "{hoses} hoses × {elements_per_hose} on {} triangles{}",
            2 * floor_quads * floor_quads,
            if moving { ", moving" } else { "" }
        ),
    };
    Ok(BenchRow {
        name: if threads > 1 {
            format!("{name}, {threads} threads")
        } else {
            name
        },
        threads,
        peak_fraction: gflops / (threads as f64 * Peak::detect().gflops_per_core),
        contact_triangles: 2 * floor_quads * floor_quads,
        contact_points: state.contact.points.len(),
        hoses,
        elements_per_hose,
        elements,
        nodes,
        time_step_s: dt,
        axial_bound_s: r.axial_bound,
        eigen_bound_s: r.eigen_bound,
        steps_per_repeat,
        repeats: per_step_ns.len(),
        ns_per_step,
        ns_per_element_step,
        ns_per_element_step_min: per_elem(
            per_step_ns.iter().copied().fold(f64::INFINITY, f64::min),
        ),
        ns_per_element_step_max: per_elem(per_step_ns.iter().copied().fold(0.0, f64::max)),
        realtime_factor: realtime_factor(dt, ns_per_step),
        elements_in_real_time: elements_in_real_time(dt, ns_per_element_step),
        flops_per_element_step,
        gflops,
        simulated_s: state.time,
    })
}

/// Simulated seconds per wall second for a step Δt costing `ns_per_step`.
pub fn realtime_factor(dt: f64, ns_per_step: f64) -> f64 {
    dt / (ns_per_step * 1e-9)
}

/// Elements that fit in real time at a cost of `ns_per_element_step` per element-step:
/// 1 / (ns_per_element_step·1e-9 / Δt).
pub fn elements_in_real_time(dt: f64, ns_per_element_step: f64) -> f64 {
    1.0 / (ns_per_element_step * 1e-9 / dt)
}

/// CPU time this thread has used \[s\]: what a piece of work costs on one core, whatever
/// else the machine runs (a wall time on a shared machine includes the waits).
pub fn thread_cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write into.
    let ok = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0;
    if ok {
        t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
    } else {
        f64::NAN
    }
}

/// Median (mean of the two middle values for an even count). Panics on an empty slice.
pub fn median(values: &[f64]) -> f64 {
    assert!(!values.is_empty(), "median of nothing");
    let mut v = values.to_vec();
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Least-squares line through (x, y); needs at least two distinct x.
pub fn fit_line(points: &[(f64, f64)]) -> LineFit {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let ss_res: f64 = points
        .iter()
        .map(|p| (p.1 - (slope * p.0 + intercept)).powi(2))
        .sum();
    let r_squared = if syy > 0.0 { 1.0 - ss_res / syy } else { 1.0 };
    LineFit {
        slope,
        intercept,
        r_squared,
    }
}

/// Fit of ln(cost) against ln(size): the exponent of a power law cost ∝ size^slope.
pub fn fit_loglog(sizes_and_costs: &[(f64, f64)]) -> LineFit {
    let logs: Vec<(f64, f64)> = sizes_and_costs
        .iter()
        .map(|&(x, y)| (x.ln(), y.ln()))
        .collect();
    fit_line(&logs)
}

/// The value of the first line of /proc/cpuinfo that starts with `key` (trimmed), if the
/// file and the line are there.
fn cpuinfo(key: &str) -> Option<String> {
    let text = std::fs::read_to_string("/proc/cpuinfo").ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    line.split(':').nth(1).map(|v| v.trim().to_string())
}

fn machine() -> MachineInfo {
    let cpu = cpuinfo("model name").unwrap_or_else(|| "unknown".into());
    MachineInfo {
        cpu,
        logical_cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
        os: std::env::consts::OS,
        arch: std::env::consts::ARCH,
        debug_build: cfg!(debug_assertions),
    }
}

/// Assembles the report from measured rows (single hoses first, then the multi-hose cases).
pub fn report(rows: Vec<BenchRow>, quick: bool) -> Result<BenchReport> {
    let single = |n: usize| {
        rows.iter()
            .find(|r| r.hoses == 1 && r.elements_per_hose == n && r.threads == 1)
            .with_context(|| format!("no row for one hose of {n} elements"))
    };
    let headline = single(HEADLINE_ELEMENTS)?.clone();
    let five = rows
        .iter()
        .find(|r| {
            r.hoses == 5 && r.elements_per_hose == 30 && r.contact_triangles == 0 && r.threads == 1
        })
        .context("no row for 5 hoses × 30")?;
    let five_contact = rows
        .iter()
        .find(|r| r.hoses == 5 && r.elements_per_hose == 30 && r.contact_triangles > 0)
        .context("no row for 5 hoses × 30 with contact")?;
    let moving_floor = rows.iter().find(|r| r.name.ends_with(", moving"));
    let contact = ContactCost {
        triangles: five_contact.contact_triangles,
        ns_per_step_free: five.ns_per_step,
        ns_per_step_contact: five_contact.ns_per_step,
        ratio: five_contact.ns_per_step / five.ns_per_step,
        realtime_factor: five_contact.realtime_factor,
        contact_points: five_contact.contact_points,
        ns_per_step_moving: moving_floor.map(|r| r.ns_per_step),
        moving_ratio: moving_floor.map(|r| r.ns_per_step / five_contact.ns_per_step),
    };
    let mut fit_sizes = Vec::new();
    let mut fit_points = Vec::new();
    for n in SINGLE_HOSE_ELEMENTS {
        let r = single(n)?;
        fit_sizes.push(n);
        fit_points.push((r.elements as f64, r.ns_per_step));
    }
    let fit = fit_loglog(&fit_points);
    let thesis = dissertation::beams_in_real_time();
    let thesis_corrected = thesis / dissertation::TIME_STEP_ERROR;
    let pliant = headline.elements_in_real_time;
    let (e, n, h) = (headline.elements, headline.nodes, headline.hoses);
    Ok(BenchReport {
        ns_per_element_step: headline.ns_per_element_step,
        realtime_factor_5x30: five.realtime_factor,
        quick,
        machine: machine(),
        peak: Peak::detect(),
        kernel: pliant_core::rod::element_block::Kernel::detect().name(),
        scaling: Scaling {
            loglog_slope: fit.slope,
            loglog_intercept: fit.intercept,
            r_squared: fit.r_squared,
            elements: fit_sizes,
        },
        flops: FlopSummary {
            per_element: flops::PER_ELEMENT,
            per_node_body: flops::PER_NODE_BODY,
            per_free_node: flops::PER_FREE_NODE,
            per_held_node: flops::PER_HELD_NODE,
            per_element_step: headline.flops_per_element_step,
            transcendental_per_element_step: flops::transcendental_per_step(e, n, h) as f64
                / e as f64,
            gflops: headline.gflops,
            method: "hand count of the source (glam 0.30 scalar f64): +,-,*,/,sqrt = 1 each; \
                     sin/cos/atan2 counted separately; see docs/performance.md",
        },
        dissertation: DissertationComparison {
            ms_per_beam: dissertation::MS_PER_BEAM,
            ms_fixed: dissertation::MS_FIXED,
            criterion_ms: dissertation::CRITERION_MS,
            thesis_beams_in_real_time: thesis,
            thesis_time_step_error: dissertation::TIME_STEP_ERROR,
            thesis_beams_with_correct_step: thesis_corrected,
            pliant_beams_in_real_time: pliant,
            ratio: pliant / thesis,
            ratio_step_corrected: pliant / thesis_corrected,
            per_beam_update_speedup: dissertation::MS_PER_BEAM * 1e6 / headline.ns_per_element_step,
        },
        material: "library material 1 (oil return hose): d_i 10 mm, d_a 16 mm, E_t 11.583 MPa, \
                   E_c 13.1363 MPa, rho 940 kg/m3, nu 0.49",
        element_length_m: ELEMENT_LENGTH,
        contact,
        rows,
        newton: None,
        engine_bay: None,
    })
}

/// Runs every case and prints the result (table, or one JSON object with `opts.json`).
pub fn run(opts: &BenchOptions) -> Result<()> {
    if opts.engine_bay_only {
        let b = crate::bench_engine_bay::run(opts.quick, !opts.json)?;
        return print_result(&b, opts.json, crate::bench_engine_bay::render);
    }
    if opts.harness_only {
        let b = crate::bench_harness::run(opts.quick)?;
        return print_result(&b, opts.json, crate::bench_harness::render);
    }
    match opts.only {
        None => run_all(opts),
        Some(BenchOnly::Contact) => run_contact_only(opts),
        Some(BenchOnly::Explicit) => run_explicit_only(opts),
        Some(BenchOnly::Newton) => {
            let newton = crate::bench_newton::run(opts.quick)?;
            print_result(&newton, opts.json, crate::bench_newton::render)
        }
        Some(BenchOnly::Worker) => {
            let cost = crate::bench_worker::measure(opts.quick)?;
            print_result(&cost, opts.json, crate::bench_worker::render)
        }
        Some(BenchOnly::Snapshot) => {
            let rows = crate::bench_snapshot::measure(opts.quick)?;
            print_result(&rows[..], opts.json, crate::bench_snapshot::render)
        }
    }
}

/// Prints one benchmark's `result`: as pretty JSON with `json`, else as `render` words it.
fn print_result<T: Serialize + ?Sized>(
    result: &T,
    json: bool,
    render: impl Fn(&T) -> String,
) -> Result<()> {
    if json {
        println!("{}", serde_json::to_string_pretty(result)?);
    } else {
        print!("{}", render(result));
    }
    Ok(())
}

/// `--only explicit`: the single-hose rows of [`SINGLE_HOSE_ELEMENTS`], one thread.
fn run_explicit_only(opts: &BenchOptions) -> Result<()> {
    let budget = Budget::new(opts.quick);
    let mut rows = Vec::with_capacity(SINGLE_HOSE_ELEMENTS.len());
    for n in SINGLE_HOSE_ELEMENTS {
        if !opts.json {
            eprintln!("measuring 1 × {n} …");
        }
        rows.push(measure(1, n, 0, 1, budget)?);
    }
    print_result(&rows[..], opts.json, |rows| {
        format!("{}\n", row_table(rows))
    })
}

/// `--only contact`: the time-boxed rows, the fixed windows
/// ([`crate::bench_contact_phases`]) and hose–hose contact
/// ([`crate::bench_hose_contact`]).
#[derive(Clone, Debug, Serialize)]
pub struct ContactOnly {
    #[serde(flatten)]
    pub rows: ContactCost,
    pub phases: Vec<crate::bench_contact_phases::ContactPhase>,
    pub hose_hose: crate::bench_hose_contact::HoseContactCost,
}

/// `--only contact`: the contact-free and the floor rows of 5 × 30, and their ratio; then
/// the same at fixed windows of steps; then hose–hose contact.
fn run_contact_only(opts: &BenchOptions) -> Result<()> {
    let budget = Budget::new(opts.quick);
    let free = measure(5, 30, 0, 1, budget)?;
    let floor = measure(5, 30, FLOOR_QUADS, 1, budget)?;
    let moving = measure_moving(5, 30, FLOOR_QUADS, 1, budget, Some(floor_sway()))?;
    let cost = ContactCost {
        triangles: floor.contact_triangles,
        ns_per_step_free: free.ns_per_step,
        ns_per_step_contact: floor.ns_per_step,
        ratio: floor.ns_per_step / free.ns_per_step,
        realtime_factor: floor.realtime_factor,
        contact_points: floor.contact_points,
        ns_per_step_moving: Some(moving.ns_per_step),
        moving_ratio: Some(moving.ns_per_step / floor.ns_per_step),
    };
    if !opts.json {
        println!(
            "5 hoses × 30: {:.0} ns/step free, {:.0} ns/step on {} triangles ({} contact points): ×{:.2}, real-time factor {:.2}",
            cost.ns_per_step_free,
            cost.ns_per_step_contact,
            cost.triangles,
            cost.contact_points,
            cost.ratio,
            cost.realtime_factor
        );
        println!(
            "the same floor moving (±2 mm at 1 Hz vertically, ±0.5° roll): {:.0} ns/step, ×{:.2} the floor at rest (goal ≤ 1.3)",
            moving.ns_per_step,
            moving.ns_per_step / floor.ns_per_step
        );
        println!("the same at fixed steps of its world:");
    }
    let phases = crate::bench_contact_phases::measure(opts.quick)?;
    if !opts.json {
        print!("{}", crate::bench_contact_phases::render(&phases));
    }
    let hose_hose = crate::bench_hose_contact::measure(opts.quick)?;
    if opts.json {
        let out = ContactOnly {
            rows: cost,
            phases,
            hose_hose,
        };
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        print!("{}", crate::bench_hose_contact::render(&hose_hose));
    }
    Ok(())
}

fn run_all(opts: &BenchOptions) -> Result<()> {
    let budget = Budget::new(opts.quick);
    let mut cases: Vec<(usize, usize, usize)> =
        SINGLE_HOSE_ELEMENTS.iter().map(|&n| (1, n, 1)).collect();
    // One hose of 30 is already a single-hose case; the multi-hose cases on one thread
    // and on every core
    let cores = pliant_core::parallel::available_cores();
    for &h in HOSE_COUNTS.iter().filter(|&&h| h != 1) {
        cases.push((h, 30, 1));
        if cores > 1 {
            cases.push((h, 30, cores));
        }
    }
    let mut rows = Vec::with_capacity(cases.len() + 1);
    for (hoses, elements, threads) in cases {
        if !opts.json {
            eprintln!("measuring {hoses} × {elements} on {threads} thread(s) …");
        }
        rows.push(measure(hoses, elements, 0, threads, budget)?);
    }
    if !opts.json {
        eprintln!(
            "measuring 5 × 30 on a {}-triangle floor …",
            2 * FLOOR_QUADS * FLOOR_QUADS
        );
    }
    rows.push(measure(5, 30, FLOOR_QUADS, 1, budget)?);
    if !opts.json {
        eprintln!("measuring 5 × 30 on the same floor, moving …");
    }
    rows.push(measure_moving(
        5,
        30,
        FLOOR_QUADS,
        1,
        budget,
        Some(floor_sway()),
    )?);
    if !opts.json {
        eprintln!("measuring the Newton solvers …");
    }
    let newton = crate::bench_newton::run(opts.quick)?;
    let engine_bay = crate::bench_engine_bay::run(opts.quick, !opts.json)?;
    let mut report = report(rows, opts.quick)?;
    report.newton = Some(newton);
    report.engine_bay = Some(engine_bay);
    if opts.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", render(&report));
        if let Some(n) = &report.newton {
            print!("{}", crate::bench_newton::render(n));
        }
        if let Some(b) = &report.engine_bay {
            print!("{}", crate::bench_engine_bay::render(b));
        }
    }
    Ok(())
}

/// The measured rows as a Markdown-compatible table.
fn row_table(rows: &[BenchRow]) -> Table {
    let mut t = Table::new();
    t.load_preset(presets::ASCII_MARKDOWN);
    t.set_header(vec![
        "case",
        "elements",
        "Δt [µs]",
        "ns/step",
        "ns/element-step",
        "min–max",
        "realtime factor",
        "elements in real time",
        "GFLOP/s",
        "of peak",
    ]);
    for row in rows {
        t.add_row(vec![
            row.name.clone(),
            row.elements.to_string(),
            format!("{:.2}", row.time_step_s * 1e6),
            format!("{:.0}", row.ns_per_step),
            format!("{:.1}", row.ns_per_element_step),
            format!(
                "{:.1}–{:.1}",
                row.ns_per_element_step_min, row.ns_per_element_step_max
            ),
            format!("{:.3}", row.realtime_factor),
            format!("{:.0}", row.elements_in_real_time),
            format!("{:.2}", row.gflops),
            format!("{:.1} %", 100.0 * row.peak_fraction),
        ]);
    }
    for i in 1..10 {
        if let Some(c) = t.column_mut(i) {
            c.set_cell_alignment(CellAlignment::Right);
        }
    }
    t
}

/// The human-readable form of a report: a Markdown-compatible table and a summary.
pub fn render(r: &BenchReport) -> String {
    let t = row_table(&r.rows);
    let d = &r.dissertation;
    let mut s = format!("{t}\n\n");
    s += &format!(
        "headline: {:.1} ns per element-step (1 hose × {HEADLINE_ELEMENTS}, median); \
         5 hoses × 30 run at {:.2}× real time\n",
        r.ns_per_element_step, r.realtime_factor_5x30
    );
    s += &format!(
        "scaling: cost per step ∝ elements^{:.3} (log-log least squares over {:?} elements, R² {:.4})\n",
        r.scaling.loglog_slope, r.scaling.elements, r.scaling.r_squared
    );
    s += &format!(
        "flops: {:.0} per element-step (hand count of the reference algorithm) → {:.2} GFLOP/s \
         = {:.1} % of one core's peak {:.1} GFLOP/s ({}); element kernel: {}\n",
        r.flops.per_element_step,
        r.flops.gflops,
        100.0 * r.flops.gflops / r.peak.gflops_per_core,
        r.peak.gflops_per_core,
        r.peak.method,
        r.kernel
    );
    s += &format!(
        "dissertation (SGI Octane, g(x) = {}·x + {} ms, {} ms criterion): {:.1} beams in real time \
         with a {:.1}× too large step ({:.1} beams with the correct step);\n\
         Pliant with the correct step: {:.0} beams in real time = {:.1}× the thesis's figure \
         ({:.0}× its step-corrected figure); one beam update is {:.0}× faster\n",
        d.ms_per_beam,
        d.ms_fixed,
        d.criterion_ms,
        d.thesis_beams_in_real_time,
        d.thesis_time_step_error,
        d.thesis_beams_with_correct_step,
        d.pliant_beams_in_real_time,
        d.ratio,
        d.ratio_step_corrected,
        d.per_beam_update_speedup
    );
    s += &format!(
        "machine: {} ({} logical cores, {}-{}){}{}\n",
        r.machine.cpu,
        r.machine.logical_cores,
        r.machine.os,
        r.machine.arch,
        if r.machine.debug_build {
            "; DEBUG BUILD — use --release"
        } else {
            ""
        },
        if r.quick {
            "; --quick (short runs, noisy)"
        } else {
            ""
        }
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loglog_fit_recovers_power_law_exponents() {
        for exponent in [1.0, 2.0, 0.5] {
            let pts: Vec<(f64, f64)> = [10.0, 30.0, 100.0, 1000.0, 10_000.0]
                .iter()
                .map(|&n: &f64| (n, 250.0 * n.powf(exponent)))
                .collect();
            let fit = fit_loglog(&pts);
            assert!((fit.slope - exponent).abs() < 1e-12, "{fit:?}");
            assert!((fit.intercept - 250f64.ln()).abs() < 1e-10, "{fit:?}");
            assert!((fit.r_squared - 1.0).abs() < 1e-12, "{fit:?}");
        }
    }

    #[test]
    fn loglog_fit_of_linear_cost_with_overhead_is_below_one() {
        // cost = 1000 + 300 n: a fixed overhead flattens the small sizes
        let pts: Vec<(f64, f64)> = [10.0, 100.0, 1000.0]
            .iter()
            .map(|&n| (n, 1000.0 + 300.0 * n))
            .collect();
        let fit = fit_loglog(&pts);
        assert!(fit.slope > 0.85 && fit.slope < 0.99, "{fit:?}");
        assert!(fit.r_squared < 1.0);
    }

    #[test]
    fn median_and_real_time_arithmetic() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        // Δt 100 µs, 1 µs per step → 100× real time; 200 ns per element-step → 500 elements
        assert!((realtime_factor(1e-4, 1000.0) - 100.0).abs() < 1e-9);
        assert!((elements_in_real_time(1e-4, 200.0) - 500.0).abs() < 1e-9);
        assert!((dissertation::beams_in_real_time() - 168.7).abs() < 0.05);
    }

    #[test]
    fn flop_count_per_step_adds_up() {
        // one hose of 2 elements: 3 nodes, 1 held
        assert_eq!(flops::per_step(2, 3, 1), 2 * 640 + 3 * 19 + 2 * 76 + 72);
        assert_eq!(flops::transcendental_per_step(2, 3, 1), 2 * 6 + 2 * 2 + 1);
    }

    #[test]
    fn benchmark_world_matches_the_brief() {
        let (model, state) = setup_moving(5, 30, 0, None).unwrap();
        assert_eq!(model.elements.len(), 150);
        assert_eq!(model.hoses.len(), 5);
        assert!(model.gravity.length() > 9.0, "gravity must be on");
        assert!(model
            .elements
            .iter()
            .all(|e| (e.rest_length - ELEMENT_LENGTH).abs() < 1e-12));
        assert_eq!(state.loads.iter().count(), 5);
        for h in &model.hoses {
            assert!(state.loads.holds(h.first_node));
            assert!(!state.loads.holds(h.first_node + h.node_count - 1));
        }
    }

    #[test]
    fn initial_bend_keeps_element_lengths_and_bends_every_element() {
        let nodes = bent_shape(DVec3::new(0.0, 0.3, 0.0), 40);
        assert_eq!(nodes.len(), 41);
        for w in nodes.windows(2) {
            assert!(((w[1] - w[0]).length() - ELEMENT_LENGTH).abs() < 1e-14);
        }
        // curvature from the turning angle between consecutive chords
        let kappa_max = BEND_AMPLITUDE * std::f64::consts::TAU / BEND_WAVELENGTH;
        let mut turned = 0;
        for w in nodes.windows(3) {
            let (a, b) = ((w[1] - w[0]).normalize(), (w[2] - w[1]).normalize());
            let angle = a.cross(b).length().asin();
            assert!(angle / ELEMENT_LENGTH <= kappa_max * 1.001);
            if angle > 2e-3 {
                turned += 1;
            }
        }
        assert!(turned >= 30, "only {turned} of 39 joints bent");
    }

    #[test]
    fn initial_state_is_bent_and_held_where_it_lies() {
        let (model, state) = setup_moving(2, 30, 0, None).unwrap();
        assert!(
            state.strain_energy(&model) > 1e-4,
            "the hoses must start deformed"
        );
        for (_, case) in state.loads.iter() {
            let (x, q) = case
                .prescribed_pose(0.0, &model.kinematics, &Default::default())
                .unwrap();
            assert_eq!(x, state.x[case.node()]);
            assert_eq!(q, state.q[case.node()]);
        }
        // released, the free ends move and the fixed ends stay
        let mut moved = state.clone();
        run_steps(&model, &mut moved, 200);
        for h in &model.hoses {
            let (first, last) = (h.first_node, h.first_node + h.node_count - 1);
            assert_eq!(moved.x[first], state.x[first]);
            assert!((moved.x[last] - state.x[last]).length() > 1e-4);
        }
        assert!(health::check(&model, &moved).is_ok());
    }

    #[test]
    fn a_short_measurement_is_consistent() {
        let budget = Budget {
            warmup: Duration::from_millis(1),
            repeat: Duration::from_millis(2),
            repeats: 3,
        };
        let row = measure(1, 10, 0, 1, budget).unwrap();
        assert_eq!(row.repeats, 3);
        assert!(row.ns_per_element_step > 0.0);
        assert!(row.ns_per_element_step_min <= row.ns_per_element_step);
        assert!(row.ns_per_element_step <= row.ns_per_element_step_max);
        let rt = row.time_step_s / (row.ns_per_step * 1e-9);
        assert!((row.realtime_factor - rt).abs() <= 1e-9 * rt);
        assert!((row.elements_in_real_time - row.realtime_factor * 10.0).abs() < 1e-6 * rt * 10.0);
        assert!(row.simulated_s > 0.0);
    }
}
