"""Timeline runs: the same verdict and report files as `pliant run`."""

import json
import subprocess

import numpy as np
import pytest

import pliant
from conftest import cantilever_dict


@pytest.fixture(scope="module")
def demo_result():
    return pliant.run_timeline(pliant.demo_scene())


def test_demo_verdict_and_report_equal_the_cli(tmp_path, pliant_bin, demo_result):
    cli = subprocess.run(
        [pliant_bin, "run", "--quiet", "--out", str(tmp_path / "cli")],
        capture_output=True,
        text=True,
    )
    assert cli.returncode == 0, cli.stderr
    demo_result.write_report(tmp_path / "py")
    cli_report = json.loads((tmp_path / "cli" / "report.json").read_text())
    py_report = json.loads((tmp_path / "py" / "report.json").read_text())
    assert py_report["verdict"]["feasible"] == cli_report["verdict"]["feasible"] is False
    assert py_report == cli_report  # same run, same peaks, same fastener series
    assert (tmp_path / "py" / "report.html").read_text() == (
        tmp_path / "cli" / "report.html"
    ).read_text()
    assert "verdict: NOT FEASIBLE" in cli.stdout
    for reason in demo_result.reasons:
        assert f"  - {reason}" in cli.stdout


def test_result_contents(demo_result):
    r = demo_result
    assert r.completed and r.diverged is None and r.feasible is False
    assert r.steps > 0 and r.simulated_time > 9.0
    assert r.hands == [0]
    s = r.hand_series(0)
    k = len(s["time"])
    assert k > 10
    assert s["force"].shape == s["torque"].shape == s["position"].shape == (k, 3)
    assert s["ratio"].shape == s["limit"].shape == s["colour"].shape == (k,)
    peak = r.hand_peaks[0]
    assert np.linalg.norm(s["force"], axis=1).max() <= peak["max_force"] + 1e-9
    assert {p["hose"] for p in r.peaks} == {"upper", "lower"}
    assert {f["name"] for f in r.fasteners} >= {"water pump inlet"}
    times = r.times
    assert times.ndim == 1 and np.all(np.diff(times) > 0)
    x = r.positions("lower")
    assert x.shape == (len(times), 16, 3) and np.all(np.isfinite(x))
    assert r.summary["steps"] == r.steps
    with pytest.raises(ValueError, match="hand 3 did not act"):
        r.hand_series(3)


def test_report_files_written(tmp_path, demo_result):
    out = tmp_path / "deep" / "report"
    demo_result.write_report(out)
    report = json.loads((out / "report.json").read_text())
    assert report["scene"] == "Engine bay with rigid parts"
    assert report["verdict"]["reasons"] == demo_result.reasons
    assert report["verdict"]["findings"] == demo_result.findings
    assert (out / "report.html").read_text().startswith("<!doctype html>")


def test_findings_are_the_reasons_as_data(demo_result):
    f = demo_result.findings
    for words in ("reasons", "warnings", "zones", "pending"):
        assert len(f[words]) == len(getattr(demo_result, words, f[words]))
    push = f["reasons"][0]
    assert push["kind"] == "hand_load_over_limit" and push["load"] == "push"
    assert push["ratio"] == pytest.approx(push["value"] / push["limit"], rel=1e-12)
    assert f"push of {push['value']:.1f} N" in demo_result.reasons[0]
    assert push["working"] == {"fastener": "clip", "name": "clip engine corner"}
    checks = {r["violation"]["check"] for r in f["reasons"] if r["kind"] == "check_violated"}
    assert checks == {v["check"] for v in demo_result.violations}
    assert {w["load"] for w in f["warnings"]} == {"twist", "bending"}


def test_ergonomics_override_and_bad_profile():
    scene = pliant.demo_scene()
    r = pliant.run_timeline(scene, ergonomics="posture=sitting, population=men")
    assert "population=men" in r.ergonomics and "push=sitting" in r.ergonomics
    with pytest.raises(ValueError, match="ergonomics 'posture=flying'"):
        pliant.run_timeline(scene, ergonomics="posture=flying")


def test_en1005_profile_judges_with_risk_zones():
    scene = pliant.demo_scene()
    r = pliant.run_timeline(
        scene, ergonomics="standard=en1005-3, action=whole_body, frequency_per_min=1"
    )
    assert r.standard == "EN 1005-3:2002+A1:2008"
    assert "standard=en1005_3" in r.ergonomics and "frequency_per_min=1" in r.ergonomics
    assert r.zones and all("EN 1005-3" in z for z in r.zones)
    assert any(
        w in z for z in r.zones for w in ("RECOMMENDED", "NOT RECOMMENDED", "TO BE AVOIDED")
    )
    assert pliant.run_timeline(scene).standard.startswith("dissertation")
    with pytest.raises(ValueError, match="`frequency_per_min` must lie in"):
        pliant.run_timeline(scene, ergonomics="standard=en1005-3, frequency_per_min=99")
    with pytest.raises(ValueError, match="give `standard=en1005-3` first"):
        pliant.run_timeline(scene, ergonomics="action=arm")


def test_no_hand_means_not_assessed():
    d = cantilever_dict()
    d["timeline"].append({"action": "run", "duration_s": 0.01})
    r = pliant.run_timeline(pliant.Scene.from_dict(d))
    assert r.feasible is None
    assert r.hands == []
    assert "no hand acted" in r.reasons[-1]
    assert r.findings["reasons"][-1] == {"kind": "no_hand_acted", "stage": "final"}


def test_diverging_timeline_raises_with_the_partial_result(tmp_path):
    d = cantilever_dict()
    d["timeline"].append(
        {"action": "move", "hose": "beam", "node": -1, "by": [0, 0, 50], "duration_s": 0.001}
    )
    with pytest.raises(pliant.SimulationDiverged) as err:
        pliant.run_timeline(pliant.Scene.from_dict(d))
    result = err.value.result
    assert result is not None and not result.completed and result.feasible is False
    assert result.reasons[0].startswith("the simulation stopped early: simulation diverged")
    result.write_report(tmp_path)
    assert json.loads((tmp_path / "report.json").read_text())["diverged"] == str(err.value)
    # the typed reason beside the message, as summary.json holds it
    d = result.divergence
    assert d["message"] == str(err.value)
    assert d["kind"] in ("non_finite_state", "non_finite_velocity", "support_load", "speed"), d
    assert d["hose"] == "beam" and d["step"] > 0 and d["time_s"] > 0


def test_a_run_planned_beyond_max_steps_is_refused_before_it_starts():
    d = cantilever_dict()
    d["timeline"] = [{"action": "run", "duration_s": 0.01}]
    scene = pliant.Scene.from_dict(d)
    steps = int(np.ceil(0.01 / scene.time_step))
    assert steps > 10 and pliant.DEFAULT_MAX_STEPS == 1_000_000_000
    with pytest.raises(pliant.SceneError, match="at most 10 are allowed"):
        pliant.run_timeline(scene, max_steps=10)
    assert pliant.run_timeline(scene, max_steps=2 * steps).completed


def test_installation_checks_are_exposed(demo_result):
    keys = {"check", "hose_name", "arc_length", "time", "value", "limit", "first_time", "last_time"}
    for v in demo_result.violations:
        assert keys <= set(v)
        assert v["check"] in ("bend_radius", "twist", "tension_at_rest", "straight_behind_stub")
    profiles = demo_result.check_profiles
    assert [p["hose_name"] for p in profiles] == ["upper", "lower"]
    for p in profiles:
        assert len(p["curvature"]) == len(p["arc_length"]) == len(p["twist"])
        assert p["allowed_bend_radius"] > 0
