//! `pliant study`: variant and tolerance studies (SPEC T1, T2). The study machinery is
//! Python (the `pliant.studies` package: sampling, Dask, Parquet, envelopes, report); this
//! command finds a Python interpreter that has it and hands the arguments over.
//!
//! The driver does not outlive this command (`kill -9` of `pliant study` left
//! the driver and its Dask workers running): on Linux it is started with
//! `PR_SET_PDEATHSIG` = SIGTERM, so the kernel signals it when this process dies however
//! it dies, and the driver takes SIGTERM as Ctrl-C — it writes the finished rows and
//! closes its local cluster, whose workers stop with it.

use anyhow::{anyhow, Context, Result};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

/// The options of `pliant study`, passed on to `python -m pliant.studies`.
pub struct StudyOptions<'a> {
    pub study: &'a Path,
    pub out: Option<&'a Path>,
    pub scheduler: Option<&'a str>,
    pub workers: Option<usize>,
    pub runs: Option<usize>,
    pub batch: Option<usize>,
    pub quiet: bool,
    /// Afterwards, this many runs again with `reference_solver` to measure how often the
    /// verdicts agree (0: none).
    pub check_agreement: usize,
    /// The solver of the agreement check's runs.
    pub reference_solver: Option<&'a str>,
    /// Each run is refused (status `invalid`) when planned beyond this many steps.
    pub max_steps: u64,
}

/// What a study imports: the package and its study extras.
const PROBE: &str = "import pliant.studies, distributed, pyarrow, pandas, scipy, skimage";

/// The first interpreter that can import `pliant.studies` and the study extras.
fn find_python() -> Result<PathBuf> {
    pliant_runs::cad_converter::first_python_where(PROBE).map_err(|tried| {
        anyhow!(
            "pliant study needs the Python package `pliant` with its study extras, and none of \
             these interpreters has it: {tried}. Install it with ./scripts/install-python.sh (into .venv), \
             or `pip install './crates/python[study]'`, \
             or name an interpreter with PLIANT_PYTHON"
        )
    })
}

/// Makes the kernel send SIGTERM to the command's process when this process ends, even
/// by SIGKILL (Linux `prctl(PR_SET_PDEATHSIG)`, kept across `exec`); elsewhere nothing.
fn stop_with_this_process(cmd: &mut Command) {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        let parent = std::process::id();
        // SAFETY: between fork and exec the closure calls only async-signal-safe functions
        // (prctl, getppid, raise) and allocates nothing.
        unsafe {
            cmd.pre_exec(move || {
                if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                // this process may have died before the prctl: then stop at once
                if libc::getppid() as u32 != parent {
                    libc::raise(libc::SIGTERM);
                }
                Ok(())
            });
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = cmd;
}

/// Runs the study; the exit code is the Python module's (0 done, 2 bad input).
pub fn run(o: &StudyOptions) -> Result<ExitCode> {
    let python = find_python()?;
    let mut cmd = Command::new(&python);
    cmd.args(["-m", "pliant.studies"]).arg(o.study);
    if let Some(out) = o.out {
        cmd.arg("--out").arg(out);
    }
    if let Some(s) = o.scheduler {
        cmd.args(["--scheduler", s]);
    }
    if let Some(w) = o.workers {
        cmd.args(["--workers", &w.to_string()]);
    }
    if let Some(r) = o.runs {
        cmd.args(["--runs", &r.to_string()]);
    }
    if let Some(b) = o.batch {
        cmd.args(["--batch", &b.to_string()]);
    }
    if o.quiet {
        cmd.arg("--quiet");
    }
    if o.check_agreement > 0 {
        cmd.args(["--check-agreement", &o.check_agreement.to_string()]);
    }
    if let Some(s) = o.reference_solver {
        cmd.args(["--reference-solver", s]);
    }
    cmd.args(["--max-steps", &o.max_steps.to_string()]);
    stop_with_this_process(&mut cmd);
    let status = cmd
        .status()
        .with_context(|| format!("starting {}", python.display()))?;
    Ok(ExitCode::from(
        status.code().unwrap_or(1).clamp(0, 255) as u8
    ))
}
