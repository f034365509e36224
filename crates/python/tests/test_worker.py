"""SPEC E1–E2 in Python: ``Simulation.worker()`` (the manikin's account and its series as
arrays), ``RunResult.worker``, a study's worker columns and the percentile as a study
axis.

The scene: a 400 mm hose along x at height ``z``, fixed at its start, its end grabbed and
lowered by 20 mm. At z = 1.9 m the grab point is above the 5th-percentile woman's reach
(shoulder 0.818 H + arm to the grip 0.386 H = 1.83 m at H = 1.523 m) and within the
95th-percentile woman's (2.09 m at H = 1.734 m).
"""

import json
import math

import numpy as np
import pytest

import pliant
from conftest import held_hose_scene
from pliant.studies import load_study, variant_scene
from pliant.studies.runner import Task, run_variant

WORKER = '[worker]\npopulation = "female"\npercentile = {percentile}\nfacing = [1, 0, 0]\n'


def scene_text(percentile=None, z=1900.0):
    worker = "" if percentile is None else WORKER.format(percentile=percentile)
    return held_hose_scene(worker, z)


def simulate(text):
    """The scene's grab and lowering driven through ``Simulation`` (its leading ``fix`` is
    applied by the Simulation itself, as a scene's initial load)."""
    sim = pliant.Simulation(pliant.Scene.from_toml(text), solver="static")
    z = 1.9 if "1900" in text else 1.2
    sim.grab(0, [0.5, -0.2, z])
    sim.move_hand(0, by=[0.0, 0.0, -0.02], duration=0.3)  # runs until the motion ends
    return sim


def test_without_a_worker_there_is_none():
    sim = simulate(scene_text())
    assert sim.worker() is None
    assert pliant.run_timeline(pliant.Scene.from_toml(scene_text())).worker is None


def test_the_small_woman_is_out_of_reach_and_the_series_are_arrays():
    sim = simulate(scene_text(5))
    w = sim.worker()
    assert w["who"] == "the 5th-percentile woman"
    series = {
        k: np.asarray(v, dtype=str if k == "posture_class" else float)
        for k, v in w["series"].items()
    }
    n = len(series["time"])
    assert n == w["instants"] > 2
    assert all(len(v) == n for v in series.values())
    assert np.all(np.diff(series["time"]) > 0)
    # the hand is the right arm's (it is right of the worker's midline); the left hangs
    assert np.all(np.isnan(series["left_residual"]))
    right = series["right_residual"]
    assert np.all(right > 0.05), right
    reach = w["reach"][0]
    assert reach["worst"] == pytest.approx(right.max())
    assert reach["first_out"] is not None and reach["hand"] == 0
    # the scores are the methods' integers, in their ranges, the worst among them
    assert np.all((series["rula"] >= 1) & (series["rula"] <= 7))
    assert np.all((series["reba"] >= 1) & (series["reba"] <= 15))
    assert w["worst_rula"]["score"]["grand"] == series["rula"].max()
    assert w["worst_reba"]["score"]["reba"] == series["reba"].max()
    # reaching up, the arm is above the shoulder at every instant (SPEC E2)
    assert w["class_instants"] == {
        "upright": 0,
        "bent_trunk": 0,
        "arms_above_shoulder": n,
        "sitting": 0,
        "sitting_bent_trunk": 0,
    }
    assert list(series["posture_class"]) == ["arms_above_shoulder"] * n
    assert w["seat"] is None
    finding = w["findings"][0]
    assert finding["kind"] == "out_of_reach" and finding["arm"] == "right"
    assert finding["distance"] == reach["worst"]


def test_the_simulation_and_the_timeline_give_the_same_worker():
    text = scene_text(5)
    sim = simulate(text)
    result = pliant.run_timeline(pliant.Scene.from_toml(text))
    a, b = sim.worker(), result.worker
    for key in ("who", "instants", "worst_rula", "worst_reba", "class_instants"):
        assert a[key] == b[key], key
    # the residuals agree to rounding, not bit for bit: the grab point and the hand's path
    # are given here in metres, in the scene in millimetres (1900 mm · 10⁻³ ≠ 1.9 m exactly)
    for ra, rb in zip(a["reach"], b["reach"]):
        assert ra["worst"] == pytest.approx(rb["worst"], rel=1e-12)
        assert (ra["time"], ra["first_out"], ra["last_out"]) == (rb["time"], rb["first_out"], rb["last_out"])
    assert [f["kind"] for f in a["findings"]] == [f["kind"] for f in b["findings"]]
    assert result.feasible is False
    assert any(r.startswith("out of reach for the 5th-percentile woman by ") for r in result.reasons)


def test_the_percentile_is_a_study_axis_and_the_worker_has_columns(tmp_path):
    scene_path = tmp_path / "reach.toml"
    scene_path.write_text(scene_text(50))
    study = load_study({
        "format": "pliant-study", "version": 1, "name": "reach", "scene": str(scene_path),
        "length_unit": "mm", "sampling": {"method": "grid", "runs": 2},
        "parameters": [{"name": "percentile", "vary": "scene_value", "path": "worker.percentile",
                        "apply": "set", "distribution": "choice", "choices": [5, 95]}],
    })
    rows = {}
    for index, percentile in enumerate((5, 95)):
        scene = variant_scene(study, {"percentile": percentile})
        assert scene["worker"]["percentile"] == percentile
        task = Task(run_id=f"r{index}", index=index, scene_json=json.dumps(scene),
                    base_dir=str(tmp_path), radii={}, envelope_hoses=[], voxel=0.0, solver="static")
        row = run_variant(task)["row"]
        assert row["status"] == "ok", row["message"]
        rows[percentile] = row
    small, tall = rows[5], rows[95]
    # the reach shortfall is the worker's worst residual; 0 when every target is reached
    result = pliant.run_timeline(pliant.Scene.from_toml(scene_text(5)), solver="static")
    assert small["reach_shortfall_m"] == result.worker["reach"][0]["worst"] > 0.05
    assert tall["reach_shortfall_m"] == 0.0
    assert small["feasible"] is False and tall["feasible"] is True
    for row in (small, tall):
        assert 1 <= row["worst_rula"] <= 7 and 1 <= row["worst_reba"] <= 15
        assert row["body_collisions"] == 0
        assert row["worst_hand_posture_class"] == "arms_above_shoulder"
    # without a worker, no worker columns
    scene = variant_scene(study, {"percentile": 5})
    del scene["worker"]
    row = run_variant(Task(run_id="p", index=0, scene_json=json.dumps(scene), base_dir=str(tmp_path),
                           radii={}, envelope_hoses=[], voxel=0.0, solver="static"))["row"]
    assert row["status"] == "ok", row["message"]
    assert "worst_rula" not in row and "reach_shortfall_m" not in row
    assert not math.isnan(row["peak_hand_force_n"])


SEATED = '[worker]\npopulation = "male 50"\nposture = "sitting"\nposition = [0, 0, 0]\nfacing = [1, 0, 0]\n'


def test_a_seated_worker_reaches_the_table_and_is_classed_sitting():
    """The 50th-percentile man on the default seat (his ANSUR II popliteal height,
    0.435 m) holds the hose end at table height (720 mm) 0.5 m in front of the seat."""
    text = held_hose_scene(SEATED, 720.0)
    w = pliant.run_timeline(pliant.Scene.from_toml(text), solver="static").worker
    assert w["seat"]["height"] == pytest.approx(0.435, abs=1e-12)
    assert w["class_instants"]["sitting"] == w["instants"] > 0
    assert w["reach"][0]["worst"] < 1e-3
    # feet on the floor: RULA's and REBA's leg scores 1
    assert w["worst_rula"]["score"]["legs"] == 1 and w["worst_reba"]["score"]["legs"] == 1
    sim = pliant.Simulation(pliant.Scene.from_toml(text), solver="static")
    sim.grab(0, [0.5, -0.2, 0.72])
    sim.move_hand(0, by=[0.0, 0.0, -0.02], duration=0.3)
    classes = np.asarray(sim.worker()["series"]["posture_class"], dtype=str)
    assert classes.size > 2 and np.all(classes == "sitting")
