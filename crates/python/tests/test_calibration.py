"""Material calibration from Python (docs/calibration.md): the example's known answers,
one test from a CSV or from arrays, synthetic curves with noise, and clear errors."""

import json

import numpy as np
import pytest

import pliant
from conftest import EXAMPLES, calibrated_material_scene

# The example's truth (crates/calibrate/src/synthetic.rs, Truth::EXAMPLE)
D_I, D_A = 0.010, 0.016
I = np.pi / 64 * (D_A**4 - D_I**4)
TRUTH = {
    "tension": 11.583e6,
    "compression": 13.1363e6,
    "three_point_bending": 12.0e6 * I,
    "torsion": 12.0e6 / 2.9 * 2 * I,
    "iso10619": 12.0e6 * I,
}


def test_the_example_recovers_its_known_stiffness(tmp_path):
    c = pliant.calibrate(EXAMPLES / "calibration" / "hose.toml")
    assert [f.kind for f in c.fits] == list(TRUTH)
    for f in c.fits:
        truth = TRUTH[f.kind]
        assert abs(f.value - truth) / truth < 0.01, f
        lo, hi = f.ci95
        assert lo < f.value < hi
        assert f.range["last_row"] > f.range["first_row"] >= 0
        assert f.x.shape == f.y.shape == (f.range["total_points"],)
        assert 0.999 < f.r_squared <= 1.0
    m = c.material
    assert m["name"] == "calibrated_hose"
    assert abs(m["e_tension_mpa"]["value"] - 11.583) < 0.1
    assert "tension.csv" in m["e_tension_mpa"]["source"]
    assert abs(m["poisson"]["value"] - 0.45) < 0.02
    paths = c.write(tmp_path / "cal")
    assert sorted(p.split("/")[-1] for p in paths) == [
        "calibration.html",
        "calibration.json",
        "library_entry.toml",
        "material.toml",
    ]
    assert json.loads((tmp_path / "cal" / "calibration.json").read_text()) == c.to_dict()
    assert c.html.count("<svg") == 10


def test_the_material_loads_in_a_scene():
    c = pliant.calibrate(EXAMPLES / "calibration" / "hose.toml")
    scene = calibrated_material_scene(c.material_toml, "calibrated_hose")
    assert scene.hose_names == ["h"]


def test_one_test_from_a_csv_or_from_arrays_agree():
    csv = EXAMPLES / "calibration" / "torsion.csv"
    a = pliant.calibrate(kind="torsion", csv=csv, length_mm=300, d_outer_mm=16, d_inner_mm=10)
    rows = np.loadtxt(csv, delimiter=",", skiprows=1)
    b = pliant.calibrate(
        kind="torsion",
        data={"angle_deg": rows[:, 0], "torque_Nm": rows[:, 1]},
        length_mm=300,
        d_outer_mm=16,
        d_inner_mm=10,
    )
    assert a.fits[0].value == pytest.approx(b.fits[0].value, rel=1e-9)
    assert a.fits[0].range["last_row"] == b.fits[0].range["last_row"]
    assert abs(a.fits[0].value - TRUTH["torsion"]) / TRUTH["torsion"] < 0.01


def synthetic_bending(ei, span, seed, noise=0.002, n=120):
    """Three-point bending: toe, linear range to 60 % of the deflection, softening tail,
    Gaussian noise (numpy's seeded generator). Returns deflection [m], force [N] and the
    index of the linear range's last point."""
    k = 48 * ei / span**3
    d_max = 0.03
    x = d_max * (np.arange(n) + 0.5) / n
    xt, xe = 0.05 * d_max, 0.6 * d_max
    c = 0.5 * k * 0.7 / (d_max - xe)
    y = np.where(x < xt, k * x**2 / (2 * xt), k * (x - xt / 2))
    y = np.where(x > xe, y - c * (x - xe) ** 2, y)
    rng = np.random.default_rng(seed)
    y = y + noise * y.max() * rng.standard_normal(n)
    return x, y, int(np.nonzero(x <= xe)[0][-1])


def test_synthetic_bending_curves_with_noise():
    ei, span = 0.05, 0.25
    covered, worst = 0, 0.0
    seeds = 40
    for seed in range(seeds):
        x, y, last = synthetic_bending(ei, span, seed)
        c = pliant.calibrate(
            kind="three_point_bending",
            data={"deflection_m": x, "force_N": y},
            length_mm=span * 1e3,
            d_outer_mm=12,
        )
        f = c.fits[0]
        worst = max(worst, abs(f.value - ei) / ei)
        covered += f.ci95[0] <= ei <= f.ci95[1]
        assert abs(f.range["last_row"] - last) <= 8, (seed, f.range, last)
    assert worst < 0.01
    assert covered >= 0.8 * seeds, covered


def test_errors_name_the_file_line_and_column(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("force_N,deflection_mm\n0,0\n1,oops\n")
    with pytest.raises(pliant.CalibrationError) as e:
        pliant.calibrate(kind="cantilever", csv=bad, length_mm=100, d_outer_mm=10)
    assert (e.value.line, e.value.column) == (3, 2)
    assert e.value.file.endswith("bad.csv")
    assert "not a number" in str(e.value)
    with pytest.raises(pliant.CalibrationError, match="too few points"):
        pliant.calibrate(
            kind="tension", data={"strain": [0, 0.1, 0.2], "stress_MPa": [0, 1, 2]}, d_outer_mm=10
        )
    with pytest.raises(pliant.CalibrationError, match="not monotonic"):
        pliant.calibrate(
            kind="tension",
            data={"strain": [0, 0.1, 0.2, 0.15, 0.3, 0.4, 0.5], "stress_MPa": range(7)},
            d_outer_mm=10,
        )
    with pytest.raises(ValueError, match="expected one of"):
        pliant.calibrate(kind="bend", data={"strain": [0]}, d_outer_mm=10)
    assert issubclass(pliant.CalibrationError, ValueError)
