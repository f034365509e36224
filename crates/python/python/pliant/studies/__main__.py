"""``python -m pliant.studies STUDY.toml [--out DIR] [--scheduler ADDR] [--workers N]
[--runs N] [--check-agreement N] [--quiet]``: what ``pliant study`` runs. Exit codes: 0 done, 2 bad input."""

import argparse
import signal
import sys


def _interrupt(signum, frame):
    """SIGTERM (a batch system, kill) stops the study like Ctrl-C: finished rows are written."""
    raise KeyboardInterrupt


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="pliant study", description="Run a variant or tolerance study on Dask.")
    ap.add_argument("study", help="study file (TOML, format pliant-study)")
    ap.add_argument("--out", help="output folder (default out/study-<name>); an interrupted study resumes there")
    ap.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a local cluster)")
    ap.add_argument("--workers", type=int, help="workers of the local cluster (default: one per core)")
    ap.add_argument("--runs", type=int, help="number of runs instead of the study file's")
    ap.add_argument("--batch", type=int, help="runs per Dask task (default: up to 16, so each worker gets about eight tasks)")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    ap.add_argument("--max-steps", type=int, default=None,
                    help="refuse a run planned beyond this many steps (status invalid; default 1e9)")
    ap.add_argument("--check-agreement", type=int, default=0, metavar="N",
                    help="afterwards run N of the runs again with the explicit solver and report the share of equal verdicts")
    ap.add_argument("--reference-solver", default="explicit", choices=("explicit", "implicit", "static"),
                    help="the solver of --check-agreement's runs (default explicit)")
    ap.add_argument("--flush-rows", type=int, default=50, help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    signal.signal(signal.SIGTERM, _interrupt)
    try:
        from . import StudyError, study
    except ImportError as e:
        print(f"error: studies need their Python packages ({e}); install them with "
              "pip install 'dask[distributed]' pyarrow pandas scipy scikit-image", file=sys.stderr)
        return 2
    try:
        result = study(a.study, a.out, scheduler=a.scheduler, workers=a.workers, runs=a.runs,
                       progress=False if a.quiet else "text", flush_rows=a.flush_rows,
                       batch=a.batch, max_steps=a.max_steps, check_agreement=a.check_agreement,
                       reference_solver=a.reference_solver)
    except StudyError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\ninterrupted: finished runs are saved; run the same command again to resume", file=sys.stderr)
        return 130
    f = result.frame
    n = len(f)
    k = int((f["feasible"] == True).sum()) if n else 0  # noqa: E712
    print(f"{k} of {n} runs feasible; results {result.results}; report {result.report}")
    if a.check_agreement and result.agreement:
        from .agreement import sentence

        print(sentence(result.agreement))
    return 0


if __name__ == "__main__":
    sys.exit(main())
