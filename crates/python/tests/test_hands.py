"""Hands: grab, move, hand force in balance with the other supports, release."""

import numpy as np
import pytest

import pliant
from conftest import G


def test_grab_and_move_produce_a_hand_force(cantilever):
    hose, a, b = cantilever.grab(0, hose="beam", node=-1)
    assert (hose, a, b) == ("beam", 19, 20)
    assert cantilever.hands == [0]
    cantilever.step()
    before = np.linalg.norm(cantilever.hand_force(0))
    cantilever.move_hand(0, by=[0.0, 0.0, 0.03], duration=0.2)
    cantilever.settle(force_tolerance=1e-7, moment_tolerance=1e-9)
    force = cantilever.hand_force(0)
    assert force.shape == (3,) and force.dtype == np.float64
    # lifting the tip 3 cm bends the beam: the hand pushes down against it (and
    # carries part of the weight) — far more than at the start
    assert np.linalg.norm(force) > 10 * max(before, 1e-6)
    # statics: hand and clamp together carry exactly the weight
    weight = cantilever.masses("beam").sum() * G
    clamp = cantilever.reaction_forces("beam")[0]
    np.testing.assert_allclose(force + clamp, [0.0, 0.0, weight], atol=1e-4 * weight)


def test_hand_follows_its_path_and_orientation(cantilever):
    cantilever.grab(0, at=[0.2, 0.0, 0.0])
    cantilever.move_hand(0, to=[0.18, 0.0, 0.02], duration=0.1)
    pos, quat = cantilever.hand_pose(0)
    np.testing.assert_allclose(pos, [0.18, 0.0, 0.02], atol=1e-12)
    np.testing.assert_allclose(quat, [1, 0, 0, 0], atol=1e-12)
    turn = [np.cos(np.pi / 8), 0.0, np.sin(np.pi / 8), 0.0]  # 45° about y
    cantilever.move_hand(0, orientation=turn, duration=0.1)
    np.testing.assert_allclose(cantilever.hand_pose(0)[1], turn, atol=1e-9)
    load = cantilever.hand_load(0)
    assert load.hose == "beam" and load.kind in ("push", "pull")
    assert load.ratio >= 0 and load.limit > 0
    np.testing.assert_allclose(load.force, cantilever.hand_force(0))
    np.testing.assert_allclose(load.torque, cantilever.hand_torque(0))


def test_release_frees_the_nodes(cantilever):
    cantilever.grab(1, hose="beam", node=-1)
    cantilever.step()
    assert cantilever.held("beam")[-1]
    cantilever.release(1)
    cantilever.step()
    assert cantilever.hands == [] and not cantilever.held("beam")[-1]
    with pytest.raises(ValueError, match="hand 1 holds nothing"):
        cantilever.hand_force(1)
    with pytest.raises(ValueError, match="hand 1 holds nothing"):
        cantilever.release(1)


def test_hand_arguments_are_checked(cantilever):
    with pytest.raises(ValueError, match="either a point `at` or both"):
        cantilever.grab(0)
    with pytest.raises(ValueError, match="either a point `at` or both"):
        cantilever.grab(0, at=[0, 0, 0], hose="beam", node=0)
    cantilever.grab(0, hose="beam", node=-1)
    with pytest.raises(ValueError, match="hand 0 holds this node"):
        cantilever.fix("beam", -1)
    with pytest.raises(ValueError, match="not both"):
        cantilever.move_hand(0, by=[0, 0, 0.01], duration=0.1, speed=0.1)
    with pytest.raises(ValueError, match="quaternion"):
        cantilever.move_hand(0, orientation=[1, 0, 0])
    with pytest.raises(ValueError, match="still moving"):
        cantilever.move_hand(0, by=[0, 0, 0.01], duration=0.1, wait=False)
        cantilever.settle()
    with pytest.raises(OverflowError):
        cantilever.grab(-1, at=[0, 0, 0])


def test_demo_hand_pushes_the_hose_onto_its_stub_in_a_simulation():
    """The interactive API reproduces the demo's first hand moves: the stub reacts."""
    scene = pliant.demo_scene()
    sim = pliant.Simulation(scene)
    grab, *moves = [a for a in scene.timeline if "Grab" in a or "MoveHand" in a][:3]
    sim.grab(0, at=grab["Grab"]["at"])
    for m in moves:
        m = m["MoveHand"]
        path = m["path"]["To"] if "To" in m["path"] else None
        by = m["path"]["By"] if "By" in m["path"] else None
        rotate = None
        if m["rotation"]:
            rotate = np.asarray(m["rotation"]["axis"]) * m["rotation"]["angle"]
        sim.move_hand(0, to=path, by=by, rotate=rotate, duration=m["duration"])
    stub = [f for f in sim.fasteners() if f["kind"] == "stub"][0]
    assert stub["max_force"] > 0
