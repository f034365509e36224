"""Parts moved from a script (`Simulation.move_part`, `rotate_part`): a hose end mounted on
a turned part goes with it (the closed form of the turn), the script's moves give the
same numbers bit for bit as the same moves in a timeline, and bad moves raise
ValueError with the reason."""

import math

import numpy as np
import pytest

import pliant
from conftest import EXAMPLES, cantilever_dict

PIN = [0.5, 0.0, 0.0]


def door_scene(tail=(), movable=True):
    d = cantilever_dict(length=0.3, elements=12, gravity=(0.0, 0.0, 0.0))
    door = {"name": "door", "box": {"size": [0.02, 0.02, 0.02]}, "position": [0.32, 0.0, -0.04]}
    if movable:
        door["movable"] = True
    d["parts"] = [door]
    d["timeline"] += [{"action": "mount", "hose": "beam", "node": -1, "part": "door"}]
    d["timeline"] += list(tail)
    return pliant.Scene.from_dict(d)


@pytest.mark.parametrize("solver", ["explicit", "implicit", "static"])
def test_a_turned_part_carries_the_mounted_end(solver):
    sim = pliant.Simulation(door_scene(), solver=solver)
    sim.rotate_part("door", [0, 0, 1], point=PIN, to=math.radians(60), duration=0.5)
    end = sim.positions("beam")[-1]
    turn = math.radians(60)
    expected = np.array(PIN) + np.array([-0.2 * math.cos(turn), -0.2 * math.sin(turn), 0.0])
    assert np.allclose(end, expected, atol=1e-9), (end, expected)
    t, q = sim.part_pose("door")
    assert abs(q[0] - math.cos(turn / 2)) < 1e-12 and abs(q[3] - math.sin(turn / 2)) < 1e-12
    sim.move_part("door", by=[0, 0, 0.01], duration=0.1)
    assert abs(sim.positions("beam")[-1][2] - 0.01) < 1e-9


@pytest.mark.parametrize("solver", ["explicit", "static"])
def test_script_and_timeline_moves_agree_bit_for_bit(solver):
    tail = [
        {"action": "rotate_part", "part": "door", "axis": [0, 0, 1], "point": PIN,
         "by_deg": 30.0, "duration_s": 0.2},
        {"action": "move_part", "part": "door", "by": [0, 0.01, 0], "duration_s": 0.1},
        {"action": "run", "duration_s": 0.05},
    ]
    result = pliant.run_timeline(door_scene(tail), solver=solver)
    sim = pliant.Simulation(door_scene(), solver=solver)
    sim.rotate_part("door", [0, 0, 1], point=PIN, by=math.radians(30.0), duration=0.2)
    sim.move_part("door", by=[0, 0.01, 0], duration=0.1)
    sim.run(0.05)
    assert np.array_equal(sim.positions("beam"), result.positions("beam")[-1])


def test_bad_part_moves_raise_with_the_reason():
    sim = pliant.Simulation(door_scene())
    with pytest.raises(ValueError, match=r'no part named "lid" \(parts: door\)'):
        sim.move_part("lid", by=[0, 0, 0.01])
    with pytest.raises(ValueError, match="not both"):
        sim.move_part("door", [0, 0, 0.01], by=[0, 0, 0.01])
    with pytest.raises(ValueError, match="must be finite"):
        sim.move_part("door", by=[0, 0, float("nan")])
    with pytest.raises(ValueError, match="a part does not jump"):
        sim.move_part("door", by=[0, 0, 0.01], duration=0.0)
    with pytest.raises(ValueError, match="axis must not be zero"):
        sim.rotate_part("door", [0, 0, 0], by=1.0)
    still = pliant.Simulation(door_scene(movable=False))
    with pytest.raises(ValueError, match="movable = true"):
        still.rotate_part("door", [0, 0, 1], by=1.0)


def test_a_sweep_gives_its_motion_table():
    """The door-hinge example's range of motion as columns: the angle runs 0 → 70° → 0,
    and the hose's bend radius ratio passes 1 where the door is open."""
    example = EXAMPLES / "door_hinge.toml"
    result = pliant.run_timeline(pliant.load_scene(example))
    table = result.motion()
    angle = table["angle_deg"]
    assert abs(angle.max() - 70.0) < 1e-6 and abs(angle[-1]) < 1e-6
    ratio = table["door hose: bend_radius_ratio"]
    assert len(ratio) == len(angle) == len(table["time_s"])
    assert ratio[angle.argmax()] > 1.0 > ratio[0]
    assert "clearance_m door hose to pillar" in table
    plain = pliant.run_timeline(door_scene())
    assert plain.motion() is None
