"""Studies that vary a motion's range (SPEC K2, docs/study.md `vary = "motion"`): a grid
over the door's opening angle, whose worst bend radius over the motion each run reports
as study columns, checked against a single run of each scene written out by hand."""
import math

import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

import pliant  # noqa: E402
from pliant.studies import StudyError, load_study, variant_scene  # noqa: E402
from conftest import EXAMPLES  # noqa: E402

DOOR = EXAMPLES / "door_hinge.toml"
ANGLES = [40.0, 55.0, 70.0]  # degrees: the door opened this far (the example: 70)


def door_study(**change):
    parameter = {"name": "opening", "vary": "motion", "part": "door", "property": "range",
                 "apply": "set", "distribution": "uniform", "min": 30, "max": 80, "levels": ANGLES}
    parameter.update(change)
    return {"format": "pliant-study", "version": 1, "name": "door opening", "scene": str(DOOR),
            "length_unit": "mm", "sampling": {"method": "grid"}, "parameters": [parameter]}


def test_a_motion_range_sets_the_hinge_keyframes_and_its_speed_scales_their_times():
    study = load_study(door_study())
    scene = variant_scene(study, {"opening": math.radians(55.0)})
    angle = next(p for p in scene["parts"] if p["name"] == "door")["motion"]["angle_deg"]
    assert angle["values"] == pytest.approx([0, 55, 55, 0], abs=1e-12)
    assert angle["times_s"] == [0.2, 2.2, 2.6, 4.6]
    faster = load_study(door_study(property="speed", apply="scale", min=0.5, max=2, levels=[2]))
    scene = variant_scene(faster, {"opening": 2.0})
    angle = next(p for p in scene["parts"] if p["name"] == "door")["motion"]["angle_deg"]
    assert angle["times_s"] == pytest.approx([0.1, 1.1, 1.3, 2.3])
    assert angle["values"] == [0, 70, 70, 0]


@pytest.mark.parametrize("change, field, message", [
    ({"property": "size"}, "parameters[0].property", "must be one of range, speed"),
    ({"part": "pillar"}, "parameters[0].part", "has no hinge, slide or periodic"),
    ({"part": "boot"}, "parameters[0].part", "no such part"),
    ({"property": "speed"}, "parameters[0].apply", "its speed is scaled"),
])
def test_motion_parameter_errors_name_the_field(change, field, message):
    with pytest.raises(StudyError) as e:
        load_study(door_study(**change))
    assert f": {field} = " in str(e.value) and message in str(e.value), str(e.value)


def smallest_bend_by_hand(angle_deg, tmp_path):
    """The door example opened to `angle_deg`, written as text and run once: its smallest
    bend radius over the motion [m] and the door angle there [deg]."""
    text = DOOR.read_text()
    keyframes = "values = [0, 70, 70, 0]"
    assert text.count(keyframes) == 1
    path = tmp_path / f"door_{angle_deg:g}.toml"
    path.write_text(text.replace(keyframes, f"values = [0, {angle_deg!r}, {angle_deg!r}, 0]"))
    table = pliant.run_timeline(pliant.load_scene(str(path))).motion()
    radius = np.asarray(table["door hose: min_bend_radius_m"])
    worst = int(np.nanargmin(radius))
    return float(radius[worst]), float(np.asarray(table["angle_deg"])[worst])


def test_a_grid_over_the_door_angle_reports_the_worst_bend_of_each_run(tmp_path):
    from distributed import Client

    from pliant.studies.cluster import local_cluster

    cluster = local_cluster(1)
    client = Client(cluster)
    try:
        result = pliant.study(door_study(), str(tmp_path / "out"), client=client, progress=False)
    finally:
        client.close()
        cluster.close()
    frame = result.frame.sort_values("p_opening")
    assert list(frame["status"]) == ["ok"] * 3, list(frame["message"])
    assert np.degrees(frame["p_opening"].to_numpy()) == pytest.approx(ANGLES, abs=1e-9)
    assert set(frame["motion_coordinate"]) == {"angle_rad"}
    radii = frame["motion_min_bend_radius_m"].to_numpy()
    print("door opened to", ANGLES, "deg: smallest bend radius", np.round(1e3 * radii, 2), "mm at",
          np.round(np.degrees(frame["motion_worst_position"].to_numpy()), 2), "deg")
    # the wider the door opens, the tighter the hose bends behind its clip
    assert radii[0] > radii[1] > radii[2], radii
    for (_, row), angle in zip(frame.iterrows(), ANGLES):
        radius, at = smallest_bend_by_hand(angle, tmp_path)
        assert row["motion_min_bend_radius_m"] == pytest.approx(radius, rel=1e-9), angle
        assert math.degrees(row["motion_worst_position"]) == pytest.approx(at, abs=1e-9), angle
