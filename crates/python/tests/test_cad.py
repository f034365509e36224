"""STEP import (pliant.cad): the converter on real files from several CAD writers
(``data/cad`` in the repository), its GLB, its errors and curves."""

import json
import os
import struct
from pathlib import Path

import pytest

from conftest import REPO
from pliant.cad import StepError, check_part21, convert, extract_curve

CAD = Path(os.environ.get("PLIANT_CAD_FILES", REPO / "data" / "cad"))
ROUTE = REPO / "crates" / "runs" / "tests" / "data" / "cad" / "route.step"


def cad(name):
    path = CAD / name
    assert path.is_file(), "missing real STEP file %s (data/cad in the repository, or PLIANT_CAD_FILES)" % path
    return str(path)


def glb_json(path):
    data = Path(path).read_bytes()
    magic, version, total = struct.unpack("<III", data[:12])
    assert magic == 0x46546C67 and version == 2 and total == len(data)
    n, kind = struct.unpack("<II", data[12:20])
    assert kind == 0x4E4F534A
    return json.loads(data[20:20 + n])


def test_assembly_keeps_solids_names_and_metres(tmp_path):
    out = tmp_path / "as1.glb"
    summary = convert(cad("as1-oc-214.stp"), str(out), 0.5e-3)
    assert summary["solids"] == 18 and summary["distinct_solids"] == 5
    assert summary["skipped"] == []
    doc = glb_json(out)
    names = [n["name"] for n in doc["nodes"]]
    assert "as1/plate_1" in names and len(set(names)) == 18
    lo = [min(a["min"][k] for a in doc["accessors"] if "min" in a) for k in range(3)]
    hi = [max(a["max"][k] for a in doc["accessors"] if "max" in a) for k in range(3)]
    assert abs((hi[0] - lo[0]) - 0.2) < 1e-4  # 200 mm, in metres
    assert doc["asset"]["extras"]["pliant"]["triangles"] == summary["triangles"]


def test_tolerance_sets_the_triangle_count(tmp_path):
    coarse = convert(cad("lower_leg_structure_fork.STEP"), str(tmp_path / "a.glb"), 1e-3)
    fine = convert(cad("lower_leg_structure_fork.STEP"), str(tmp_path / "b.glb"), 0.02e-3)
    assert fine["triangles"] > 2 * coarse["triangles"]


def test_truncated_file_names_the_entity(tmp_path):
    data = Path(cad("sg1-c5-214.stp")).read_bytes()
    cut = tmp_path / "cut.stp"
    cut.write_bytes(data[: len(data) // 2])
    with pytest.raises(StepError, match=r"truncated.*#\d+ = [A-Z_]+ \(line \d+\)"):
        convert(str(cut), str(tmp_path / "cut.glb"))
    with pytest.raises(StepError, match=r"no solid could be read.*PRODUCT_DEFINITION"):
        convert(str(ROUTE), str(tmp_path / "route.glb"))
    with pytest.raises(StepError, match="not a STEP file"):
        check_part21(b"solid x\nendsolid\n")


def test_curves_by_name_and_index():
    helix = extract_curve(str(ROUTE), name="hose_route", tolerance=1e-5)
    assert helix["curves"] == ["hose_route", "guide"]
    assert abs(helix["points"][0][0] - 0.1) < 1e-9 and len(helix["points"]) > 50
    guide = extract_curve(str(ROUTE), index=1)
    assert len(guide["points"]) == 4
    with pytest.raises(StepError, match="no curve named 'x'"):
        extract_curve(str(ROUTE), name="x")
    with pytest.raises(StepError, match="out of range"):
        extract_curve(str(ROUTE), index=5)
