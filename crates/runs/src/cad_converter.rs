//! Running the STEP converter: OpenCASCADE through its Python binding `OCP`
//! (PyPI `cadquery-ocp-novtk`, installed into the repository's `.venv` by
//! `scripts/install-cad.sh`). The converter's source
//! (`crates/python/python/pliant/cad/step_mesh.py`) is embedded in this crate and piped
//! to the interpreter, so the importer works without the `pliant` Python package; its
//! hash is part of every cache key, so a changed converter never reuses old meshes.
//!
//! Only scenes loaded from the user's own disk (and `pliant import`) run it: scenes sent
//! to `pliant serve` only read meshes already imported (see [`pliant_scene::step_cache`]).

use pliant_scene::step_cache::{hex, ConverterChoice, CurvePick, StepConverter};
use pliant_scene::LoadOptions;
use sha2::{Digest, Sha256};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

/// The converter's source, as embedded.
pub const CONVERTER_SOURCE: &str = include_str!("../../python/python/pliant/cad/step_mesh.py");

/// How to install the importer, for messages.
pub const INSTALL_HINT: &str = "install it with ./scripts/install-cad.sh (OpenCASCADE's Python binding, PyPI cadquery-ocp-novtk, into the repository's .venv), or name an interpreter that has it with PLIANT_PYTHON";

/// How many conversions this process started (tests check that a cached load runs none).
static CONVERSIONS: AtomicUsize = AtomicUsize::new(0);

/// Number of converter runs (STEP meshes and curves) started by this process.
pub fn conversions() -> usize {
    CONVERSIONS.load(Ordering::SeqCst)
}

/// SHA-256 (hex) of the embedded converter: the converter's identity in cache keys.
pub fn converter_id() -> &'static str {
    static ID: OnceLock<String> = OnceLock::new();
    ID.get_or_init(|| hex(&Sha256::digest(CONVERTER_SOURCE.as_bytes())))
}

/// Interpreters to try, in order: `PLIANT_PYTHON` (alone, if set), the repository's
/// `.venv` (where the project's scripts install the packages), a `.venv` in the working
/// directory, `python3`. Shared by every command that runs Python (import, study).
pub fn python_candidates() -> Vec<PathBuf> {
    if let Some(p) = std::env::var_os("PLIANT_PYTHON") {
        return vec![PathBuf::from(p)];
    }
    let mut list = Vec::new();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for root in [repo, PathBuf::from(".")] {
        let venv = root.join(".venv/bin/python");
        if venv.is_file() {
            list.push(venv);
        }
    }
    list.push(PathBuf::from("python3"));
    list
}

/// The first of [`python_candidates`] on which `python -c probe` succeeds; if none does,
/// the candidates tried, comma-separated, for the caller's error message.
pub fn first_python_where(probe: &str) -> Result<PathBuf, String> {
    let tried = python_candidates();
    for python in &tried {
        let ok = Command::new(python)
            .args(["-c", probe])
            .stdin(Stdio::null())
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false);
        if ok {
            return Ok(python.clone());
        }
    }
    let names: Vec<String> = tried.iter().map(|p| p.display().to_string()).collect();
    Err(names.join(", "))
}

/// The first interpreter that has `OCP` (checked without importing it: fast).
pub fn find_python() -> Result<PathBuf, String> {
    let probe = "import importlib.util, sys; sys.exit(importlib.util.find_spec('OCP') is None)";
    first_python_where(probe).map_err(|tried| {
        format!(
            "the STEP importer is not installed: none of these Python interpreters has OpenCASCADE's binding `OCP`: {tried}; {INSTALL_HINT}"
        )
    })
}

/// The environment variable that sets the converter's time limit \[s\].
pub const TIME_LIMIT_VAR: &str = "PLIANT_CONVERTER_TIME_LIMIT_S";

/// The converter's default time limit \[s\]: ten minutes, several times what the
/// largest STEP files of the test data take.
pub const DEFAULT_TIME_LIMIT_S: f64 = 600.0;

/// Largest STEP file converted or read \[bytes\].
pub const MAX_STEP_BYTES: u64 = 1 << 30;

/// The converter's time limit: [`TIME_LIMIT_VAR`] if set to a positive number of
/// seconds, else [`DEFAULT_TIME_LIMIT_S`].
pub fn converter_time_limit() -> std::time::Duration {
    let seconds = std::env::var(TIME_LIMIT_VAR)
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0 && *s < 1e9)
        .unwrap_or(DEFAULT_TIME_LIMIT_S);
    std::time::Duration::from_secs_f64(seconds)
}

/// Runs the embedded converter with `args` (at most [`converter_time_limit`]); its
/// error line on failure.
fn run(args: &[&std::ffi::OsStr]) -> Result<String, String> {
    let python = find_python()?;
    CONVERSIONS.fetch_add(1, Ordering::SeqCst);
    let mut child = Command::new(&python)
        .arg("-")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", python.display()))?;
    if let Some(mut stdin) = child.stdin.take() {
        // from a thread: a converter that never reads its source must not block us
        // before the time limit is even started (a failed write fails the converter)
        std::thread::spawn(move || {
            let _ = stdin.write_all(CONVERTER_SOURCE.as_bytes());
        });
    }
    let limit = converter_time_limit();
    let out = crate::time_limit::output_within(child, limit)
        .map_err(|e| format!("the STEP converter did not finish: {e}"))?
        .map_err(|t| {
            format!(
                "the STEP converter did not finish within {} s and was stopped (a file with absurd coordinates, or one too large to convert in time; allow more with {TIME_LIMIT_VAR}=SECONDS){}",
                t.limit.as_secs_f64(),
                t.stderr
                    .lines()
                    .rev()
                    .find(|l| !l.trim().is_empty())
                    .map(|l| format!("; its last words: {l}"))
                    .unwrap_or_default()
            )
        })?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        let line = stderr
            .lines()
            .rev()
            .find_map(|l| l.strip_prefix("error: "))
            .map(str::to_string)
            .unwrap_or_else(|| {
                let tail: Vec<&str> = stderr.lines().rev().take(5).collect();
                format!(
                    "the STEP converter failed ({}): {}",
                    out.status,
                    tail.into_iter().rev().collect::<Vec<_>>().join(" | ")
                )
            });
        return Err(line);
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Converts `step` to the GLB `out` (one named node per solid, metres) with a chord
/// tolerance \[m\]. The converter writes `out` atomically.
pub fn import_step(step: &Path, out: &Path, tolerance_m: f64) -> Result<(), String> {
    let tol = format!("{tolerance_m:e}");
    run(&[
        "import".as_ref(),
        step.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--tolerance".as_ref(),
        tol.as_ref(),
    ])
    .map(|_| ())
}

/// Samples one curve of `step` into points within `tolerance_m` \[m\] of it (metres),
/// written to the JSON file `out` (kept as the cache).
pub fn sample_curve(
    step: &Path,
    pick: &CurvePick,
    tolerance_m: f64,
    out: &Path,
) -> Result<(), String> {
    let tol = format!("{tolerance_m:e}");
    let (flag, value) = match pick {
        CurvePick::Name(n) => ("--name", n.clone()),
        CurvePick::Index(i) => ("--index", i.to_string()),
    };
    run(&[
        "curve".as_ref(),
        step.as_os_str(),
        flag.as_ref(),
        value.as_ref(),
        "--tolerance".as_ref(),
        tol.as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ])
    .map(|_| ())
}

/// The embedded converter run by a Python interpreter that has `OCP` ([`find_python`]).
pub struct PythonStepConverter;

/// The converter every program of Pliant loads scenes with.
pub static PYTHON_STEP_CONVERTER: PythonStepConverter = PythonStepConverter;

impl StepConverter for PythonStepConverter {
    fn id(&self) -> &str {
        converter_id()
    }

    fn convert_mesh(&self, step: &Path, out: &Path, tolerance_m: f64) -> Result<(), String> {
        import_step(step, out, tolerance_m)
    }

    fn sample_curve(
        &self,
        step: &Path,
        pick: &CurvePick,
        tolerance_m: f64,
        out: &Path,
    ) -> Result<(), String> {
        sample_curve(step, pick, tolerance_m, out)
    }
}

/// `options` with STEP files converted by [`PYTHON_STEP_CONVERTER`].
pub fn converting(options: LoadOptions) -> LoadOptions {
    LoadOptions {
        converter: ConverterChoice(Some(&PYTHON_STEP_CONVERTER)),
        ..options
    }
}

/// The default load options ([`LoadOptions::default`]) with STEP files converted by
/// [`PYTHON_STEP_CONVERTER`]: how every program loads a scene from the user's disk.
pub fn load_options() -> LoadOptions {
    converting(LoadOptions::default())
}
