"""Variant and tolerance studies (SPEC T1, T2): a base scene plus parameters to vary,
sampled as a grid, a Latin hypercube or Monte Carlo, run on a Dask cluster; results as
Parquet (one row per run), tolerance envelopes (STL, GLB) and an HTML report.
``pliant.study(...)`` and ``pliant study STUDY.toml`` are the entry points; the study
format is documented in docs/study.md.

Needs the study extras: ``pip install 'dask[distributed]' pyarrow pandas scipy scikit-image``.
"""

from .spec import Study, StudyError, load_study, parse_study
from .sampling import samples
from .variant import apply as variant_scene
from .results import StudyResult, read_rows, run_envelope


def study(study, out=None, *, scheduler=None, workers=None, runs=None, processes=True,
          progress=True, client=None, flush_rows=50, batch=None, max_steps=None, check_agreement=0,
          reference_solver="explicit"):
    """Runs (or resumes) a study and returns a :class:`StudyResult` (``.frame`` is a
    pandas DataFrame, one row per run; ``.report`` the HTML report's path).

    ``study``: a study TOML file or a dict of its content. ``out``: output folder
    (default ``out/study-<name>``); an interrupted study resumes there. ``scheduler``:
    address of an existing Dask scheduler; otherwise a local cluster of ``workers``
    single-threaded processes (default: one per core; ``processes=False``: threads).
    ``client``: an existing ``distributed.Client`` to use instead. ``progress``: a
    notebook-friendly bar (tqdm.auto) if available, ``"text"`` for a plain one, False
    for none. ``flush_rows``: rows per Parquet part (also written every 10 s). ``batch``:
    runs per Dask task (default: up to 16, fewer for small studies so every worker gets
    about eight tasks). ``max_steps``: a run planned beyond this many steps (its
    timeline's duration over the time step) is refused before it starts, with status
    ``invalid`` and the estimate in its message (default: ``pliant.DEFAULT_MAX_STEPS``).
    ``check_agreement`` N: then N of the runs, drawn at random, are run again with
    ``reference_solver`` (explicit) and the share of equal verdicts is written with its
    95 % interval (``agreement.json``, the report, ``StudyResult.agreement``). The scene's
    files reach the workers as bytes (no shared file system needed)."""
    from .cluster import run_study

    return run_study(study, out, scheduler=scheduler, workers=workers, runs=runs,
                     processes=processes, progress=progress, client=client, flush_rows=flush_rows,
                     batch=batch, max_steps=max_steps, check_agreement=check_agreement,
                     reference_solver=reference_solver)


__all__ = ["Study", "StudyError", "StudyResult", "load_study", "parse_study", "read_rows", "run_envelope",
           "samples", "study", "variant_scene"]
