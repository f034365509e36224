"""Arrays: shapes, dtypes, units and independence from the simulation."""

import numpy as np
import pytest

import pliant


@pytest.fixture(scope="module")
def sim():
    s = pliant.Simulation(pliant.demo_scene())
    s.run(0.02)
    return s


@pytest.mark.parametrize(
    "name",
    [
        "positions",
        "velocities",
        "angular_velocities",
        "forces",
        "moments",
        "reaction_forces",
        "reaction_moments",
        "contact_forces",
        "hose_contact_forces",
        "rest_positions",
    ],
)
def test_vector_arrays_are_n_by_3_float64(sim, name):
    for hose in sim.hose_names:
        a = getattr(sim, name)(hose)
        assert a.shape == (sim.node_count(hose), 3)
        assert a.dtype == np.float64
        assert np.all(np.isfinite(a))


def test_orientations_are_unit_quaternions(sim):
    q = sim.orientations("lower")
    assert q.shape == (sim.node_count("lower"), 4) and q.dtype == np.float64
    np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12)


def test_held_and_masses(sim):
    held = sim.held("upper")
    assert held.dtype == np.bool_ and held.shape == (sim.node_count("upper"),)
    assert held[0] and held[-1]  # the demo fixes both ends of the upper hose
    m = sim.masses("upper")
    assert m.shape == (sim.node_count("upper"),) and np.all(m > 0)


def test_arrays_are_copies(sim):
    x = sim.positions("lower")
    x[:] = 0.0
    assert not np.allclose(sim.positions("lower"), 0.0)


def test_hose_by_index_and_name_agree(sim):
    np.testing.assert_array_equal(sim.positions(1), sim.positions("lower"))
    np.testing.assert_array_equal(sim.positions(-1), sim.positions("lower"))


def test_bad_hose_and_node_references(sim):
    with pytest.raises(ValueError, match="no hose named 'middle'"):
        sim.positions("middle")
    with pytest.raises(IndexError, match="hose index 5 out of range"):
        sim.positions(5)
    with pytest.raises(IndexError, match="node 99 out of range"):
        sim.fix("lower", 99)
    with pytest.raises(TypeError):
        sim.positions(1.5)


def test_energies_are_finite(sim):
    assert sim.kinetic_energy >= 0
    assert np.isfinite(sim.strain_energy) and np.isfinite(sim.gravity_energy)
