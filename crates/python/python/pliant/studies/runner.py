"""One run of a study, on a Dask worker: the variant's whole timeline (``run_timeline``,
its solver), reduced to one result row plus its hoses' centre-line samples (dilated to
voxels once per batch).

Nothing is lost: a scene the engine refuses is recorded with status ``invalid``, a
diverged run as ``diverged`` (its metrics are those of the run up to the last healthy
state), an unconverged Newton solve sets ``uncertain``; any other exception is
``error``. The message is kept in every case.
"""

from __future__ import annotations

import json
import os
import re
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from . import envelope, motion, scene_files
from .geometry import Part

STATUSES = ("ok", "diverged", "invalid", "error")


def column_name(*words: str) -> str:
    """A SQL-friendly column name: lower case, words joined by '_'."""
    return re.sub(r"[^0-9a-z]+", "_", "_".join(words).lower()).strip("_")


@dataclass
class Task:
    """Everything a worker needs for one run (picklable)."""

    run_id: str
    index: int
    scene_json: str
    base_dir: str  # the folder the scene's relative paths start from (see files_key)
    radii: Dict[str, float]  # outer radius per hose [m]
    envelope_hoses: List[str]
    voxel: float  # [m]; 0: no envelope
    parts: List[Part] = field(default_factory=list)
    fasteners: List[str] = field(default_factory=list)
    solver: str = "explicit"
    max_steps: Optional[int] = None  # None: pliant.DEFAULT_MAX_STEPS
    files_key: Optional[str] = None  # the scene's files were sent to the workers: paths start there
    rerun_unsettled: bool = False  # a run whose verdict the cheaper physics may have changed runs again, plain (see run_variant)


def _result_row(result, task: Task) -> Dict[str, Any]:
    """Peaks, verdict and checks of a RunResult as flat columns (SI)."""
    solver = result.solver_record or {}  # not the whole summary: it holds the fastener series
    row: Dict[str, Any] = {
        "feasible": result.feasible,
        "uncertain": bool(result.uncertain),
        "completed": bool(result.completed),
        "reasons": list(result.reasons),
        "warnings": list(result.warnings),
        "steps": int(result.steps),
        "simulated_time_s": float(result.simulated_time),
        "solver": task.solver,
        "rerun": False,
        "solver_warnings": len(result.solver_warnings),
        "unconverged_steps": int(solver.get("unconverged_steps") or 0),
        "instabilities": int(solver.get("instability_count") or 0),
    }
    hands = result.hand_peaks
    row["peak_hand_force_n"] = max((h["max_force"] for h in hands), default=0.0)
    row["peak_hand_torque_nm"] = max((h["max_torque"] for h in hands), default=0.0)
    worst = max(hands, key=lambda h: h.get("worst_ratio") or 0.0, default=None)
    row["worst_hand_ratio"] = worst.get("worst_ratio") if worst else None
    row["worst_hand_kind"] = worst.get("worst_kind") if worst else None
    row["worst_hand_limit_n"] = worst.get("worst_limit") if worst else None
    for f in result.fasteners:
        base = column_name(f["kind"], f["name"])
        row[base + "_force_n"] = float(f["max_force"])
        row[base + "_assembled"] = bool(f.get("assembled"))
    profiles = result.check_profiles
    ratios = [p["min_bend_radius"] / p["allowed_bend_radius"] for p in profiles
              if p.get("allowed_bend_radius") and p.get("min_bend_radius") is not None]
    twists = [p["max_twist"] for p in profiles if p.get("max_twist") is not None]
    row["min_bend_radius_ratio"] = min(ratios) if ratios else None
    row["max_twist_rad_per_m"] = max(twists) if twists else None
    row["violated_checks"] = sorted({v["check"] for v in result.violations})
    row.update(motion.columns(result))
    worker = result.worker
    if worker is not None:
        row.update(_worker_columns(worker))
        row["worst_hand_posture_class"] = worst.get("worst_class") if worst else None
    return row


def _worker_columns(worker: Dict[str, Any]) -> Dict[str, Any]:
    """The worker's columns (SPEC E1–E2): worst RULA and REBA (None if never posed), the
    reach shortfall [m] — the larger arm's worst residual among targets out of reach, 0
    when every target was reached — and the number of body collisions (segment–part
    pairs)."""
    rula, reba = worker.get("worst_rula"), worker.get("worst_reba")
    out = [r["worst"] for r in worker["reach"] if r.get("first_out") is not None]
    return {
        "worst_rula": rula["score"]["grand"] if rula else None,
        "worst_reba": reba["score"]["reba"] if reba else None,
        "reach_shortfall_m": float(max(out, default=0.0)),
        "body_collisions": len(worker["collisions"]),
    }


def _sweep(result, task: Task, row: Dict[str, Any]) -> Dict[str, np.ndarray]:
    """Centre-line samples of each envelope hose (keys of :func:`envelope.sample_keys`;
    the study dilates their union to voxels once), and the hoses' smallest clearance to each part
    [m] (nodes and element midpoints of every recorded instant)."""
    samples: Dict[str, np.ndarray] = {}
    points, radii = [], []
    for hose in task.envelope_hoses:
        r = task.radii[hose]
        frames = np.asarray(result.positions(hose))
        if frames.size == 0:
            continue
        if task.voxel > 0:
            samples[hose] = envelope.sample_keys(frames, task.voxel)
        mids = 0.5 * (frames[:, 1:] + frames[:, :-1])
        pts = np.concatenate([frames.reshape(-1, 3), mids.reshape(-1, 3)])
        points.append(pts)
        radii.append(np.full(len(pts), r))
    if points:
        pts, rad = np.concatenate(points), np.concatenate(radii)
        for part in task.parts:
            d = part.min_distance(pts, rad)
            row[column_name("clearance", part.name, "m")] = d if np.isfinite(d) else None
    return samples


def run_batch(tasks: List[Task]) -> Dict[str, Any]:
    """Runs several variants in one Dask task (each as :func:`run_variant`): the task's
    scheduling, (de)serialisation and the parts' geometry are paid once per batch, and
    the batch's centre-line samples are united (the study unites every batch's and
    dilates the whole union to voxels once at its end: the same voxels as run by run,
    see :func:`envelope.sample_keys`). Returns {"results": [{"row": ...}, ...],
    "samples": {hose: sorted keys}}."""
    # one thread per run: a study keeps every core busy with runs of its own (the
    # explicit solver would otherwise start a thread per core for a scene of several
    # hoses, for each worker); a worker started with PLIANT_THREADS set keeps its value
    os.environ.setdefault("PLIANT_THREADS", "1")
    results, samples = [], {}
    for task in tasks:
        res = run_variant(task)
        for h, keys in res.pop("samples").items():
            samples[h] = envelope.union(samples[h], keys) if h in samples else keys
        results.append(res)
    return {"results": results, "samples": samples}


def plain_physics(scene: Dict[str, Any]) -> Dict[str, Any]:
    """The scene with its own physics: no mass scaling, every settle relaxed dynamically
    all the way (what the cheaper study modes change; changed in place, returned)."""
    scene.get("simulation", {}).pop("mass_scaling", None)
    for action in scene.get("timeline", []):
        if isinstance(action, dict) and action.get("action") == "settle":
            action.pop("finish", None)
    return scene


def _unsettled(result) -> bool:
    """Whether a settle of the run ended without coming to rest."""
    return any(not s["at_rest"] for s in result.settles)


def _mass_scaled(scene_json: str) -> bool:
    """Whether the scene scales its inertia (``[simulation] mass_scaling`` above 1)."""
    return (json.loads(scene_json).get("simulation") or {}).get("mass_scaling", 1) > 1


def _doubtful(result, task: Task) -> bool:
    """Whether the cheaper physics may have changed the run's verdict: a settle that did
    not come to rest, or — under mass scaling — a clip or stub that ended unassembled. A
    clip snaps into its seat or springs back out of it by the hose's motion as the hand
    lets go, which s times the inertia changes (the engine-corner clip of the demo study
    ends free scaled where it seats plain; docs/study.md)."""
    if _unsettled(result):
        return True
    free = any(not f.get("assembled") for f in result.fasteners)
    return free and _mass_scaled(task.scene_json)


def _run(task: Task, scene_json: str):
    """The timeline of one scene (JSON) of the task."""
    import pliant

    base_dir = scene_files.folder(task.files_key) if task.files_key else task.base_dir
    scene = pliant.Scene.from_json(scene_json, origin=f"runs/{task.run_id}.json", base_dir=base_dir)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", pliant.SolverWarning)
        if task.max_steps is None:
            return pliant.run_timeline(scene)
        return pliant.run_timeline(scene, max_steps=task.max_steps)


def run_variant(task: Task) -> Dict[str, Any]:
    """Runs one variant; returns {"row": {...}, "samples": {hose: centre-line sample
    keys}}. Never raises for a bad variant: its status and message are in the row. With
    ``task.rerun_unsettled`` a run (mass-scaled, or its settles finished by the static
    solver) whose settles do not all come to rest, or mass-scaled with a clip or stub not
    assembled (:func:`_doubtful`), is run again with the scene's own physics
    (:func:`plain_physics`), and the row is that run's (``rerun`` true; the CPU time is
    both runs')."""
    import pliant

    row: Dict[str, Any] = {"run_id": task.run_id, "index": task.index, "status": "ok", "message": ""}
    samples: Dict[str, np.ndarray] = {}
    start, cpu = time.perf_counter(), time.process_time()
    result = None
    rerun = False
    try:
        result = _run(task, task.scene_json)
        if task.rerun_unsettled and _doubtful(result, task):
            rerun = True
            result = _run(task, json.dumps(plain_physics(json.loads(task.scene_json))))
    except pliant.SceneError as e:
        row.update(status="invalid", message=str(e))
    except pliant.SimulationDiverged as e:
        row.update(status="diverged", message=str(e))
        result = e.result
    except Exception as e:  # recorded, never lost
        row.update(status="error", message=f"{type(e).__name__}: {e}")
    if result is not None:
        try:
            row.update(_result_row(result, task))
            row["rerun"] = rerun
            if row["status"] == "diverged":
                row["feasible"] = False
            if row["status"] == "ok":  # a diverged run's last states are not physical
                samples = _sweep(result, task, row)
        except Exception as e:
            row.update(status="error", message=f"reading the result: {type(e).__name__}: {e}")
    row["wall_time_s"] = time.perf_counter() - start
    row["cpu_time_s"] = time.process_time() - cpu  # the worker's CPU: < wall when cores are shared
    return {"row": row, "samples": samples}
