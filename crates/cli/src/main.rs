//! `pliant`: run a scene and write its time series, validate the physics against exact
//! solutions, benchmark the solver.
// The doc comments of the command-line types below are clap's --help text, not API
// docs: units in brackets ("[m]") and placeholders ("<unix time>") are written as users
// read them there.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

mod bench;
mod bench_contact_phases;
mod bench_engine_bay;
mod bench_harness;
mod bench_hose_contact;
mod bench_newton;
mod bench_snapshot;
mod bench_worker;
mod calibrate_cmd;
mod export_cmd;
mod import_cmd;
mod inspect_cmd;
mod limit_args;
mod peers;
mod progress;
mod replay_cmd;
mod run_cmd;
mod serve_cmd;
mod study_cmd;
mod validate_cmd;

use clap::{Parser, Subcommand};
use pliant_server::access::Access;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "pliant",
    version,
    about = "Real-time simulation of flexible hoses and cables for assembly studies"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Threads the explicit solver may use (default: 1 for one hose, every core for
    /// several; results are the same for any number). Sets PLIANT_THREADS.
    #[arg(long, global = true)]
    threads: Option<std::num::NonZeroUsize>,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene's timeline (the built-in demo when no scene is given) and write CSV
    /// time series, VTK frames and summary.json.
    Run {
        /// Scene file (TOML or JSON); omit for the built-in demo.
        scene: Option<PathBuf>,
        /// Output folder.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Ergonomic profile hand loads are judged with, e.g.
        /// "posture=standing, population=men, duty=continuous, moments_decide=true", or
        /// EN 1005-3 instead of the dissertation's tables: "standard=en1005-3,
        /// action=whole_body, frequency_per_min=1, action_time_s=2, duration_h=4".
        #[arg(long)]
        ergonomics: Option<String>,
        /// Solver instead of the scene's: explicit (the dissertation's central
        /// differences), implicit (HHT-α, 10 ms steps) or static (equilibrium per input).
        #[arg(long)]
        solver: Option<pliant_core::SolverKind>,
        #[command(flatten)]
        limits: limit_args::LimitArgs,
    },
    /// Replays a session's input log (a folder of `pliant serve`, or its inputs.jsonl)
    /// bit for bit and writes the same outputs as `run`.
    Replay {
        session: PathBuf,
        /// Output folder (default: SESSION/replay).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Also write the session as a scene file whose timeline re-enacts it.
        #[arg(long)]
        timeline: Option<PathBuf>,
        /// Replay a damaged log up to its first damaged line (exit 4) instead of
        /// refusing it (exit 2).
        #[arg(long)]
        up_to_damage: bool,
        #[arg(long)]
        quiet: bool,
        #[command(flatten)]
        steps: limit_args::StepLimit,
    },
    /// Run the validation suite against exact and independent reference solutions.
    Validate {
        /// Print one JSON array of checks instead of a table.
        #[arg(long)]
        json: bool,
        /// Run only this case.
        #[arg(long)]
        case: Option<String>,
        /// Also write the results table to this Markdown file (e.g. docs/validation.md).
        #[arg(long)]
        write_docs: Option<PathBuf>,
        /// Reach rest states with this solver instead of the explicit one (the `solvers`
        /// case compares all three anyway).
        #[arg(long)]
        solver: Option<pliant_core::SolverKind>,
    },
    /// Serve a scene interactively (the built-in demo when no scene is given): the
    /// simulation runs in real time; clients connect over WebSocket (docs/protocol.md).
    ///
    /// Every session is recorded as it runs (SPEC W2): a copy of the scene and every input
    /// (grab, move, release, reset, ergonomics), stamped with the step it took effect at,
    /// go into out/sessions/session-<unix time>/ under the current directory (the folder
    /// is printed at start). A report of the session so far — report.html, report.json,
    /// summary.json and the CSVs of `pliant run`, made by replaying the log — is written
    /// into report-N/ inside that folder by the viewer's Report button, or on Ctrl-C when
    /// the server stops. `pliant replay out/sessions/session-<unix time>` replays a session
    /// bit for bit at any time (`--timeline edited.toml` turns it into an editable scene).
    Serve {
        /// Scene file (TOML or JSON); omit for the built-in demo.
        scene: Option<PathBuf>,
        /// Port to listen on (0 picks a free one).
        #[arg(long, default_value_t = 8080)]
        port: u16,
        /// Address to listen on. Anything but loopback serves the network: a token is then
        /// required (generated unless --token gives one) and printed in the URL.
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
        /// Solver instead of the scene's: explicit, implicit or static.
        #[arg(long)]
        solver: Option<pliant_core::SolverKind>,
        /// Require this token (?token=… in the page URL) on every connection, also on
        /// loopback: ≥ 8 letters, digits, '-', '_', '.'.
        #[arg(long)]
        token: Option<String>,
        /// Also accept WebSocket connections from pages of this origin
        /// (scheme://host[:port]); repeatable. The server's own pages are always accepted.
        #[arg(long = "allow-origin")]
        allow_origin: Vec<String>,
        /// Most clients connected at once (the next is refused until one leaves).
        #[arg(long = "max-clients", default_value_t = pliant_server::server::MAX_CLIENTS)]
        max_clients: usize,
        /// Folder the scenes that clients send may read mesh files from [default: the
        /// served scene's folder]; nothing outside it is read.
        #[arg(long)]
        assets: Option<PathBuf>,
        /// Also serve the haptic force stream (SPEC H1, docs/protocol.md): hand pose in,
        /// force and torque out, over UDP on 127.0.0.1:PORT only (0 picks a free port).
        #[arg(long = "haptic-port")]
        haptic_port: Option<u16>,
        #[command(flatten)]
        limits: limit_args::LimitArgs,
    },
    /// Run a variant or tolerance study (docs/study.md) on a Dask cluster: Parquet
    /// results, tolerance envelopes and a study report (needs the Python package).
    Study {
        /// Study file (TOML, format "pliant-study").
        study: PathBuf,
        /// Output folder (default: out/study-<the study's name>); an interrupted study
        /// resumes there.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Address of an existing Dask scheduler (default: a local cluster).
        #[arg(long)]
        scheduler: Option<String>,
        /// Workers of the local cluster (default: one per core).
        #[arg(long)]
        workers: Option<usize>,
        /// Number of runs instead of the study file's (Monte Carlo, Latin hypercube).
        #[arg(long)]
        runs: Option<usize>,
        /// Runs per Dask task (default: up to 32, fewer for small studies so that every
        /// worker gets about eight tasks).
        #[arg(long)]
        batch: Option<usize>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
        /// Afterwards, run N of the runs again (drawn at random) with the reference solver
        /// and report the share of equal verdicts with its 95 % interval (agreement.json).
        #[arg(long, value_name = "N", default_value_t = 0)]
        check_agreement: usize,
        /// Solver of the --check-agreement runs (default explicit).
        #[arg(long, value_parser = ["explicit", "implicit", "static"])]
        reference_solver: Option<String>,
        #[command(flatten)]
        steps: limit_args::StepLimit,
    },
    /// Import CAD or harness data. A STEP assembly (AP203, AP214, AP242) is converted
    /// once with OpenCASCADE: into the cache a scene beside it reads (`[[parts]] step =
    /// …`), or into a GLB (--out). A wire harness in KBL 2.3–2.5 (`.kbl`, VDA 4964)
    /// becomes a scene: `--out DIR` receives scene.toml (segments, junctions, bundle
    /// sections, fixings, the installed state as timeline), harness.json and install.toml
    /// (the harness installed by two hands: connectors plugged, fixings pressed in;
    /// docs/harness.md). VEC 2.x files (`.vec`) are read where they carry 3-D
    /// geometry (nodes, segments, centre curves; not their wires, fixings, connectors);
    /// a topology-only VEC is refused.
    Import {
        /// The STEP or KBL file.
        step: PathBuf,
        /// STEP: write this GLB (one named node per solid, metres) instead of the cache
        /// entry. KBL: the folder to write the scene into [default: the file's name
        /// without extension, beside it].
        #[arg(long)]
        out: Option<PathBuf>,
        /// The scene's folder whose .pliant-cache/ receives the entry [default: the STEP
        /// file's folder].
        #[arg(long)]
        cache_dir: Option<PathBuf>,
        /// Chord tolerance: largest distance of a triangle from the surface, e.g. 0.5mm,
        /// 0.02in (a bare number is mm) [default: 0.5mm]. A scene's `chord_tolerance`
        /// must be the same for it to find the entry.
        #[arg(long)]
        tolerance: Option<String>,
        /// KBL: import only the branch beyond this node or segment (its KBL id or <Id>
        /// text), held fixed where it is cut off (the rest of the harness, installed).
        /// A node: every outlet of that branch point but the trunk (the part with the most
        /// segments); a segment: the segment and all beyond it, away from the larger rest.
        #[arg(long, value_name = "NODE_OR_SEGMENT")]
        branch: Option<String>,
        /// KBL: the bundle model's data to use instead of the built-in (e.g. the
        /// bundle.toml of `pliant calibrate --kind bundle`, with a fitted factor).
        #[arg(long = "bundle-data", value_name = "BUNDLE_TOML")]
        bundle_data: Option<PathBuf>,
        /// KBL: give each bundle the default friction between its wires for its
        /// protection (Dahl hysteresis; modelling choices of the bundle data, see
        /// docs/harness.md): each hose then gets a material of its own.
        #[arg(long = "bundle-friction")]
        bundle_friction: bool,
    },
    /// Print what a scene builds: hoses (length, elements, nodes), junctions (degree,
    /// position), fixings and parts, in metres.
    Inspect {
        /// The scene file.
        scene: PathBuf,
        /// JSON for scripts: {"hoses": [{"name", "length_m", "elements", "nodes"}],
        /// "junctions": [{"name", "degree", "position"}], "fixings", "parts"}.
        #[arg(long)]
        json: bool,
    },
    /// The settled route of an imported harness back to CAD: runs the scene `pliant
    /// import harness.kbl --out DIR` wrote (its installed state) and writes the segments'
    /// settled centre lines as KBL (a copy of the original with new centre curves,
    /// lengths and node positions) and STEP (one named curve per segment).
    Export {
        /// The folder `pliant import … --out DIR` wrote (scene.toml, harness.json).
        dir: PathBuf,
        /// Where to write harness.kbl and harness.step [default: DIR/export].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Solver for the settling run [default: the scene's].
        #[arg(long)]
        solver: Option<pliant_core::SolverKind>,
        /// The original KBL file [default: the one harness.json names].
        #[arg(long)]
        kbl: Option<PathBuf>,
        #[command(flatten)]
        steps: limit_args::StepLimit,
    },
    /// Fit a material's stiffness to measured test curves (docs/calibration.md): E_t and
    /// E_c from tension and compression, EI from three-point bending, a cantilever or
    /// ISO 10619-1, GJ from torsion; least squares over the linear range (found
    /// automatically) with 95 % confidence intervals. Writes material.toml (a scene's
    /// [materials.NAME]), library_entry.toml, calibration.json and calibration.html.
    /// A bundle (--kind bundle, or a "pliant-bundle-calibration" file): a protection's
    /// coupling factor between the slip and bonded bounds from a bending test of a bundle
    /// of wires; writes bundle.toml (for `pliant import --bundle-data`), calibration.json
    /// and calibration.html.
    Calibrate {
        /// Calibration file (TOML, format "pliant-calibration", e.g.
        /// examples/calibration/hose.toml, or "pliant-bundle-calibration"); or give
        /// --kind and --csv for one test.
        spec: Option<PathBuf>,
        /// One test's kind: tension, compression, three_point_bending, cantilever,
        /// torsion, iso10619; plastic_bending, plastic_torsion, plastic_cantilever,
        /// plastic_three_point_bending, relaxation (with --held-strain for E0),
        /// cyclic_bending, cyclic_torsion; or bundle (with --kbl and --segment).
        #[arg(long)]
        kind: Option<String>,
        /// Bundle: the bending test the curve comes from, three_point_bending (--length:
        /// span) or cantilever (--length: free length).
        #[arg(long = "bending-test", default_value = "three_point_bending")]
        bending_test: String,
        /// Bundle: the KBL file holding the tested bundle's wires.
        #[arg(long)]
        kbl: Option<PathBuf>,
        /// Bundle: the tested segment (KBL id or <Id> text).
        #[arg(long)]
        segment: Option<String>,
        /// Bundle: the protection whose factor is fitted (none, tape, fleece_tape,
        /// corrugated_tube, sleeve, other) [default: the segment's].
        #[arg(long)]
        protection: Option<String>,
        /// One test's curve (CSV with a header naming quantities and units, e.g.
        /// force_N,displacement_mm).
        #[arg(long)]
        csv: Option<PathBuf>,
        /// Gauge length (tension, compression), span (three-point bending), free length
        /// (cantilever), grip distance (torsion) or lever arm (iso10619) \[mm\]; the same
        /// for the tests past yield and cyclic torsion.
        #[arg(long)]
        length: Option<f64>,
        /// The specimen's outer diameter \[mm\].
        #[arg(long = "d-outer")]
        d_outer: Option<f64>,
        /// The specimen's inner diameter \[mm\] (0: a solid rod).
        #[arg(long = "d-inner", default_value_t = 0.0)]
        d_inner: f64,
        /// Name of the material.
        #[arg(long, default_value = "calibrated")]
        name: String,
        /// Density [kg/m³] (not measured; the material needs one).
        #[arg(long, default_value_t = 1100.0)]
        density: f64,
        /// Poisson's ratio when no torsion test determines it [default: 0.49].
        #[arg(long)]
        poisson: Option<f64>,
        /// Relaxation: the number of Prony terms to fit [default: chosen by BIC].
        #[arg(long)]
        terms: Option<usize>,
        /// Relaxation: the strain held during the test [-], which gives the
        /// instantaneous modulus E0 from the held force (over the section's area) or stress.
        #[arg(long = "held-strain")]
        held_strain: Option<f64>,
        /// Output folder.
        #[arg(long, default_value = "out/calibration")]
        out: PathBuf,
        /// Print calibration.json instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Measure cost per element per step and the real-time factor.
    Bench {
        /// Print one JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Shorter measurements (for smoke tests).
        #[arg(long)]
        quick: bool,
        /// Only the engine-bay section (20 hoses among ≥ 1 M part triangles, each
        /// solver with and without sleeping).
        #[arg(long = "engine-bay")]
        engine_bay: bool,
        /// Only the harness section: the main harness of data/harness/ imported, settled
        /// and moved by a hand in a quasi-static session, back and forth ±10 mm in 2 mm
        /// steps where nothing holds it (`update_cpu_ms`, `update_ms`: CPU and wall time
        /// of one update, median; `update_iterations`: the Newton iterations of the median
        /// update), beside one chain of as many elements, and the harness pulled hard
        /// (`pulled_update_cpu_ms`: a span between fixings dragged 2 mm per update).
        #[arg(long)]
        harness: bool,
        /// Measure one group of rows only: `contact` (5 × 30 without and with the floor),
        /// `newton` (the Newton solvers' rows), `snapshot` (a live snapshot's cost beside
        /// a small and a large part), `worker` or `explicit` (the single-hose rows of the
        /// explicit step, 10 … 10 000 elements).
        #[arg(long, value_enum)]
        only: Option<bench::BenchOnly>,
    },
    /// Pliant's side of the head-to-head benchmarks with PyElastica and MuJoCo
    /// (bench/peers/run.sh); prints one JSON object.
    Peer {
        #[command(subcommand)]
        case: PeerCase,
    },
}

#[derive(Subcommand)]
enum PeerCase {
    /// The shared problem data (material, geometry, damping rules) as JSON.
    Params,
    /// Cantilever (1 m, library hose 1) under a dead tip load λ = PL²/EI.
    Cantilever {
        #[arg(long, default_value_t = 16)]
        elements: usize,
        #[arg(long, value_enum, default_value_t = peers::Method::Relax)]
        solver: peers::Method,
        #[arg(long, default_value_t = 2.0)]
        lambda: f64,
        /// Convergence tolerance (relative residual for relax; speed for damped).
        #[arg(long, default_value_t = 1e-6)]
        tol: f64,
    },
    /// 500 mm hose dropped onto a horizontal cylinder: time to rest.
    Drop {
        #[arg(long, default_value_t = 20)]
        elements: usize,
    },
}

fn main() -> ExitCode {
    // `pliant inspect … | head`: a closed pipe ends the process quietly, as it does any
    // Unix tool, instead of panicking in `println!` (Rust ignores SIGPIPE by default)
    #[cfg(unix)]
    // SAFETY: restores the default action of one signal before any thread starts
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    if let Some(n) = cli.threads {
        // before any thread is started: read by every model built in this process
        std::env::set_var(pliant_core::model::THREADS_ENV, n.to_string());
    }
    let command = cli.command.unwrap_or(Command::Run {
        scene: None,
        out: PathBuf::from("out"),
        quiet: false,
        ergonomics: None,
        solver: None,
        limits: Default::default(),
    });
    let result = match command {
        Command::Run {
            scene,
            out,
            quiet,
            ergonomics,
            solver,
            limits,
        } => run_cmd::run(
            scene.as_deref(),
            &out,
            quiet,
            ergonomics.as_deref(),
            solver,
            &limits.load_options(),
        ),
        Command::Replay {
            session,
            out,
            timeline,
            up_to_damage,
            quiet,
            steps,
        } => replay_cmd::run(
            &session,
            out.as_deref(),
            timeline.as_deref(),
            up_to_damage,
            quiet,
            steps.get(),
        ),
        Command::Validate {
            json,
            case,
            write_docs,
            solver,
        } => validate_cmd::run(json, case.as_deref(), write_docs.as_deref(), solver),
        Command::Serve {
            scene,
            port,
            host,
            token,
            allow_origin,
            max_clients,
            solver,
            assets,
            haptic_port,
            limits,
        } => Access::for_host(&host, token, allow_origin)
            .map_err(anyhow::Error::msg)
            .and_then(|access| {
                serve_cmd::run(&serve_cmd::ServeArgs {
                    scene: scene.as_deref(),
                    host: &host,
                    port,
                    solver,
                    access,
                    max_clients,
                    assets: assets.as_deref(),
                    haptic_port,
                    limits: limits.load_options(),
                })
            }),
        Command::Study {
            study,
            out,
            scheduler,
            workers,
            runs,
            batch,
            quiet,
            check_agreement,
            reference_solver,
            steps,
        } => study_cmd::run(&study_cmd::StudyOptions {
            study: &study,
            out: out.as_deref(),
            scheduler: scheduler.as_deref(),
            workers,
            runs,
            batch,
            quiet,
            check_agreement,
            reference_solver: reference_solver.as_deref(),
            max_steps: steps.get(),
        }),
        Command::Inspect { scene, json } => inspect_cmd::run(&scene, json),
        Command::Export {
            dir,
            out,
            solver,
            kbl,
            steps,
        } => export_cmd::run(&export_cmd::ExportOptions {
            dir: &dir,
            out: out.as_deref(),
            solver,
            kbl: kbl.as_deref(),
            max_steps: steps.get(),
        }),
        Command::Import {
            step,
            out,
            cache_dir,
            tolerance,
            branch,
            bundle_data,
            bundle_friction,
        } => import_cmd::run(&import_cmd::ImportOptions {
            step: &step,
            out: out.as_deref(),
            cache_dir: cache_dir.as_deref(),
            tolerance: tolerance.as_deref(),
            branch: branch.as_deref(),
            bundle_data: bundle_data.as_deref(),
            bundle_friction,
        }),
        Command::Calibrate {
            spec,
            kind,
            bending_test,
            kbl,
            segment,
            protection,
            csv,
            length,
            d_outer,
            d_inner,
            name,
            density,
            poisson,
            terms,
            held_strain,
            out,
            json,
        } => calibrate_cmd::run(
            spec.as_deref(),
            &calibrate_cmd::OneTest {
                kind: kind.as_deref(),
                bundle: calibrate_cmd::BundleArgs {
                    bending_test: &bending_test,
                    kbl: kbl.as_deref(),
                    segment: segment.as_deref(),
                    protection: protection.as_deref(),
                },
                csv: csv.as_deref(),
                length_mm: length,
                d_inner_mm: d_inner,
                d_outer_mm: d_outer,
                name: &name,
                density_kg_m3: density,
                poisson,
                terms,
                held_strain,
            },
            &out,
            json,
        ),
        Command::Bench {
            json,
            quick,
            engine_bay,
            harness,
            only,
        } => bench::run(&bench::BenchOptions {
            json,
            quick,
            engine_bay_only: engine_bay,
            harness_only: harness,
            only,
        })
        .map(|_| ExitCode::SUCCESS),
        Command::Peer { case } => match case {
            PeerCase::Params => peers::params().and_then(|p| peers::print(&p)),
            PeerCase::Cantilever {
                elements,
                solver,
                lambda,
                tol,
            } => peers::solve_cantilever(elements, solver, lambda, tol)
                .and_then(|r| peers::print(&r)),
            PeerCase::Drop { elements } => peers::drop(elements).and_then(|r| peers::print(&r)),
        }
        .map(|_| ExitCode::SUCCESS),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
