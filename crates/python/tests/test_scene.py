"""Loading scenes: the demo, files, TOML/JSON/dict text, and clear SceneErrors."""

import json
import subprocess

import numpy as np
import pytest

import pliant
from conftest import EXAMPLES, cantilever_dict


def test_demo_scene_loads():
    scene = pliant.demo_scene()
    assert scene.name == "Engine bay with rigid parts"
    assert scene.hose_names == ["upper", "lower"]
    assert scene.node_count("lower") == scene.node_count(1) == scene.node_count(-1)
    assert scene.stub_names == ["water pump inlet"]
    assert len(scene.clip_names) == 2
    assert scene.time_step > 0
    assert scene.timeline[0]["Fix"]["node"] == {"hose": 0, "node": 0}


def test_load_scene_file_equals_text():
    path = EXAMPLES / "demo.toml"
    a = pliant.load_scene(path)
    b = pliant.Scene.from_toml(path.read_text(), origin=str(path))
    assert a.hose_names == b.hose_names == ["coolant"]
    assert a.node_count("coolant") == b.node_count("coolant")
    assert a.time_step == b.time_step


def test_dict_and_json_give_the_same_scene():
    d = cantilever_dict()
    a = pliant.Scene.from_dict(d)
    b = pliant.Scene.from_json(json.dumps(d))
    assert a.hoses == b.hoses
    assert a.time_step == b.time_step
    assert a.hoses[0]["nodes"] == 21


def test_dict_accepts_numpy_values():
    d = cantilever_dict()
    d["hoses"][0]["start"] = np.zeros(3)
    d["hoses"][0]["elements"] = np.int64(10)
    assert pliant.Scene.from_dict(d).node_count("beam") == 11


def test_bad_value_names_the_field_value_and_reason():
    d = cantilever_dict()
    d["hoses"][0]["section"]["d_inner"] = 0.02  # larger than d_outer
    with pytest.raises(pliant.SceneError) as err:
        pliant.Scene.from_dict(d)
    e = err.value
    assert isinstance(e, ValueError)
    assert e.field == "hoses[0].section.d_inner"
    assert "d_inner" in str(e) and "d_outer" in str(e)
    assert str(e).startswith("<dict>: hoses[0].section.d_inner = ")


def test_unknown_field_is_named_with_its_location():
    text = (EXAMPLES / "demo.toml").read_text().replace("normal_hint", "normal_hnit")
    with pytest.raises(pliant.SceneError) as err:
        pliant.Scene.from_toml(text, origin="demo.toml")
    assert err.value.field == "hoses[0].normal_hnit"
    assert err.value.location is not None
    assert "unknown field" in str(err.value)


def test_nan_in_a_dict_is_refused():
    d = cantilever_dict()
    d["hoses"][0]["start"] = [float("nan"), 0, 0]
    with pytest.raises(pliant.SceneError, match="<dict>"):
        pliant.Scene.from_dict(d)


def test_missing_file_is_a_scene_error():
    with pytest.raises(pliant.SceneError, match="/nonexistent/scene.toml: cannot read"):
        pliant.load_scene("/nonexistent/scene.toml")


def test_message_is_the_one_the_cli_prints(tmp_path, pliant_bin):
    bad = tmp_path / "bad.toml"
    bad.write_text((EXAMPLES / "thesis_1.toml").read_text().replace("d_inner = 30", "d_inner = 45"))
    with pytest.raises(pliant.SceneError) as err:
        pliant.load_scene(bad)
    cli = subprocess.run(
        [pliant_bin, "run", "--quiet", str(bad), "--out", str(tmp_path / "o")],
        capture_output=True,
        text=True,
    )
    assert cli.returncode == 2
    assert cli.stderr.strip() == f"error: {err.value}"
