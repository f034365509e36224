"""Statics: a clamped cantilever under gravity against beam theory, dead loads added and
removed, reactions in balance with the loads."""

import numpy as np
import pytest

import pliant
from conftest import AREA, DENSITY, EI, G, cantilever_dict

LENGTH = 0.2
TIGHT = dict(force_tolerance=1e-7, moment_tolerance=1e-9)


def tip_deflection(sim):
    return -sim.positions("beam")[-1, 2]


def test_cantilever_under_gravity_matches_beam_theory(cantilever):
    report = cantilever.settle(**TIGHT)
    assert report.converged, report
    w = DENSITY * AREA * G  # N/m
    expected = w * LENGTH**4 / (8 * EI)  # small-deflection tip deflection
    assert expected / LENGTH < 0.05  # small deflection indeed
    # lumped masses on 20 elements: the node loads differ from the distributed load by
    # O(1/N^2); geometric non-linearity at δ/L ≈ 3 % is smaller still
    assert tip_deflection(cantilever) == pytest.approx(expected, rel=0.02)


def test_clamp_reaction_carries_the_weight(cantilever):
    cantilever.settle(**TIGHT)
    weight = cantilever.masses("beam").sum() * G
    reaction = cantilever.reaction_forces("beam")[0]
    np.testing.assert_allclose(reaction, [0.0, 0.0, weight], atol=1e-4 * weight)
    # free nodes are in balance
    assert np.abs(cantilever.forces("beam")[1:]).max() < 1e-6


def test_dead_load_adds_the_tip_load_deflection_and_removing_it_restores(cantilever):
    cantilever.settle(**TIGHT)
    before = cantilever.positions("beam")
    p = 0.02  # N, downwards at the tip
    load = cantilever.add_dead_load("beam", -1, force=[0, 0, -p])
    assert load in cantilever.load_cases and load.kind == "dead_load" and load.node == 20
    assert cantilever.settle(**TIGHT).converged
    extra = tip_deflection(cantilever) + before[-1, 2]
    assert extra == pytest.approx(p * LENGTH**3 / (3 * EI), rel=0.02)
    cantilever.remove_load(load)
    assert load not in cantilever.load_cases
    assert cantilever.settle(**TIGHT).converged
    np.testing.assert_allclose(cantilever.positions("beam"), before, atol=1e-6)
    with pytest.raises(KeyError, match="not active"):
        cantilever.remove_load(load)


def test_removing_the_clamp_lets_it_fall(cantilever):
    (clamp,) = cantilever.load_cases
    assert clamp.kind == "fix" and clamp.node == 0
    cantilever.remove_load(clamp)
    cantilever.run(0.05)
    # free fall: every node has dropped by about g t^2 / 2
    assert cantilever.positions("beam")[:, 2].max() < -0.5 * G * 0.05**2 * 0.9
    assert not cantilever.held("beam").any()


def test_without_initial_loads_nothing_is_fixed():
    sim = pliant.Simulation(pliant.Scene.from_dict(cantilever_dict()), initial_loads=False)
    assert sim.load_cases == []


def test_fix_replaces_an_earlier_fix_on_the_node(cantilever):
    first = cantilever.load_cases[0]
    second = cantilever.fix("beam", 0)
    assert cantilever.load_cases == [second]
    with pytest.raises(KeyError):
        cantilever.remove_load(first)


def test_drive_moves_a_node_and_holds_it(cantilever):
    tip0 = cantilever.positions("beam")[-1]
    drive = cantilever.drive("beam", -1, by=[0.0, 0.0, 0.01], duration=0.05)
    assert drive.kind == "drive"
    np.testing.assert_allclose(cantilever.positions("beam")[-1], tip0 + [0, 0, 0.01], atol=1e-9)
    assert cantilever.held("beam")[-1]


def test_a_drive_too_fast_diverges_with_step_node_and_cause(cantilever):
    cantilever.drive("beam", -1, by=[0.0, 0.0, 50.0], duration=0.001, wait=False)
    with pytest.raises(pliant.SimulationDiverged) as err:
        cantilever.run(0.01)
    e = err.value
    assert isinstance(e, RuntimeError)
    assert "diverged at step" in str(e) and "too fast" in e.cause
    assert e.hose == "beam" and 0 <= e.node <= 20 and e.step > 0
    with pytest.raises(pliant.SimulationDiverged):
        cantilever.step()  # refuses until reset
    cantilever.reset()
    assert cantilever.time == 0.0 and np.all(np.isfinite(cantilever.positions("beam")))
    cantilever.step(10)


def test_invalid_arguments_are_value_errors(cantilever):
    with pytest.raises(ValueError, match="force must be three numbers"):
        cantilever.add_dead_load("beam", -1, force=[1.0, 2.0])
    with pytest.raises(ValueError, match="finite"):
        cantilever.add_dead_load("beam", -1, force=[np.nan, 0, 0])
    with pytest.raises(ValueError, match="duration must be finite and > 0"):
        cantilever.drive("beam", -1, by=[0, 0, 0.01], duration=0.0)
    with pytest.raises(ValueError, match="not both"):
        cantilever.drive("beam", -1, to=[0.2, 0, 0], by=[0, 0, 0.01])
    with pytest.raises(ValueError, match="seconds must be finite"):
        cantilever.run(-1.0)
    with pytest.raises(ValueError, match="force_tolerance"):
        cantilever.settle(force_tolerance=0.0)


def test_solve_static_agrees_with_settle(cantilever):
    """The quasi-static Newton solver and dynamic relaxation reach one equilibrium."""
    report = cantilever.solve_static()
    assert report.converged, report
    assert report.steps < 100
    newton = cantilever.positions("beam").copy()
    cantilever.settle(**TIGHT)
    relaxed = cantilever.positions("beam")
    scale = tip_deflection(cantilever)
    assert np.abs(newton - relaxed).max() < 1e-4 * scale


@pytest.mark.parametrize("solver", ["implicit", "static"])
def test_newton_solvers_reach_the_same_sag(solver):
    """A cantilever under gravity run with the implicit or static solver comes to the
    equilibrium the explicit solver settles to."""
    scene = pliant.Scene.from_dict(cantilever_dict())
    explicit = pliant.Simulation(scene)
    explicit.settle(**TIGHT)
    other = pliant.Simulation(scene, solver=solver)
    assert other.solver == solver
    assert other.time_step == pytest.approx(0.01)
    other.run(3.0)
    scale = tip_deflection(explicit)
    assert abs(tip_deflection(other) - scale) < 1e-3 * scale


def test_unknown_solver_is_a_value_error():
    with pytest.raises(ValueError, match="unknown solver 'newton'"):
        pliant.Simulation(pliant.Scene.from_dict(cantilever_dict()), solver="newton")


def test_a_ramped_dead_load_rises_over_its_ramp(cantilever):
    p = 0.02  # N, downwards at the tip, reached after 0.2 s
    cantilever.add_dead_load("beam", -1, force=[0, 0, -p], ramp=0.2)
    # equilibria at t = 0, 0.1 s and 0.3 s: none, half and all of the load
    cantilever.solve_static()
    at_start = tip_deflection(cantilever)
    cantilever.run(0.1)
    cantilever.solve_static()
    half = tip_deflection(cantilever)
    cantilever.run(0.2)
    cantilever.solve_static()
    full = tip_deflection(cantilever)
    extra = p * LENGTH**3 / (3 * EI)
    assert half - at_start == pytest.approx(0.5 * extra, rel=0.03)
    assert full - at_start == pytest.approx(extra, rel=0.03)
    with pytest.raises(ValueError, match="ramp"):
        cantilever.add_dead_load("beam", -1, force=[0, 0, -p], ramp=-1.0)
