"""Studies on a cluster started as on real machines: a `dask scheduler` and `dask worker`
processes of their own, in another working directory, sharing no files with the study:
the scene's files reach them as bytes; a worker killed mid-study costs no row; the
verdicts of a sample of runs are checked against another solver."""

import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

import pytest

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

import pliant  # noqa: E402
from pliant.studies import agreement, scene_files  # noqa: E402

from test_study import SCENE, study_dict  # noqa: E402

# the block of the small study's scene as an OBJ mesh in a folder beside the scene
BLOCK_OBJ = "\n".join(
    [f"v {x} {y} {z}" for x in (100, 200) for y in (-50, 50) for z in (-130, -30)]
    + ["f 1 2 4 3", "f 5 7 8 6", "f 1 5 6 2", "f 3 4 8 7", "f 1 3 7 5", "f 2 6 8 4"]) + "\n"


def mesh_scene(folder):
    """The small study's scene with its block read from meshes/block.obj (mm)."""
    (folder / "meshes").mkdir(parents=True)
    (folder / "meshes" / "block.obj").write_text(BLOCK_OBJ)
    text = SCENE.replace('box = { size = [100, 100, 100] }\nposition = [150, 0, -80]',
                         'mesh = "meshes/block.obj"\nmesh_unit = "mm"')
    assert "block.obj" in text
    path = folder / "scene.toml"
    path.write_text(text)
    return path


def wait_for(condition, what, limit=120):
    """Waits until ``condition()`` holds (polling); fails naming ``what`` after ``limit``
    seconds, a guard against a hang, not a timing."""
    end = time.monotonic() + limit
    while not condition():
        if time.monotonic() > end:
            pytest.fail(f"gave up waiting for {what}")
        time.sleep(0.05)


@pytest.fixture
def cluster(tmp_path):
    """A `dask scheduler` and `dask worker` processes (2 single-threaded workers under a
    nanny) started in their own empty working directory; yields (address, worker
    folder)."""
    elsewhere = tmp_path / "worker-cwd"
    elsewhere.mkdir()
    info = tmp_path / "scheduler.json"
    env = dict(os.environ, DASK_DISTRIBUTED__NANNY__PRE_SPAWN_ENVIRON="{'MALLOC_TRIM_THRESHOLD_': None}")  # docs/study.md
    procs = [subprocess.Popen([sys.executable, "-m", "dask", "scheduler", "--port", "0", "--no-dashboard",
                               "--scheduler-file", str(info)], cwd=elsewhere, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        wait_for(info.exists, "the scheduler's file")
        wait_for(lambda: json.loads(info.read_text() or "{}").get("address"), "the scheduler's address")
        address = json.loads(info.read_text())["address"]
        procs.append(subprocess.Popen(
            [sys.executable, "-m", "dask", "worker", address, "--nworkers", "2", "--nthreads", "1",
             "--local-directory", str(elsewhere), "--no-dashboard"], cwd=elsewhere, env=env,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        from distributed import Client

        with Client(address) as c:
            c.wait_for_workers(2)
        yield address, elsewhere
    finally:
        for p in reversed(procs):
            p.send_signal(signal.SIGINT)
        for p in reversed(procs):
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()


def test_scene_files_reach_workers_in_another_directory(cluster, tmp_path, monkeypatch):
    address, elsewhere = cluster
    scene = mesh_scene(tmp_path / "scene")
    moved = tmp_path / "moved-away"
    collect = scene_files.collect

    def collect_then_hide(*args, **kwargs):
        # once read for the workers, the mesh is nowhere a worker could find it by path
        files = collect(*args, **kwargs)
        shutil.move(str(tmp_path / "scene" / "meshes"), str(moved))
        return files

    monkeypatch.setattr(scene_files, "collect", collect_then_hide)
    result = pliant.study(study_dict(scene, runs=6, absurd=False), str(tmp_path / "out"), scheduler=address,
                          progress=False)
    assert moved.is_dir() and not (tmp_path / "scene" / "meshes").exists()
    frame = result.frame
    assert list(frame["status"]) == ["ok"] * 6, list(frame["message"])
    # the workers wrote the mesh below their own folder, in their working directory
    written = list(elsewhere.rglob("files/0/block.obj"))
    assert written and all(p.read_text() == BLOCK_OBJ for p in written)


def test_a_missing_scene_file_is_named(tmp_path):
    scene = mesh_scene(tmp_path / "scene")
    os.remove(tmp_path / "scene" / "meshes" / "block.obj")
    raw = {"parts": [{"name": "block", "mesh": "meshes/block.obj"}]}
    with pytest.raises(pliant.studies.StudyError, match=r"parts\[0\]\.mesh = meshes/block.obj: no such file"):
        scene_files.collect(raw, str(scene.parent))


def test_a_worker_killed_mid_study_loses_no_row(cluster, tmp_path):
    """A worker process is killed while it runs a batch; the study still ends with every
    row, each once, all ok (the scheduler runs the lost batch again elsewhere)."""
    from distributed import Client

    address, _ = cluster
    slow = tmp_path / "slow.toml"  # each run simulates 2 s: the batches take a while
    slow.write_text(SCENE.replace("duration_s = 0.2", "duration_s = 2.0"))
    out = tmp_path / "out"
    box = {}
    thread = threading.Thread(target=lambda: box.update(result=pliant.study(
        study_dict(slow, runs=12, absurd=False), str(out), scheduler=address, progress=False, batch=2)))
    thread.start()
    with Client(address) as c:
        def busy_worker():
            return next((w for w, tasks in c.processing().items() if any("pliant-" in t for t in tasks)), None)

        wait_for(lambda: busy_worker() is not None or not thread.is_alive(), "a worker running a batch")
        victim = busy_worker()
        assert victim is not None, "the study ended before a worker could be killed"
        pid = c.run(os.getpid, workers=[victim])[victim]
        os.kill(pid, signal.SIGKILL)
        wait_for(lambda: victim not in c.scheduler_info()["workers"], "the scheduler to notice the dead worker")
        thread.join()
    frame = box["result"].frame
    assert list(frame["index"]) == list(range(12)) and frame["run_id"].is_unique
    assert (frame["status"] == "ok").all(), list(frame["message"])


def test_verdicts_are_checked_against_the_reference_solver(tmp_path):
    """The study's runs under the static solver, a sample of 8 run again explicit: the
    summary counts what the rows say, and the rows hold both verdicts."""
    import pyarrow.parquet as pq

    scene = tmp_path / "s.toml"
    scene.write_text(SCENE)
    d = dict(study_dict(scene, runs=16, absurd=False), solver="static")
    result = pliant.study(d, str(tmp_path / "out"), workers=2, progress=False, check_agreement=8)
    summary = result.agreement
    rows = pq.read_table(tmp_path / "out" / agreement.AGREEMENT_ROWS).to_pandas()
    assert summary["checked"] == len(rows) == 8 and rows["index"].is_unique
    assert set(rows["solver"]) == {"static"} and set(rows["reference_solver"]) == {"explicit"}
    for _, r in rows.iterrows():  # each verdict compared column by column, as stored
        same = all(r[c] == r["reference_" + c] for c in summary["verdict_columns"])
        assert same == r["agree"]
    assert summary["agreeing"] == int(rows["agree"].sum())
    lo, hi = summary["ci95"]
    assert lo <= summary["share"] <= hi
    # the reference runs really ran explicit: their peak forces are not the static ones
    assert (rows["peak_hand_force_n"] != rows["reference_peak_hand_force_n"]).any()
    assert "Verdicts checked against the explicit solver" in open(result.report).read()


def test_agreement_counts_each_differing_column():
    cols = ["status", "feasible", "violated_checks", "clip_a_assembled"]
    mine = {0: {"run_id": "run-00000", "status": "ok", "feasible": False, "violated_checks": ["bend", "hand"],
                "clip_a_assembled": True},
            1: {"run_id": "run-00001", "status": "ok", "feasible": True, "violated_checks": [],
                "clip_a_assembled": True}}
    ref = {0: {"run_id": "run-00000", "status": "ok", "feasible": False, "violated_checks": ["hand", "bend"],
               "clip_a_assembled": True},
           1: {"run_id": "run-00001", "status": "ok", "feasible": True, "violated_checks": [],
               "clip_a_assembled": False}}
    result = agreement.compare(mine, ref, "implicit", "explicit")
    s = result["summary"]
    assert s["verdict_columns"] == cols
    assert (s["checked"], s["agreeing"], s["share"]) == (2, 1, 0.5)
    assert s["disagreeing"] == [{"run_id": "run-00001", "columns": ["clip_a_assembled"]}]


def test_the_sample_is_the_same_for_the_same_seed_and_never_repeats():
    a = agreement.choose(list(range(100)), 30, seed=4)
    assert a == agreement.choose(list(range(100)), 30, seed=4) and len(set(a)) == 30
    assert agreement.choose(list(range(5)), 30, seed=4) == list(range(5))


def checked_study(tmp_path, scene_text, **options):
    """Four runs of the small study on ``scene_text`` with the study ``options``, all four
    checked against the reference solver: (agreement summary, agreement rows)."""
    import pyarrow.parquet as pq

    scene = tmp_path / "s.toml"
    scene.write_text(scene_text)
    d = dict(study_dict(scene, runs=4, absurd=False), **options)
    result = pliant.study(d, str(tmp_path / "out"), workers=2, progress=False, check_agreement=4)
    rows = pq.read_table(tmp_path / "out" / agreement.AGREEMENT_ROWS).to_pandas()
    assert len(rows) == 4 and result.agreement["checked"] == 4
    return result.agreement, rows


def test_mass_scaled_runs_are_checked_against_unscaled_ones(tmp_path):
    """A study with mass scaling 4: its reference runs are the scene's own physics (no
    scaling), labelled so, and their step counts show it (the scaled step is twice as
    long, so the same timeline takes about half the steps)."""
    summary, rows = checked_study(tmp_path, SCENE, mass_scaling=4)
    assert summary["solver"] == "explicit (mass scaling 4)"
    assert summary["reference_solver"] == "explicit (unscaled)"
    assert (rows["reference_steps"] > 1.5 * rows["steps"]).all(), rows[["steps", "reference_steps"]]


def test_settles_finished_static_are_checked_against_dynamic_ones(tmp_path):
    """A study whose settles the static solver finishes: its reference runs settle
    dynamically (labelled so: their step counts are the dynamic settles', not the
    study's), each verdict compared."""
    summary, rows = checked_study(tmp_path, SCENE + '\n[[timeline]]\naction = "settle"\nmax_duration_s = 10\n',
                                  settle="static")
    assert summary["solver"] == "explicit (settles finished static)"
    assert summary["reference_solver"] == "explicit (settles dynamic)"
    assert (rows["steps"] != rows["reference_steps"]).all(), rows[["steps", "reference_steps"]]
    assert 0 <= summary["agreeing"] <= 4
