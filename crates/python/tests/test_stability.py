"""Stability and honest convergence in Python: a clamped hose pushed past its
Euler load under the static solver buckles onto the stable branch, the instability is
reported with its mode shape, and the numbers stay certain (every solve converged)."""

import math
import warnings

import numpy as np

import pliant
from conftest import EI, cantilever_dict

LENGTH = 0.2


def clamped_column(**options):
    scene = cantilever_dict(length=LENGTH, elements=20, gravity=(0.0, 0.0, 0.0))
    scene["simulation"]["solver"] = "static"
    scene["timeline"].append({"action": "fix", "hose": "beam", "node": -1})
    return pliant.Simulation(pliant.Scene.from_dict(scene), **options)


def test_a_column_pushed_past_buckling_reports_the_instability():
    sim = clamped_column(strict=True)  # strict: an unconverged step would raise
    with warnings.catch_warnings():
        warnings.simplefilter("error", pliant.SolverWarning)
        sim.drive("beam", -1, by=[[-0.3 * LENGTH, 0.0, 0.0]], duration=0.5)
    events = sim.instabilities()
    assert events, "the straight column past its Euler load was not found unstable"
    first = events[0]
    assert first["hose"] == "beam" and 0 < first["time"] <= 0.5
    assert first["negative_eigenvalues"] >= 1
    mode = first["mode"]
    assert mode.shape == (21, 3) and math.isclose(np.linalg.norm(mode, axis=1).max(), 1.0)
    assert sim.solver_warnings == []
    # buckled: mid-span out of line, end load near the Euler load 4π²EI/L², far below
    # the straight branch's E A · 30 %
    mid = sim.positions("beam")[10]
    assert math.hypot(mid[1], mid[2]) > 0.05 * LENGTH
    end_load = np.linalg.norm(sim.reaction_forces("beam")[-1])
    euler = 4 * math.pi**2 * EI / LENGTH**2
    assert euler < end_load < 1.5 * euler
