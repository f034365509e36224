"""A live simulation's range of motion (`Simulation.sweep`): the door-hinge example
stepped from Python gives the rows `pliant run` writes to motion.csv, number for number,
and the same worst positions as the CLI's verdict."""

import pathlib
import subprocess

import numpy as np
import pytest

import pliant

EXAMPLE = pathlib.Path(__file__).resolve().parents[3] / "examples" / "door_hinge.toml"


def read_csv(path):
    lines = pathlib.Path(path).read_text().splitlines()
    head = lines[0].split(",")
    rows = [[float(v) if v else float("nan") for v in line.split(",")] for line in lines[1:]]
    return {name: np.array([r[k] for r in rows]) for k, name in enumerate(head)}


def test_a_live_sweep_gives_the_rows_the_cli_writes(pliant_bin, tmp_path):
    out = tmp_path / "out"
    done = subprocess.run([pliant_bin, "run", "--quiet", str(EXAMPLE), "--out", str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    cli = read_csv(out / "motion.csv")

    scene = pliant.load_scene(EXAMPLE)
    sim = pliant.Simulation(scene)  # the timeline's initial fixes; then its 4.8 s run
    assert sim.sweep()["columns"]["time_s"].size <= 1
    sim.run(4.8)
    found = sim.sweep()
    live = found["columns"]
    assert list(live) == list(cli)
    assert len(live["time_s"]) == len(cli["time_s"]) > 100
    for name in cli:
        assert np.array_equal(np.isnan(live[name]), np.isnan(cli[name])), name
        assert np.array_equal(live[name], cli[name], equal_nan=True), name

    # the worst positions: as the rows say, and as the CLI's verdict words them
    angle = live["angle_deg"]
    bend = next(w for w in found["worst"] if w["what"] == "hose 'door hose': bend radius")
    i = int(np.argmin(np.abs(live["time_s"] - bend["time"])))
    assert bend["position"] == "door angle 70°" and abs(angle[i] - 70.0) < 1e-6
    pillar = next(w for w in found["worst"] if "to part 'pillar'" in w["what"])
    column = live["clearance_m door hose to pillar"]
    assert abs(pillar["value"] - column.min()) <= 1e-6 * max(1.0, abs(column.min()))
    report = (out / "report.json").read_text()
    assert found["over_the_motion"] in report
    assert found["clearance_violations"] == []


def test_no_sweep_without_a_sweep_section():
    sim = pliant.Simulation(pliant.demo_scene())
    assert sim.sweep() is None
