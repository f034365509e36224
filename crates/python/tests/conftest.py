"""Shared fixtures: a cantilever scene built in code, a worker's held-hose scene, a
calibrated material in a scene, the repository's paths and the `pliant` binary (for
comparing with the command line)."""

import math
import os
import pathlib
import shutil

import pytest

import pliant

REPO = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "examples"

# A user material with an explicit bending modulus, so EI is known exactly.
E_BENDING = 12.0e6  # Pa
DENSITY = 1000.0  # kg/m^3
D_OUTER, D_INNER = 0.016, 0.010  # m
AREA = math.pi / 4 * (D_OUTER**2 - D_INNER**2)
SECOND_MOMENT = math.pi / 64 * (D_OUTER**4 - D_INNER**4)
EI = E_BENDING * SECOND_MOMENT
G = 9.81

HELD_HOSE_SCENE = """
format = "pliant-scene"
version = 1
length_unit = "mm"

[simulation]
solver = "static"

{extra}

[[hoses]]
name = "h"
material = "hose3"
elements = 10
start = [100, -200, {z}]
path = [{{ line = {{ to = [500, -200, {z}] }} }}]

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "grab"
hand = 0
at = [500, -200, {z}]

[[timeline]]
action = "move_hand"
hand = 0
by = [0, 0, -20]
duration_s = 0.3
"""


def held_hose_scene(extra="", z=1900.0):
    """A worker's scene (mm, the static solver): ``extra`` (a ``[worker]``, parts), then a
    400 mm hose "h" of library hose 3 along x at height ``z`` mm, fixed at its start, its
    end grabbed by hand 0 and lowered 20 mm in 0.3 s."""
    return HELD_HOSE_SCENE.format(extra=extra, z=z)


def calibrated_material_scene(material_toml, material):
    """A scene (mm) of a calibration's ``material_toml`` and a 200 mm hose "h" of 4
    elements in ``material`` with a 10/16 mm tube section: whether the written material
    loads in a scene."""
    return pliant.Scene.from_toml(
        'format = "pliant-scene"\nversion = 1\nlength_unit = "mm"\n'
        + material_toml
        + f'\n[[hoses]]\nname = "h"\nmaterial = "{material}"\n'
        "section = { d_inner = 10, d_outer = 16 }\nelements = 4\nstart = [0, 0, 0]\n"
        "path = [{ line = { to = [200, 0, 0] } }]\n"
    )


def cantilever_dict(length=0.2, elements=20, gravity=(0.0, 0.0, -G), fixed=True):
    """A straight hose along +x from the origin, clamped at node 0 (SI units)."""
    scene = {
        "format": "pliant-scene",
        "version": 1,
        "name": "cantilever",
        "length_unit": "m",
        "simulation": {"gravity": list(gravity), "damping_mass_per_s": 5.0},
        "materials": {
            "test_rubber": {
                "e_tension_mpa": 20.0,
                "e_compression_mpa": 20.0,
                "e_bending_mpa": E_BENDING / 1e6,
                "poisson": 0.45,
                "density_kg_m3": DENSITY,
            }
        },
        "hoses": [
            {
                "name": "beam",
                "material": "test_rubber",
                "section": {"d_inner": D_INNER, "d_outer": D_OUTER},
                "elements": elements,
                "start": [0.0, 0.0, 0.0],
                "path": [{"line": {"to": [length, 0.0, 0.0]}}],
                "normal_hint": [0.0, 0.0, 1.0],
            }
        ],
        "timeline": [],
    }
    if fixed:
        scene["timeline"].append({"action": "fix", "hose": "beam", "node": 0})
    return scene


@pytest.fixture
def cantilever():
    """A Simulation of the clamped cantilever under gravity, at rest in its rest shape."""
    return pliant.Simulation(pliant.Scene.from_dict(cantilever_dict()))


@pytest.fixture
def pliant_bin():
    """The `pliant` command: $PLIANT_BIN, else target*/release/pliant of the repository.
    Fails (does not skip) if $PLIANT_BIN is set but missing."""
    given = os.environ.get("PLIANT_BIN")
    if given:
        assert pathlib.Path(given).is_file(), f"PLIANT_BIN={given} does not exist"
        return given
    for target in [os.environ.get("CARGO_TARGET_DIR"), REPO / "target"]:
        if target:
            candidate = pathlib.Path(target) / "release" / "pliant"
            if candidate.is_file():
                return str(candidate)
    found = shutil.which("pliant")
    if found:
        return found
    pytest.skip("the pliant binary is not built (cargo build --release -p pliant)")
