"""Running a study on Dask: a local cluster (one single-threaded worker process per core)
or any cluster by its scheduler address. Runs are submitted in a bounded window and
collected as they finish (``distributed.as_completed``); rows stream to Parquet parts
(``OUT/parts/part-NNNNN.parquet``, each written whole and renamed into place) and the
union of the runs' centre-line samples to ``OUT/envelope/samples-<hose>.npy``, dilated to
the envelope's voxels (``voxels-<hose>.npy``) once at the end. A study started again in
the same folder skips the runs whose rows are there (resume); the union is idempotent, so
a run done twice changes nothing.

Layout of OUT: ``study.json`` (what the study is), ``runs/<id>.json`` (each run's scene:
its replay input), ``parts/`` (rows as they came), ``results.parquet`` (all rows, by
index), ``envelope/`` (meshes, clearances), ``report.html``.
"""

from __future__ import annotations

import glob
import json
import os
import sys
import time
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional

import numpy as np

from . import agreement, envelope, geometry, motion, sampling, scene_files, variant
from .runner import Task, column_name, plain_physics, run_batch
from .spec import SOLVERS, Study, StudyError, load_study

FLUSH_ROWS = 50  # a part is written after this many rows or seconds
FLUSH_SECONDS = 10.0
MAX_BATCH = 32  # runs per Dask task at most


def batch_size(pending: int, workers: int, batch: Optional[int] = None) -> int:
    """Runs per Dask task: ``batch`` if given, else as many as leave every worker about
    eight tasks (so the last ones finish together and the bar moves), at most
    :data:`MAX_BATCH`. One task then costs the scheduler, the (de)serialisation and the
    parts' geometry once for several runs."""
    if batch is not None:
        if batch < 1:
            raise StudyError(f"batch = {batch}: must be at least 1 run per task")
        return batch
    return max(1, min(MAX_BATCH, pending // (8 * max(workers, 1))))


def schema(study: Study):
    """The Parquet schema of the result rows (fixed columns, then the study's)."""
    import pyarrow as pa

    strings = pa.list_(pa.string())
    fields = [
        ("run_id", pa.string()), ("index", pa.int64()), ("status", pa.string()),
        ("message", pa.string()),
    ]
    fields += [(p.column, pa.string() if p.categorical else pa.float64()) for p in study.parameters]
    fields += [
        ("feasible", pa.bool_()), ("uncertain", pa.bool_()), ("completed", pa.bool_()),
        ("reasons", strings), ("warnings", strings), ("violated_checks", strings),
        ("peak_hand_force_n", pa.float64()), ("peak_hand_torque_nm", pa.float64()),
        ("worst_hand_ratio", pa.float64()), ("worst_hand_kind", pa.string()),
        ("worst_hand_limit_n", pa.float64()),
    ]
    for kind, table in (("stub", "stubs"), ("clip", "clips")):
        for item in study.scene.get(table, []):
            base = column_name(kind, item["name"])
            fields += [(base + "_force_n", pa.float64()), (base + "_assembled", pa.bool_())]
    fields += [("min_bend_radius_ratio", pa.float64()), ("max_twist_rad_per_m", pa.float64())]
    fields += [(column_name("clearance", p["name"], "m"), pa.float64()) for p in study.scene.get("parts", [])]
    fields += [(name, pa.float64() if kind == "float" else pa.string()) for name, kind in motion.fields(study.scene)]
    fields += [
        ("steps", pa.int64()), ("simulated_time_s", pa.float64()), ("solver", pa.string()), ("rerun", pa.bool_()),
        ("solver_warnings", pa.int64()), ("unconverged_steps", pa.int64()),
        ("instabilities", pa.int64()), ("wall_time_s", pa.float64()), ("cpu_time_s", pa.float64()),
    ]
    return pa.schema(fields, metadata={"pliant": json.dumps({"units": "SI", "study": study.name})})


class TextProgress:
    """Runs done, rate and ETA on stderr: one updating line on a terminal, else a line
    every 10 s."""

    def __init__(self, total: int, done: int, stream=None):
        self.total, self.start_done = total, done
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.t0 = time.monotonic()
        self.last = 0.0

    def update(self, done: int, failed: int, final: bool = False) -> None:
        now = time.monotonic()
        if not final and not self.tty and now - self.last < 10:
            return
        if not final and self.tty and now - self.last < 0.2:
            return
        self.last = now
        new = done - self.start_done
        rate = new / max(now - self.t0, 1e-9) * 60
        left = self.total - done
        eta = left / (rate / 60) if new and rate > 0 else float("nan")
        width = 30
        bar = "#" * int(width * done / max(self.total, 1))
        eta_s = "--:--" if eta != eta else f"{int(eta // 60):d}:{int(eta % 60):02d}"
        text = (f"[{bar:<{width}}] {done}/{self.total} runs, {rate:.1f} runs/min, ETA {eta_s}"
                + (f", {failed} not ok" if failed else ""))
        self.stream.write(("\r" + text) if self.tty else text + "\n")
        if final and self.tty:
            self.stream.write("\n")
        self.stream.flush()

    def close(self) -> None:
        pass


class TqdmProgress:
    """A notebook-friendly bar (tqdm.auto picks the Jupyter widget in a notebook)."""

    def __init__(self, total: int, done: int):
        from tqdm.auto import tqdm

        self.bar = tqdm(total=total, initial=done, unit="run")

    def update(self, done: int, failed: int, final: bool = False) -> None:
        self.bar.n = done
        self.bar.set_postfix(not_ok=failed, refresh=False)
        self.bar.refresh()

    def close(self) -> None:
        self.bar.close()


def make_progress(kind: Any, total: int, done: int):
    if kind is False or kind is None:
        return None
    if kind == "text":
        return TextProgress(total, done)
    try:
        return TqdmProgress(total, done)
    except ImportError:
        return TextProgress(total, done)


def _atomic_write(path: str, write: Callable[[str], None]) -> None:
    tmp = path + ".tmp"
    write(tmp)
    os.replace(tmp, path)


@dataclass
class Layout:
    out: str

    @property
    def runs(self) -> str:
        return os.path.join(self.out, "runs")

    @property
    def parts(self) -> str:
        return os.path.join(self.out, "parts")

    @property
    def envelope(self) -> str:
        return os.path.join(self.out, "envelope")

    def voxels(self, hose: str) -> str:
        return os.path.join(self.envelope, f"voxels-{column_name(hose)}.npy")

    def samples(self, hose: str) -> str:
        """The union of the runs' centre-line samples on disk: what a resumed study
        starts from (the voxels are dilated from it at the end)."""
        return os.path.join(self.envelope, f"samples-{column_name(hose)}.npy")


def done_run_ids(layout: Layout) -> set:
    """Run ids whose rows are already on disk."""
    import pyarrow.parquet as pq

    ids: set = set()
    for path in sorted(glob.glob(os.path.join(layout.parts, "part-*.parquet"))):
        ids.update(pq.read_table(path, columns=["run_id"]).column("run_id").to_pylist())
    return ids


def _prepare(study: Study, out: str) -> Layout:
    layout = Layout(out)
    for d in (layout.out, layout.runs, layout.parts, layout.envelope):
        os.makedirs(d, exist_ok=True)
    meta_path = os.path.join(out, "study.json")
    meta = {
        "format": "pliant-study-output", "name": study.name, "study_file": os.path.abspath(study.origin)
        if study.origin != "<dict>" else None, "scene": study.scene_path, "fingerprint": study.fingerprint(),
        "method": study.method, "seed": study.seed,
        "parameters": [{"name": p.name, "column": p.column, "vary": p.vary, "apply": p.apply, "unit": p.unit,
                        "distribution": p.distribution.kind, "target": p.target} for p in study.parameters],
    }
    if os.path.exists(meta_path):
        with open(meta_path) as f:
            old = json.load(f)
        if old.get("fingerprint") != meta["fingerprint"]:
            raise StudyError(
                f"{out}: holds another study (or the same one with other settings or run count); "
                "choose another --out, or delete the folder to start again")
    else:
        _atomic_write(meta_path, lambda p: open(p, "w").write(json.dumps(meta, indent=2, default=str)))
    return layout


def connect(scheduler: Optional[str], workers: Optional[int], processes: bool = True):
    """A Dask client: to the scheduler at this address, or to a new local cluster."""
    try:
        from distributed import Client
    except ImportError:
        raise StudyError("studies need Dask: pip install 'dask[distributed]' pyarrow pandas scipy scikit-image") from None
    if scheduler:
        return Client(scheduler), None
    cluster = local_cluster(workers or os.cpu_count() or 1, processes)
    return Client(cluster), cluster


def dashboard_link(client) -> Optional[str]:
    """The address of the dashboard of the scheduler ``client`` is connected to, or
    ``None`` when that scheduler serves none. For a cluster this process started, its
    own link; for a scheduler started elsewhere (``--scheduler``), the link that
    scheduler reports (its host, its dashboard port) — never that of a local cluster."""
    try:
        # without a dashboard service distributed still fills in its default template
        # (port 8787), so ask the scheduler what it serves
        if "dashboard" not in client.scheduler_info().get("services", {}):
            return None
        return client.dashboard_link or None
    except (KeyError, AttributeError, TypeError):
        return None


def local_cluster(workers: int, processes: bool = True):
    """A local Dask cluster of single-threaded workers for a study. Its worker processes
    start without Dask's default ``MALLOC_TRIM_THRESHOLD_`` (65536): setting it switches
    off glibc's adaptive mmap threshold (mallopt(3)), so every allocation above 128 KiB —
    a run's recorded frames, the row's numpy arrays — is mapped and unmapped again. On
    the demo study that cost 13 500 page faults and 0.06 CPU-s per run (1 800 faults
    without; docs/performance.md, "Studies"). Nor do they run Dask's statistical
    profiler (``distributed.worker.profile.enabled``), which samples every thread's stack
    a hundred times a second for the dashboard's Profile page: ≈ 4 % of a worker's CPU
    on the demo study. Workers of a cluster started elsewhere (``--scheduler``) keep
    their own environment and settings: start them the same way (docs/study.md)."""
    import dask
    from distributed import LocalCluster

    environ = {k: v for k, v in (dask.config.get("distributed.nanny.pre-spawn-environ", None) or {}).items()
               if k != "MALLOC_TRIM_THRESHOLD_"}
    with dask.config.set({"distributed.nanny.pre-spawn-environ": environ,
                          "distributed.worker.profile.enabled": False}):
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=processes,
                            dashboard_address=":0", silence_logs=40)


def stream_batches(client, runs: List[int], make_task: Callable[[int], Task], size: int, window: int,
                   name: str, on_batch: Callable[[List[int], Dict[str, Any]], None]) -> None:
    """Runs ``runs`` (study run indices) on the cluster, ``size`` runs per Dask task and
    ``window`` tasks in flight, and hands each finished batch's result (as
    :func:`run_batch` returns it) to ``on_batch`` as it comes (``distributed.as_completed``).
    A batch that fails outside the engine — its worker died more often than the
    scheduler retries, or the task failed outside ``run_variant`` — is submitted again run
    by run, so one bad run costs no other run its row; a single run that fails so is
    handed on as status ``error`` with the reason. A worker that dies mid-batch loses
    nothing: the scheduler runs its tasks again on the others (and on the worker its
    nanny starts instead)."""
    from distributed import as_completed

    queue = iter(range(0, len(runs), size))
    batch_of: Dict[str, List[int]] = {}

    def submit(chosen=None):
        if chosen is None:
            first = next(queue, None)
            if first is None:
                return None
            chosen = runs[first:first + size]
        fut = client.submit(run_batch, [make_task(i) for i in chosen], key=f"{name}-{chosen[0]:05d}-{len(chosen)}",
                            pure=False)
        batch_of[fut.key] = chosen
        return fut

    first = [f for f in (submit() for _ in range(window)) if f is not None]
    stream = as_completed(first, with_results=True, raise_errors=False)
    for fut, res in stream:
        chosen = batch_of.pop(fut.key)
        fut.release()
        if isinstance(res, BaseException) and len(chosen) > 1:
            for i in chosen:
                stream.add(submit([i]))
            continue
        if isinstance(res, BaseException):
            res = {"results": [{"row": {"status": "error", "message": f"{type(res).__name__}: {res}"}}],
                   "samples": {}}
        on_batch(chosen, res)
        nxt = submit()
        if nxt is not None:
            stream.add(nxt)


def run_study(
    study: Any,
    out: Optional[str] = None,
    *,
    scheduler: Optional[str] = None,
    workers: Optional[int] = None,
    runs: Optional[int] = None,
    processes: bool = True,
    progress: Any = True,
    client: Any = None,
    flush_rows: int = FLUSH_ROWS,
    batch: Optional[int] = None,
    max_steps: Optional[int] = None,
    check_agreement: int = 0,
    reference_solver: str = "explicit",
    log: Callable[[str], None] = lambda s: print(s, file=sys.stderr),
):
    """Runs (or resumes) a study; returns a :class:`~pliant.studies.StudyResult`.
    ``check_agreement`` N > 0: afterwards N of its runs are run again with
    ``reference_solver`` and their verdicts compared (:mod:`.agreement`)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from .results import StudyResult, finish, read_rows

    if not isinstance(study, Study):
        study = load_study(study, runs=runs)
    if check_agreement < 0:
        raise StudyError(f"check_agreement = {check_agreement}: must be a number of runs, at least 0")
    if reference_solver not in SOLVERS:
        raise StudyError(f"reference_solver = {reference_solver}: must be one of {', '.join(SOLVERS)}")
    out = out or os.path.join("out", "study-" + column_name(study.name))
    layout = _prepare(study, out)
    samples = sampling.samples(study)
    ids = [f"run-{i:05d}" for i in range(len(samples))]
    done = done_run_ids(layout)
    pending = [i for i, rid in enumerate(ids) if rid not in done]
    hoses = study.envelope_hoses or [h["name"] for h in study.scene.get("hoses", [])]
    base_scene = variant.absolute_meshes(study.scene, os.path.dirname(study.scene_path))
    radii = variant.hose_radii(base_scene)
    voxel = study.envelope_voxel_m or min(0.005, min(radii.values()) / 2)
    parts = geometry.parts(base_scene)
    fasteners = [s["name"] for s in study.scene.get("stubs", []) + study.scene.get("clips", [])]
    union = _samples_on_disk(layout, hoses, done)
    sch = schema(study)
    seq = 1 + max((int(os.path.basename(p)[5:10]) for p in glob.glob(os.path.join(layout.parts, "part-*.parquet"))),
                  default=-1)
    log(f"study {study.name!r}: {len(samples)} runs ({study.method}), {len(done)} done before, "
        f"{len(pending)} to run; results in {out}")

    upload = scene_files.collect(base_scene, os.path.dirname(study.scene_path))

    def task(i: int, reference: bool = False) -> Task:
        """Run i's task: its scene with the paths of the files the workers were sent. The
        study's own run also writes the replay file; a reference run (agreement) has
        ``reference_solver`` and no envelope."""
        scene = variant.apply(study, samples[i])
        if not reference:
            path = os.path.join(layout.runs, ids[i] + ".json")
            if not os.path.exists(path):
                # compact: the C encoder (with an indent json encodes in Python, ~6 ms a run)
                text = json.dumps(variant.relative_meshes(scene, layout.runs))
                _atomic_write(path, lambda p: open(p, "w").write(text))
        else:
            # the reference is the scene's own physics: that solver, no mass scaling, its
            # settles relaxed dynamically all the way
            scene.setdefault("simulation", {})["solver"] = reference_solver
            plain_physics(scene)
        solver = scene.get("simulation", {}).get("solver", "explicit")
        text = json.dumps(upload.scene_for_workers(scene))
        if reference:
            return Task(ids[i], i, text, "", radii, [], 0.0, [], fasteners, solver, max_steps, upload.key)
        return Task(ids[i], i, text, "", radii, hoses, voxel, parts, fasteners, solver, max_steps, upload.key,
                    study.rerun_unsettled)

    buffer: List[Dict[str, Any]] = []
    state = {"seq": seq, "flushed": time.monotonic(), "failed": 0, "count": len(done)}

    def flush() -> None:
        if not buffer:
            return
        for h in hoses:  # samples first: a row on disk always has its samples in the union
            _atomic_write(layout.samples(h), lambda p, h=h: np.save(open(p, "wb"), union[h]))
        table = pa.Table.from_pylist(buffer, schema=sch)
        path = os.path.join(layout.parts, f"part-{state['seq']:05d}.parquet")
        _atomic_write(path, lambda p: pq.write_table(table, p))
        state["seq"] += 1
        state["flushed"] = time.monotonic()
        buffer.clear()

    def with_ids(chosen: List[int], res: Dict[str, Any]) -> List[Dict[str, Any]]:
        rows = [one["row"] for one in res["results"]]
        if len(rows) == 1 and len(chosen) == 1:
            rows[0].setdefault("run_id", ids[chosen[0]])
            rows[0].setdefault("index", chosen[0])
        return rows

    def record(chosen: List[int], res: Dict[str, Any]) -> None:
        for h, keys in res["samples"].items():  # samples first (see flush)
            union[h] = envelope.union(union[h], keys)
        for i, row in zip(chosen, with_ids(chosen, res)):
            row.update({p.column: str(samples[i][p.name]) if p.categorical else samples[i][p.name]
                        for p in study.parameters})
            if row["status"] != "ok":
                state["failed"] += 1
            buffer.append(row)
            if len(buffer) >= flush_rows or time.monotonic() - state["flushed"] > FLUSH_SECONDS:
                flush()
        state["count"] += len(chosen)
        if bar:
            bar.update(state["count"], state["failed"])

    own_client = client is None
    cluster = None
    bar = None
    measured = None
    try:
        if pending or check_agreement:
            if own_client:
                client, cluster = connect(scheduler, workers, processes)
            link = dashboard_link(client)
            log(f"Dask dashboard: {link}" if link else
                f"Dask dashboard: none (the scheduler at {client.scheduler.address} serves none)")
            if upload.files:
                log(f"sending the scene's {len(upload.files)} files ({upload.size / 2**20:.1f} MiB) to the workers")
            scene_files.upload(client, upload)
            nthreads = max(1, sum(client.nthreads().values()))
        if pending:
            bar = make_progress(progress, len(samples), len(done))
            stream_batches(client, pending, task, batch_size(len(pending), nthreads, batch), 2 * nthreads,
                           f"pliant-{study.fingerprint()}", record)
            if bar:
                bar.update(state["count"], state["failed"], final=True)
        flush()
        if check_agreement:
            rows = {r["index"]: r for r in read_rows(layout.out, sch).to_pylist()}
            chosen = agreement.choose(sorted(rows), check_agreement, study.seed)
            log(f"checking the verdicts of {len(chosen)} runs against the {reference_solver} solver")
            reference: Dict[int, Dict[str, Any]] = {}
            stream_batches(client, chosen, lambda i: task(i, reference=True),
                           batch_size(len(chosen), nthreads, batch), 2 * nthreads,
                           f"pliant-{study.fingerprint()}-{reference_solver}",
                           lambda c, res: reference.update(zip(c, with_ids(c, res))))
            solvers = ",".join(sorted({str(rows[i].get("solver")) for i in chosen}))
            scaling = study.mass_scaling or study.scene.get("simulation", {}).get("mass_scaling") or 1
            reference_label = reference_solver
            if scaling != 1:
                solvers += f" (mass scaling {scaling:g})"
                reference_label += " (unscaled)"
            if study.settle in ("static", "static_equilibrium"):
                solvers += " (settles finished static)" if study.settle == "static" else " (settles ended static)"
                reference_label += " (settles dynamic)"
            if study.rerun_unsettled:
                solvers += " (unsettled runs rerun plain)"
            measured = agreement.compare({i: rows[i] for i in chosen}, reference, solvers, reference_label)
            agreement.write(layout.out, measured)
            log(agreement.sentence(measured["summary"]))
    finally:
        flush()
        if bar:
            bar.close()
        if own_client and client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    voxels = _dilate(layout, union, radii, voxel, log)
    frame = finish(study, layout, sch, voxels, voxel, parts, log)
    return StudyResult(out=os.path.abspath(out), frame=frame, study=study)


def _samples_on_disk(layout: Layout, hoses: List[str], done: set) -> Dict[str, np.ndarray]:
    """The union of the centre-line samples of the runs on disk, per hose (empty for a
    new study); a folder whose rows have no samples (written before the samples were
    kept) cannot be resumed: its envelope would miss those runs."""
    union = {}
    for h in hoses:
        if os.path.exists(layout.samples(h)):
            union[h] = np.load(layout.samples(h))
        elif done and os.path.exists(layout.voxels(h)):
            raise StudyError(
                f"{layout.out}: its envelope holds voxels but not the runs' centre-line samples "
                f"({os.path.basename(layout.samples(h))} is missing: written by an older Pliant), so "
                "the study cannot resume there; choose another --out, or delete the folder to start again")
        else:
            union[h] = np.zeros(0, np.int64)
    return union


def _dilate(layout: Layout, union: Dict[str, np.ndarray], radii: Dict[str, float], voxel: float,
            log: Callable[[str], None]) -> Dict[str, np.ndarray]:
    """The envelope's voxels: each hose's united samples dilated by its tube once
    (:func:`envelope.voxels_of_samples`), written to ``voxels-<hose>.npy``. A hose whose
    swept region is too large for the voxel size gets no envelope, and the log says why
    (the rows stay)."""
    voxels = {}
    for h, keys in union.items():
        try:
            voxels[h] = envelope.voxels_of_samples(keys, radii[h], voxel)
        except ValueError as e:
            log(f"no envelope for hose {h!r}: {e}")
            continue
        _atomic_write(layout.voxels(h), lambda p, h=h: np.save(open(p, "wb"), voxels[h]))
    return voxels
