"""SPEC W1: Python drives the same workcell as `pliant run` — the same inputs through
`Simulation` and through a scene timeline (`run_timeline`) give the same numbers bit for
bit, for each solver; and the workcell's grab rules hold in Python."""

import numpy as np
import pytest

import pliant
from conftest import cantilever_dict

STEPS = [40, 60, 30]


def scene_with(timeline_tail):
    d = cantilever_dict(length=0.3, elements=12)
    d["timeline"] += timeline_tail
    return pliant.Scene.from_dict(d)


@pytest.mark.parametrize("solver", ["explicit", "implicit", "static"])
def test_simulation_and_timeline_agree_bit_for_bit(solver):
    tip = [0.3, 0.0, 0.0]
    probe = pliant.Simulation(scene_with([]), solver=solver)
    dt = probe.time_step
    tail = [
        {"action": "grab", "hand": 0, "at": tip},
        {"action": "run", "duration_s": STEPS[0] * dt},
        {"action": "aim_hand", "hand": 0, "position": [0.28, 0.02, 0.05]},
        {"action": "run", "duration_s": STEPS[1] * dt},
        {"action": "release_hand", "hand": 0},
        {"action": "run", "duration_s": STEPS[2] * dt},
    ]
    result = pliant.run_timeline(scene_with(tail), solver=solver)

    sim = pliant.Simulation(scene_with([]), solver=solver)
    sim.grab(0, tip)
    sim.step(STEPS[0])
    sim.aim_hand(0, [0.28, 0.02, 0.05])
    sim.step(STEPS[1])
    sim.release(0)
    sim.step(STEPS[2])

    assert sim.step_count == sum(STEPS)
    final = result.positions("beam")[-1]
    assert np.array_equal(final, sim.positions("beam")), (
        f"{solver}: largest difference {np.abs(final - sim.positions('beam')).max()} m"
    )
    assert result.times[-1] == sim.time


def test_a_grab_of_a_held_beam_is_refused_and_the_hand_keeps_its_grip(cantilever):
    cantilever.grab(0, [0.2, 0.0, 0.0])
    cantilever.grab(1, [0.1, 0.0, 0.0])
    before = cantilever.hand_pose(1)
    with pytest.raises(ValueError, match="hand 0 already holds"):
        cantilever.grab(1, [0.2, 0.0, 0.0])
    assert cantilever.hands == [0, 1]
    assert np.array_equal(cantilever.hand_pose(1)[0], before[0])
