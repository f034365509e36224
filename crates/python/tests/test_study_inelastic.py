"""Studies over a metal line that yields (SPEC X1, T1; docs/study.md `property =
"yield_stress_mpa"`): the library steel brake line bent past yield by an end moment and
let go. A grid over its yield stress gives rows whose bend differs — the weaker the
steel, the tighter it bends under the same moment — each row equal to a run of the same
scene written by hand, and the runs keep permanent sets that differ the same way."""
import math

import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

import pliant  # noqa: E402
from pliant.studies import load_study, variant_scene  # noqa: E402

# The library's steel_tube (E = 210 GPa, σ_y = 170 MPa, H = 480 MPa, 4.75 × 0.7 mm):
# first yield at M_e = 1.35 N·m, fully plastic at M_p = 1.97 N·m. The end moment 1.9 N·m
# is past yield for σ_y below 246 MPa, elastic above.
SCENE = """
format = "pliant-scene"
version = 1
name = "steel line bent past yield by an end moment"
length_unit = "mm"

[simulation]
solver = "static"
gravity = [0, 0, 0]
{materials}
[[hoses]]
name = "line"
material = "{material}"
elements = 10
start = [0, 0, 0]
path = [{{ line = {{ to = [100, 0, 0] }} }}]

[[timeline]]
action = "fix"
hose = "line"
node = 0

[[timeline]]
action = "load"
hose = "line"
node = -1
moment_nm = [0, 1.9, 0]
ramp_s = 0.3
name = "bend"

[[timeline]]
action = "run"
duration_s = 0.3

[[timeline]]
action = "unload"
hose = "line"
node = -1
name = "bend"

[[timeline]]
action = "run"
duration_s = 0.1
"""
YIELD_MPA = [140.0, 170.0, 250.0]


def library_scene():
    return SCENE.format(materials="", material="steel_tube")


def scene_by_hand(yield_mpa):
    """The scene with the steel line's own material table, written out (the library's
    values and section) with yield stress `yield_mpa`."""
    materials = f"""
[materials.steel]
e_tension_mpa = 210000.0
e_compression_mpa = 210000.0
poisson = 0.3
density_kg_m3 = 7850.0
min_bend_radius_mm = 14.25
yield_stress_mpa = {yield_mpa!r}
hardening_modulus_mpa = 480.0
"""
    text = SCENE.format(materials=materials, material="steel")
    return text.replace('elements = 10', 'elements = 10\nsection = { d_inner = 3.35, d_outer = 4.75 }')


def yield_study(scene_path, **change):
    parameter = {"name": "yield", "vary": "material", "material": "steel_tube",
                 "property": "yield_stress_mpa", "apply": "set", "distribution": "uniform",
                 "min": 100, "max": 300, "levels": YIELD_MPA}
    parameter.update(change)
    return {"format": "pliant-study", "version": 1, "name": "steel yield", "scene": str(scene_path),
            "length_unit": "mm", "sampling": {"method": "grid"}, "parameters": [parameter]}


@pytest.fixture(scope="module")
def scene_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "steel_line.toml"
    path.write_text(library_scene())
    return path


def test_a_library_metal_keeps_its_yield_law_when_a_study_varies_it(scene_path):
    # scaling E of the library steel copies the entry with its yield law, not without it
    stiffer = load_study(yield_study(scene_path, name="e", property="e_mpa", apply="scale",
                                     min=0.9, max=1.1, levels=[1.1]))
    scene = variant_scene(stiffer, {"e": 1.1})
    steel = scene["materials"]["steel_tube_study"]
    assert steel["yield_stress_mpa"] == 170.0 and steel["hardening_modulus_mpa"] == 480.0
    assert steel["e_tension_mpa"] == pytest.approx(1.1 * 210000.0, rel=1e-15)
    assert scene["hoses"][0]["material"] == "steel_tube_study"
    assert scene["hoses"][0]["section"] == {"d_inner": 3.35, "d_outer": 4.75}
    # the yield stress is set in MPa, recorded in Pa
    weaker = variant_scene(load_study(yield_study(scene_path)), {"yield": 140e6})
    assert weaker["materials"]["steel_tube_study"]["yield_stress_mpa"] == pytest.approx(140.0, rel=1e-15)
    assert weaker["materials"]["steel_tube_study"]["e_tension_mpa"] == 210000.0


def end_rotation(result):
    """The line's end tangent angle from +x at the last recorded instant [rad]."""
    p = np.asarray(result.positions("line"))[-1]
    d = p[-1] - p[-2]
    return math.atan2(-d[2], d[0])


def test_a_grid_over_the_yield_stress_gives_the_rows_of_direct_runs(scene_path, tmp_path):
    from distributed import Client

    from pliant.studies.cluster import local_cluster

    cluster = local_cluster(1)
    client = Client(cluster)
    try:
        result = pliant.study(yield_study(scene_path), str(tmp_path / "out"), client=client, progress=False)
    finally:
        client.close()
        cluster.close()
    frame = result.frame.sort_values("p_yield")
    assert list(frame["status"]) == ["ok"] * 3, list(frame["message"])
    assert frame["p_yield"].to_numpy() == pytest.approx(np.array(YIELD_MPA) * 1e6, rel=1e-15)
    assert (frame["unconverged_steps"] == 0).all()
    ratios = frame["min_bend_radius_ratio"].to_numpy()
    sets = []
    for (_, row), sy in zip(frame.iterrows(), YIELD_MPA):
        path = tmp_path / f"steel_{sy:g}.toml"
        path.write_text(scene_by_hand(sy))
        direct = pliant.run_timeline(pliant.load_scene(str(path)))
        profiles = direct.check_profiles
        ratio = min(p["min_bend_radius"] / p["allowed_bend_radius"] for p in profiles)
        assert row["min_bend_radius_ratio"] == pytest.approx(ratio, rel=1e-12), sy
        assert row["violated_checks"].tolist() == sorted({v["check"] for v in direct.violations}), sy
        assert row["feasible"] is None or row["feasible"] == direct.feasible
        # the study's own run of this row, replayed, keeps the same set as the direct one
        again = pliant.run_timeline(pliant.load_scene(result.replay_scene(row["run_id"])))
        assert end_rotation(again) == pytest.approx(end_rotation(direct), rel=1e-12, abs=1e-15), sy
        sets.append(end_rotation(direct))
    print("yield stress", YIELD_MPA, "MPa: smallest bend radius / allowed", np.round(ratios, 4),
          "end rotation kept after release", np.round(np.degrees(sets), 4), "deg")
    # the weaker the steel, the tighter the same moment bends it, and the more it keeps
    assert ratios[0] < ratios[1] < ratios[2], ratios
    assert sets[0] > sets[1] > 0.0, sets
    # σ_y = 250 MPa stays elastic under 1.9 N·m (M_e = 1.98 N·m): it springs straight
    assert abs(sets[2]) < 1e-9, sets
