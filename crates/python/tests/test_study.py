"""Studies (SPEC T1, T2): the study format's errors, sampling, variants, and a small study
on a local Dask cluster — Parquet rows, report, a diverged run kept, resume, envelope."""

import json
import math
import os
import shutil
import subprocess
import sys
import tomllib

import numpy as np
import pytest

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

import pliant  # noqa: E402
from pliant.studies import StudyError, load_study, samples, variant_scene  # noqa: E402
from pliant.studies import envelope, geometry, runner, variant  # noqa: E402
from pliant.studies.sampling import unit_samples  # noqa: E402

from conftest import EXAMPLES  # noqa: E402

# A short hose clamped at one end, above a block: a hand pulls its free end along the
# hose and lets go. How far it pulls (EA·Δ/L) decides the hand force against its limit.
SCENE = """
format = "pliant-scene"
version = 1
name = "small study scene"
length_unit = "mm"

[[parts]]
name = "block"
box = { size = [100, 100, 100] }
position = [150, 0, -80]

[[hoses]]
name = "h"
material = "hose1"
elements = 8
start = [0, 0, 0]
path = [{ line = { to = [250, 0, 0] } }]

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "load"
hose = "h"
node = 4
force_n = [0, 0, -0.5]

[[timeline]]
action = "grab"
hand = 0
at = [250, 0, 0]

[[timeline]]
action = "move_hand"
hand = 0
by = [15, 0, 0]
duration_s = 0.4

[[timeline]]
action = "release_hand"
hand = 0

[[timeline]]
action = "run"
duration_s = 0.2
"""


def study_dict(scene_path, runs=24, seed=7, method="monte_carlo", absurd=True):
    params = [
        {"name": "pull", "vary": "hand_path_offset", "action": 3, "direction": [1, 0, 0],
         "distribution": "uniform", "min": -10, "max": 10},
        {"name": "stiffness", "vary": "material", "material": "hose1", "property": "e_mpa",
         "distribution": "normal", "mean": 1.0, "std": 0.03, "min": 0.9, "max": 1.1},
        {"name": "grab_x", "vary": "grab_offset", "action": 2, "direction": [1, 0, 0],
         "distribution": "triangular", "min": -5, "mode": 0, "max": 5},
    ]
    if absurd:  # one run in five pulls with 10⁸ times the load (5·10⁷ N, within the scene limit of 10⁸ N): it diverges
        params.append({"name": "load_factor", "vary": "scene_value", "path": "timeline[1].force_n[2]",
                       "apply": "scale", "distribution": "choice", "choices": [1, 1, 1, 1, 1e8]})
    return {"format": "pliant-study", "version": 1, "name": "small", "scene": str(scene_path),
            "length_unit": "mm", "sampling": {"method": method, "runs": runs, "seed": seed},
            "envelope": {"voxel": 4}, "parameters": params}


def write_study_toml(path, scene_path, runs, seed):
    """The study file of :func:`study_dict` (without the absurd load) as TOML at ``path``,
    sampling ``runs`` runs from ``seed``; returns ``path``."""
    lines = ['format = "pliant-study"', "version = 1", f'scene = "{scene_path}"', 'length_unit = "mm"',
             "[sampling]", f"runs = {runs}", f"seed = {seed}"]
    for p in study_dict(scene_path, runs=runs, seed=seed, absurd=False)["parameters"]:
        lines.append("[[parameters]]")
        lines += [f"{k} = {json.dumps(v)}" for k, v in p.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture(scope="module")
def scene_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "small.toml"
    path.write_text(SCENE)
    return path


@pytest.fixture(scope="module")
def client():
    from distributed import Client
    from pliant.studies.cluster import local_cluster

    cluster = local_cluster(2)  # what `pliant study` starts
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def done(scene_path, client, tmp_path_factory):
    """The small study, run once on the 2-worker cluster."""
    out = tmp_path_factory.mktemp("study") / "out"
    result = pliant.study(study_dict(scene_path), str(out), client=client, progress=False, flush_rows=5)
    return result


# --- the study format ---------------------------------------------------------------

def test_runs_planned_beyond_max_steps_are_invalid_with_the_estimate(scene_path, client, tmp_path):
    d = study_dict(scene_path, runs=2, absurd=False)
    result = pliant.study(d, str(tmp_path / "out"), client=client, progress=False, max_steps=10)
    f = result.frame
    assert len(f) == 2 and set(f["status"]) == {"invalid"}, f[["status", "message"]]
    assert all("at most 10 are allowed" in m for m in f["message"]), list(f["message"])


@pytest.mark.parametrize("change, field", [
    (lambda d: d.update(format="pliant-scene"), "format"),
    (lambda d: d["sampling"].update(method="sobol"), "sampling.method"),
    (lambda d: d["sampling"].update(runs=0), "sampling.runs"),
    (lambda d: d["parameters"][1].update(std=-1), "parameters[1].std"),
    (lambda d: d["parameters"][1].update(distribution="gauss"), "parameters[1].distribution"),
    (lambda d: d["parameters"][2].update(mode=9), "parameters[2].mode"),
    (lambda d: d["parameters"][1].update(material="hose9"), "parameters[1].material"),
    (lambda d: d["parameters"][0].update(action=2), "parameters[0].action"),
    (lambda d: d["parameters"][0].update(direction=[0, 0, 0]), "parameters[0].direction"),
    (lambda d: d["parameters"][0].update(colour="red"), "parameters[0].colour"),
    (lambda d: d["parameters"][0].update(vary="wind"), "parameters[0].vary"),
    # a list where a name belongs is refused, not looked up (fuzzing found a TypeError)
    (lambda d: d["parameters"][0].update(vary=["grab_offset"]), "parameters[0].vary"),
    (lambda d: d["parameters"][1].update(property=["e_mpa"]), "parameters[1].property"),
    (lambda d: d.update(length_unit=["mm"]), "length_unit"),
    (lambda d: d.update(scene="nowhere.toml"), "scene"),
    # finite as written, beyond the largest number once in SI (× 10⁶ for MPa)
    (lambda d: d["parameters"][1].update(property="e_tension_mpa", apply="set", mean=1e305, std=1.0,
                                         min=1e304, max=1e306), "parameters[1].mean"),
])
def test_errors_name_the_field(scene_path, change, field):
    d = study_dict(scene_path)
    change(d)
    with pytest.raises(StudyError) as e:
        load_study(d)
    assert f": {field} = " in str(e.value), str(e.value)


def test_a_study_file_reads_and_its_errors_name_the_file(tmp_path, scene_path):
    good = load_study(EXAMPLES / "engine_bay_study.toml")
    assert good.runs == 200 and len(good.parameters) == 6
    bad = tmp_path / "bad.toml"
    bad.write_text(f'format = "pliant-study"\nversion = 1\nscene = "{scene_path}"\n'
                   '[sampling]\nmethod = "grid"\nlevels = 0\n[[parameters]]\nvary = "solver"\nchoices = ["explicit"]\n')
    with pytest.raises(StudyError, match=r"bad\.toml:6:1: sampling\.levels = 0: must be an integer"):
        load_study(bad)


def test_study_errors_point_at_line_and_column(tmp_path, scene_path):
    text = (f'format = "pliant-study"\nversion = 1\nscene = "{scene_path}"\n'
            '[sampling]\nruns = 4\n'
            '[[parameters]]\nvary = "solver"\nchoices = ["explicit"]\n'
            '[[parameters]]\nname = "p"\nvary = "grab_offset"\naction = 2\n'
            'direction = [1, 0, 0]\ndistribution = "normal"\nmean = 0\nstd = -1\n')
    bad = tmp_path / "s.toml"
    bad.write_text(text)
    with pytest.raises(StudyError, match=r"s\.toml:16:1: parameters\[1\]\.std = -1: must be > 0"):
        load_study(bad)
    # inside an array: the item's own column
    bad.write_text(text.replace("direction = [1, 0, 0]", "direction = [0, 0, 0]").replace("std = -1", "std = 1"))
    with pytest.raises(StudyError, match=r"s\.toml:13:1: parameters\[1\]\.direction = \[0, 0, 0\]"):
        load_study(bad)
    # a missing field: the table that lacks it
    bad.write_text(text.replace('vary = "grab_offset"\n', "").replace("std = -1", "std = 1"))
    with pytest.raises(StudyError, match=r"s\.toml:9:1: parameters\[1\]\.vary"):
        load_study(bad)
    # a TOML syntax error, with tomllib's position
    bad.write_text(text.replace("runs = 4", "runs = 4 4"))
    with pytest.raises(StudyError, match=r"s\.toml:5:10: syntax error"):
        load_study(bad)


# --- sampling -----------------------------------------------------------------------

@pytest.mark.parametrize("method", ["monte_carlo", "latin_hypercube"])
def test_same_seed_same_samples(scene_path, method):
    a = samples(load_study(study_dict(scene_path, method=method, seed=3)))
    b = samples(load_study(study_dict(scene_path, method=method, seed=3)))
    c = samples(load_study(study_dict(scene_path, method=method, seed=4)))
    assert a == b
    assert a != c


def test_saltelli_design_is_a_b_and_a_with_one_column_of_b(scene_path):
    d = study_dict(scene_path, runs=8, method="saltelli", absurd=False)
    st = load_study(d)
    rows = samples(st)
    names = [p["name"] for p in d["parameters"]]
    assert len(rows) == 8 * (len(names) + 2)
    a, b = rows[:8], rows[8:16]
    for i, name in enumerate(names):
        ab = rows[(2 + i) * 8:(3 + i) * 8]
        for j in range(8):
            for other in names:
                assert ab[j][other] == (b[j][other] if other == name else a[j][other])
    assert all(a[j]["pull"] != b[j]["pull"] for j in range(8))
    assert samples(load_study(d)) == rows  # the same seed, the same design


def test_sobol_indices_of_the_ishigami_function_match_the_exact_ones():
    """Ishigami & Homma (1990) f = sin x₁ + 7 sin² x₂ + 0.1 x₃⁴ sin x₁ on [−π, π]³; exact
    indices from its variance decomposition (e.g. Saltelli et al. 2008, §4.7)."""
    from pliant.studies import sobol

    a, b, n = 7.0, 0.1, 2 ** 12
    u = sobol.unit_design(n, 3, seed=5)
    x = -math.pi + 2 * math.pi * u
    y = np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])
    v1 = 0.5 * (1 + b * math.pi ** 4 / 5) ** 2
    v2 = a * a / 8
    v13 = b * b * math.pi ** 8 * 8 / 225
    v = v1 + v2 + v13
    exact_first = [v1 / v, v2 / v, 0.0]
    exact_total = [(v1 + v13) / v, v2 / v, v13 / v]
    got = sobol.indices(y, n, 3, seed=1)
    for i in range(3):
        assert abs(got[i].first - exact_first[i]) < 0.02, (i, got[i])
        assert abs(got[i].total - exact_total[i]) < 0.02, (i, got[i])
        assert got[i].total_ci[0] - 0.01 <= exact_total[i] <= got[i].total_ci[1] + 0.01, (i, got[i])
        assert got[i].points == n
    # x₃ acts only through its interaction with x₁: no first-order share, a total one
    assert got[2].first < 0.02 < 0.2 < got[2].total
    # a failed run leaves its base point out of the estimates it belongs to
    y[2 * n + 5] = np.nan  # AB⁽¹⁾ of point 5
    y[1] = np.nan  # A of point 1: every parameter loses it
    again = sobol.indices(y, n, 3, seed=1)
    assert [g.points for g in again] == [n - 2, n - 1, n - 1]


def test_a_saltelli_study_reports_total_effects(scene_path, client, tmp_path):
    from pliant.studies.report import sobol_estimates

    d = study_dict(scene_path, runs=4, seed=2, method="saltelli", absurd=False)
    result = pliant.study(d, str(tmp_path / "out"), client=client, progress=False)
    assert len(result.frame) == 4 * 5 and (result.frame["status"] == "ok").all()
    est = sobol_estimates(result.frame, load_study(d))["worst_hand_ratio"]
    pull, stiffness, grab_x = est
    # how far the hand pulls decides the hand force (EA·Δ/L); a ±3 % stiffness and a ±5 mm
    # grab point matter far less
    assert pull.total > 3 * max(stiffness.total, grab_x.total), est
    page = open(result.report).read()
    assert "Sobol' indices (Saltelli design)" in page and "S<sub>T</sub> =" in page


def test_latin_hypercube_puts_one_point_in_every_stratum():
    n = 37
    u = unit_samples("latin_hypercube", n, 4, seed=11)
    for j in range(4):
        assert sorted(np.floor(u[:, j] * n).astype(int)) == list(range(n))
    mc = unit_samples("monte_carlo", n, 4, seed=11)  # plain Monte Carlo does not
    assert any(len(set(np.floor(mc[:, j] * n).astype(int))) < n for j in range(4))


def test_distributions_respect_their_bounds(scene_path):
    s = samples(load_study(study_dict(scene_path, runs=500, absurd=False)))
    pull = np.array([x["pull"] for x in s])
    stiff = np.array([x["stiffness"] for x in s])
    grab = np.array([x["grab_x"] for x in s])
    assert pull.min() >= -0.010 and pull.max() <= 0.010 and pull.max() > 0.0099  # SI: metres
    assert stiff.min() >= 0.9 and stiff.max() <= 1.1 and abs(stiff.mean() - 1.0) < 0.01
    assert grab.min() >= -0.005 and grab.max() <= 0.005 and abs(np.median(grab)) < 0.001


def test_grid_is_full_factorial(scene_path):
    d = study_dict(scene_path, method="grid", absurd=False)
    d["sampling"]["levels"] = 3
    d["parameters"][2]["levels"] = [-5, 5]
    s = samples(load_study(d))
    assert len(s) == 3 * 3 * 2
    assert len({tuple(x.values()) for x in s}) == 18
    assert sorted({x["grab_x"] for x in s}) == [-0.005, 0.005]


# --- variants -----------------------------------------------------------------------

def test_variants_change_what_they_name():
    st = load_study(EXAMPLES / "engine_bay_study.toml")
    nominal = {"stiffness": 1.1, "length": 1.01, "clip_corner_x": 0.003, "clip_corner_y": 0.0,
               "stub_angle": math.radians(90), "grab_corner": -0.01}
    scene = variant_scene(st, nominal)
    base = tomllib.loads((EXAMPLES / "engine_bay.toml").read_text())
    clip = next(c for c in scene["clips"] if c["name"] == "clip engine corner")
    assert clip["origin"] == pytest.approx([-162, -369, 250])  # mm: +3 mm along x
    stub = scene["stubs"][0]
    assert stub["axis"] == pytest.approx([-1, 0, 0], abs=1e-12)  # (0, 1, 0) turned 90° about z
    assert scene["timeline"][11]["at"] == pytest.approx([-175, -398, 250])
    mat = scene["materials"]["hose3_study"]
    assert mat["e_tension_mpa"] == pytest.approx(6.9442 * 1.1)
    assert mat["e_compression_mpa"] == pytest.approx(8.6913 * 1.1)
    lengths = {}
    for name, s in (("base", base), ("variant", scene)):
        sc = variant_module().absolute_meshes(s, str(EXAMPLES))
        lengths[name] = {h["name"]: h["length"] for h in pliant.Scene.from_dict(sc).hoses}
    assert lengths["variant"]["lower"] == pytest.approx(1.01 * lengths["base"]["lower"], rel=1e-6)
    assert lengths["variant"]["upper"] == pytest.approx(lengths["base"]["upper"], rel=1e-12)


def variant_module():
    from pliant.studies import variant

    return variant


# --- the study on a local cluster ---------------------------------------------------

def test_parquet_has_one_row_per_run_readable_by_pandas_and_duckdb(done):
    import pandas as pd

    frame = pd.read_parquet(done.results)
    assert len(frame) == 24 and list(frame["index"]) == list(range(24))
    for col in ["run_id", "status", "message", "p_pull", "p_stiffness", "p_grab_x", "p_load_factor",
                "feasible", "reasons", "peak_hand_force_n", "peak_hand_torque_nm", "worst_hand_ratio",
                "min_bend_radius_ratio", "max_twist_rad_per_m", "clearance_block_m", "uncertain",
                "unconverged_steps", "wall_time_s", "cpu_time_s"]:
        assert col in frame, col
    parts = pd.read_parquet(os.path.join(done.out, "parts"))  # the streamed parts, as a dataset
    assert sorted(parts["run_id"]) == sorted(frame["run_id"])
    duckdb = pytest.importorskip("duckdb")
    [(n, feasible)] = duckdb.sql(
        f"select count(*), count(*) filter (where feasible) from read_parquet('{done.results}')").fetchall()
    assert n == 24 and feasible == int(frame["feasible"].fillna(False).sum())
    ok = frame[frame["status"] == "ok"]
    assert (ok["peak_hand_force_n"] > 0).all() and ok["feasible"].notna().all()


def test_a_diverged_run_is_recorded_with_its_message(done):
    frame = done.frame
    absurd = frame["p_load_factor"] == "100000000.0"
    assert absurd.any() and (~absurd).any()
    assert (frame.loc[absurd, "status"] == "diverged").all()
    assert frame.loc[absurd, "message"].str.contains("diverged").all()
    assert (frame.loc[absurd, "feasible"] == False).all()  # noqa: E712
    assert (frame.loc[~absurd, "status"] == "ok").all()


def test_every_row_replays_from_its_scene(done):
    frame = done.frame
    row = frame[frame["status"] == "ok"].iloc[0]
    scene = pliant.load_scene(done.replay_scene(row["run_id"]))
    again = pliant.run_timeline(scene)
    assert again.feasible == row["feasible"]
    assert max(h["max_force"] for h in again.hand_peaks) == row["peak_hand_force_n"]  # bit for bit
    # the clearance to the block, from the recorded centre line, by the box's own formula
    pos = again.positions("h")
    pts = np.concatenate([pos.reshape(-1, 3), (0.5 * (pos[:, 1:] + pos[:, :-1])).reshape(-1, 3)])
    q = np.abs(pts - [0.15, 0, -0.08]) - 0.05
    d = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
    assert row["clearance_block_m"] == pytest.approx(d.min() - 0.008, abs=1e-6)  # hose 1: d_outer 16 mm


def test_the_outcome_depends_on_the_hand_path_and_the_report_says_so(done):
    frame = done.frame
    ok = frame[frame["status"] == "ok"]
    assert ok["feasible"].any() and not ok["feasible"].all()  # the pull decides
    text = open(done.report).read()
    assert "Wilson score interval" in text and "95 % confidence interval" in text
    assert "Spearman rank correlation" in text
    k = int(frame["feasible"].fillna(False).sum())
    assert f"Feasible in <b>{k} of 24</b>" in text
    from pliant.studies.report import sensitivity

    ranking = sensitivity(ok, done.study, ["feasible", "worst_hand_ratio"])
    assert ranking[0]["parameter"] == "pull"
    assert text.index("<code>pull</code>") < text.index("<code>stiffness</code>", text.index("What drives"))
    assert 'href="runs/run-' in text


def test_wilson_interval():
    from pliant.studies.report import wilson

    lo, hi = wilson(8, 10)
    assert (lo, hi) == pytest.approx((0.4902, 0.9433), abs=1e-4)  # textbook values
    assert wilson(0, 20)[0] == 0.0 and wilson(20, 20)[1] == 1.0


def test_resume_does_no_new_work_and_redoes_what_was_lost(done, client, scene_path):
    parts_dir = os.path.join(done.out, "parts")
    before = sorted(os.listdir(parts_dir))
    again = pliant.study(study_dict(scene_path), done.out, client=client, progress=False)
    assert len(before) >= 5  # parts of 5 rows
    assert sorted(os.listdir(parts_dir)) == before  # nothing was run
    assert again.frame.equals(done.frame)
    # lose a part file (as if the study was stopped before writing it)
    import pyarrow.parquet as pq

    last = os.path.join(parts_dir, before[len(before) // 2])
    lost = pq.read_table(last).num_rows
    os.remove(last)
    third = pliant.study(study_dict(scene_path), done.out, client=client, progress=False, flush_rows=5)
    assert len(third.frame) == 24
    added = [f for f in os.listdir(parts_dir) if f not in before]
    assert len(os.listdir(parts_dir)) == len(before)
    assert sum(pq.read_table(os.path.join(parts_dir, f)).num_rows for f in added) == lost
    cols = ["run_id", "status", "feasible", "peak_hand_force_n"]
    assert third.frame[cols].equals(done.frame[cols])
    with pytest.raises(StudyError, match="holds another study"):
        pliant.study(study_dict(scene_path, seed=99), done.out, client=client, progress=False)


def test_the_envelope_is_dilated_from_the_samples_on_disk_and_an_older_folder_is_refused(done, client, scene_path,
                                                                                       tmp_path):
    """The union of the runs' centre-line samples is what a study keeps on disk; its
    voxels are that union dilated once. A folder from before (voxels, no samples) cannot
    be resumed: its envelope would miss the runs on disk."""
    folder = os.path.join(done.out, "envelope")
    samples = np.load(os.path.join(folder, "samples-h.npy"))
    voxels = np.load(os.path.join(folder, "voxels-h.npy"))
    radius = variant.hose_radii(done.study.scene)["h"]
    assert 0 < len(samples) and np.array_equal(envelope.voxels_of_samples(samples, radius, done.envelope["voxel_m"]),
                                               voxels)
    older = str(tmp_path / "older")
    shutil.copytree(done.out, older)
    os.remove(os.path.join(older, "envelope", "samples-h.npy"))
    with pytest.raises(StudyError, match="samples-h.npy is missing"):
        pliant.study(study_dict(scene_path), older, client=client, progress=False)


def centreline_samples(frames, spacing):
    """The envelope's centre-line samples, written with numpy as the reference of the Rust
    ``centreline_sample_keys``: every element of every frame (T, N, 3) at n + 1 points,
    n from the longest element so they are at most ``spacing`` apart."""
    a, b = frames[:, :-1].reshape(-1, 3), frames[:, 1:].reshape(-1, 3)
    if len(a) == 0:
        return frames.reshape(-1, 3)
    n = max(1, int(math.ceil(np.linalg.norm(b - a, axis=1).max() / spacing)))
    t = np.linspace(0.0, 1.0, n + 1)
    return (a[:, None, :] + (b - a)[:, None, :] * t[None, :, None]).reshape(-1, 3)


def test_envelope_is_closed_and_contains_every_run(done):
    info = done.envelope
    assert info["hoses"]["h"]["closed"]
    keys = np.load(os.path.join(done.out, "envelope", "voxels-h.npy"))
    h = info["voxel_m"]
    verts, faces = envelope.mesh(keys, h)
    assert envelope.is_closed(faces)
    occupied = set(keys.tolist())
    rng = np.random.default_rng(0)
    probe = []
    for run_id in done.frame.loc[done.frame["status"] == "ok", "run_id"]:
        pos = pliant.run_timeline(pliant.load_scene(done.replay_scene(run_id))).positions("h")
        pts = centreline_samples(pos, h / 2)
        # every sampled centre-line point: the 8 voxel centres around it are occupied
        base = np.floor(pts / h).astype(np.int64)
        for corner in np.array(np.meshgrid([0, 1], [0, 1], [0, 1])).T.reshape(-1, 3):
            assert np.isin(envelope.pack(base + corner), keys).all(), run_id
        probe.append(pts[rng.choice(len(pts), 10)])
    # and the mesh itself encloses them (generalised winding number ≈ 1)
    w = envelope.winding_number(verts, faces, np.concatenate(probe))
    assert np.all(np.abs(np.abs(w) - 1) < 1e-6)
    outside = np.array([[1.0, 1.0, 1.0]])
    assert abs(envelope.winding_number(verts, faces, outside)[0]) < 1e-6
    assert len(occupied) == len(keys)
    for name in ("envelope.glb", "h.stl"):
        assert os.path.getsize(os.path.join(done.out, "envelope", name)) > 1000
    with open(os.path.join(done.out, "envelope", "envelope.glb"), "rb") as f:
        assert f.read(4) == b"glTF"


def test_envelope_voxels_hold_the_tube():
    """A straight tube: the voxels reach r from the axis and no more than r + 1.1 h."""
    h, r = 0.002, 0.01
    frames = np.array([[[0, 0, 0], [0.1, 0, 0]]], float)
    keys = envelope.voxelize(frames, r, h)
    c = envelope.unpack(keys) * h
    inside = c[(c[:, 0] > 0.01) & (c[:, 0] < 0.09)]
    rad = np.hypot(inside[:, 1], inside[:, 2])
    assert rad.max() <= r + (math.sqrt(3) / 2 * 1.25 + 0.25) * h + 1e-12
    assert rad.max() >= r
    g = np.arange(-10, 11) * h  # every grid point within r of the axis is occupied
    yy, zz = np.meshgrid(g, g)
    want = np.hypot(yy, zz) <= r
    ring = envelope.pack(np.stack([np.full(want.sum(), 25), np.round(yy[want] / h), np.round(zz[want] / h)], 1))
    assert np.isin(ring, keys).all()


def test_cli_runs_a_study_and_reports_bad_input(pliant_bin, scene_path, tmp_path):
    import pyarrow.parquet as pq

    study_file = write_study_toml(tmp_path / "s.toml", scene_path, runs=4, seed=1)
    env = dict(os.environ, PLIANT_PYTHON=sys.executable)
    out = tmp_path / "out"
    run = subprocess.run([pliant_bin, "study", str(study_file), "--out", str(out), "--workers", "1"],
                         env=env, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "Dask dashboard: http" in run.stderr
    assert "runs/min" in run.stderr
    assert pq.read_table(out / "results.parquet").num_rows == 4
    assert (out / "report.html").is_file() and (out / "runs" / "run-00003.json").is_file()
    study_file.write_text(study_file.read_text().replace('distribution = "uniform"', 'distribution = "flat"'))
    bad = subprocess.run([pliant_bin, "study", str(study_file), "--out", str(tmp_path / "o2")],
                         env=env, capture_output=True, text=True, timeout=600)
    assert bad.returncode == 2
    assert "parameters[0].distribution = flat: must be one of" in bad.stderr


def test_schema_and_parser_agree_on_the_fields():
    from pliant.studies import spec

    schema = json.loads((EXAMPLES.parent / "docs" / "study.schema.json").read_text())
    assert set(schema["properties"]) == spec.TOP_KEYS
    param = schema["properties"]["parameters"]["items"]
    assert set(param["properties"]) == spec.PARAMETER_KEYS
    assert param["properties"]["vary"]["enum"] == list(spec.KINDS)
    assert param["properties"]["distribution"]["enum"] == list(spec.DISTRIBUTIONS)
    assert set(param["properties"]["property"]["enum"]) == set(spec.MATERIAL_PROPERTIES) | set(spec.MOTION_PROPERTIES)
    example = tomllib.loads((EXAMPLES / "engine_bay_study.toml").read_text())
    for p in example["parameters"]:
        assert set(p) <= spec.PARAMETER_KEYS


def test_profile_solver_and_scene_values_reach_the_scene(scene_path):
    d = study_dict(scene_path, absurd=False)
    d["parameters"] += [
        {"vary": "ergonomics", "choices": ["posture=sitting, population=men, moments_decide=true"]},
        {"vary": "solver", "choices": ["static"]},
        {"name": "dur", "vary": "scene_value", "path": "timeline[3].duration_s", "apply": "scale",
         "distribution": "uniform", "min": 2, "max": 3},
    ]
    st = load_study(d)
    s = samples(st)[0]
    scene = variant_scene(st, s)
    assert scene["ergonomics"] == {"posture": "sitting", "population": "men", "moments_decide": True}
    assert scene["simulation"]["solver"] == "static"
    assert scene["timeline"][3]["duration_s"] == pytest.approx(0.4 * s["dur"])
    assert pliant.Scene.from_dict(scene).ergonomics != pliant.Scene.from_dict(tomllib.loads(SCENE)).ergonomics
    d["parameters"][-1]["path"] = "timeline[3].speed"
    with pytest.raises(StudyError, match=r"timeline\[3\]\.speed.*no such value"):
        variant_scene(load_study(d), s)


def test_mass_scaling_reaches_every_run_and_is_checked(scene_path):
    d = study_dict(scene_path, absurd=False)
    d["mass_scaling"] = 9
    scene = variant_scene(load_study(d), samples(load_study(d))[0])
    assert scene["simulation"]["mass_scaling"] == 9.0
    for bad in (0.5, "9", True, 2e4):
        d["mass_scaling"] = bad
        with pytest.raises(StudyError, match="mass_scaling"):
            load_study(d)


def test_settle_finish_reaches_every_settle_and_is_checked(scene_path, tmp_path):
    path = tmp_path / "settles.toml"
    path.write_text(SCENE + '\n[[timeline]]\naction = "settle"\n\n[[timeline]]\naction = "settle"\n')
    d = study_dict(path, absurd=False)
    for finish in ("static", "static_equilibrium"):
        d["settle"] = finish
        st = load_study(d)
        scene = variant_scene(st, samples(st)[0])
        settles = [a for a in scene["timeline"] if a["action"] == "settle"]
        assert [a["finish"] for a in settles] == [finish, finish]
        assert all("finish" not in a for a in scene["timeline"] if a["action"] != "settle")
        assert pliant.Scene.from_dict(scene)  # the engine takes the field
    scene["simulation"] = {"mass_scaling": 9}
    runner.plain_physics(scene)  # what the agreement's reference runs and the reruns get
    assert all("finish" not in a for a in scene["timeline"]) and scene["simulation"] == {}
    for bad in ("quasi-static", 1, True):
        d["settle"] = bad
        with pytest.raises(StudyError, match="settle"):
            load_study(d)
    d["settle"] = "static"
    assert load_study(d).rerun_unsettled is False
    assert load_study(dict(d, rerun_unsettled=True)).rerun_unsettled is True
    with pytest.raises(StudyError, match="rerun_unsettled"):
        load_study(dict(d, rerun_unsettled="yes"))


def test_an_unsettled_run_is_run_again_with_the_scenes_own_physics(tmp_path):
    """Mass-scaled with its settles finished static, a run whose settle cannot come to rest
    in its 10 ms is run again plain (no scaling, settle dynamic): the row is the plain
    run's, to the step; one that rests keeps its own row."""
    base = tomllib.loads(SCENE)
    base["simulation"] = {"mass_scaling": 4}

    def row(settle_s, rerun):
        scene = variant.plain_copy(base)
        scene["timeline"].append({"action": "settle", "max_duration_s": settle_s, "finish": "static"})
        task = runner.Task("r", 0, json.dumps(scene), str(tmp_path), {}, [], 0.0, rerun_unsettled=rerun)
        return runner.run_variant(task)["row"], scene

    short, scene = row(0.01, True)
    assert short["status"] == "ok" and short["rerun"] is True
    plain = pliant.run_timeline(pliant.Scene.from_dict(runner.plain_physics(scene)))
    assert short["steps"] == plain.steps and short["feasible"] == plain.feasible
    cheap, _ = row(0.01, False)
    assert cheap["rerun"] is False and cheap["steps"] < 0.75 * short["steps"]  # the step is twice as long
    rested, _ = row(10.0, True)
    assert rested["rerun"] is False


def test_a_mass_scaled_run_with_a_fastener_left_free_is_run_again():
    """A run is doubtful — run again plain — when a settle did not rest, or when it is
    mass-scaled and a clip or stub ended unassembled (seating is decided by the release's
    dynamics, which the scaled inertia changes); an unscaled run keeps a free clip."""
    from types import SimpleNamespace

    def result(at_rest, assembled):
        return SimpleNamespace(settles=[{"at_rest": at_rest}],
                               fasteners=[{"kind": "clip", "name": "c", "assembled": assembled},
                                          {"kind": "stub", "name": "s", "assembled": True}])

    def task(scaling):
        scene = {"simulation": {"mass_scaling": scaling}} if scaling else {}
        return runner.Task("r", 0, json.dumps(scene), "", {}, [], 0.0, rerun_unsettled=True)

    for scaling in (None, 1, 9):
        assert runner._doubtful(result(False, True), task(scaling))
        assert not runner._doubtful(result(True, True), task(scaling))
    assert runner._doubtful(result(True, False), task(9))
    assert not runner._doubtful(result(True, False), task(1))
    assert not runner._doubtful(result(True, False), task(None))


def test_scene_values_are_set_in_every_run_and_checked_on_load(scene_path):
    d = study_dict(scene_path, absurd=False)
    d["scene_values"] = {"simulation.time_step_safety": 0.9, "timeline[3].duration_s": 0.5}
    st = load_study(d)
    for s in samples(st)[:3]:
        scene = variant_scene(st, s)
        assert scene["simulation"]["time_step_safety"] == 0.9
        assert scene["timeline"][3]["duration_s"] == 0.5
    assert "time_step_safety" not in tomllib.loads(SCENE).get("simulation", {})
    for values, message in [
        ({"simulation.time_step_safety": 1.5}, r"scene_values = .*the scene refuses them: .*time_step_safety"),
        ({"simulation.time_step_safty": 0.9}, r"scene_values = .*the scene refuses them: .*time_step_safty"),
        ({"nothing[2].x": 1}, r"scene_values\.nothing\[2\]\.x = 1: path .*no such value"),
        ({"simulation.gravity": [0, 0, 1]}, r"scene_values\.simulation\.gravity = .*must be a number"),
        ("fast", r"scene_values = fast: must be a table"),
    ]:
        with pytest.raises(StudyError, match=message):
            load_study(dict(d, scene_values=values))


def test_an_existing_cluster_by_its_scheduler_address(client, scene_path, tmp_path, capsys):
    result = pliant.study(study_dict(scene_path, runs=3, absurd=False), str(tmp_path / "o"),
                          scheduler=client.scheduler.address, progress=False)
    assert list(result.frame["status"]) == ["ok"] * 3
    assert len(client.scheduler_info()["workers"]) == 2  # the cluster is still there
    # the dashboard named is that scheduler's own: its host, its dashboard's port
    host = client.scheduler.address.split("://")[1].rsplit(":", 1)[0]
    port = client.scheduler_info()["services"]["dashboard"]
    lines = [s for s in capsys.readouterr().err.splitlines() if s.startswith("Dask dashboard")]
    assert len(lines) == 1 and f"{host}:{port}/" in lines[0], lines


def test_a_study_stopped_midway_resumes_where_it_stopped(scene_path, tmp_path):
    """SIGTERM once some rows are on disk; the same command then runs only the rest."""
    import signal
    import time

    import pyarrow.parquet as pq

    slow = tmp_path / "slow.toml"  # each run simulates 3 s: the study takes a while
    slow.write_text(SCENE.replace("duration_s = 0.2", "duration_s = 3.0"))
    study_file = write_study_toml(tmp_path / "s.toml", slow, runs=40, seed=2)
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "pliant.studies", str(study_file), "--out", str(out), "--workers", "2",
           "--flush-rows", "2"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    parts = out / "parts"
    while proc.poll() is None and not (parts.is_dir() and len(list(parts.glob("*.parquet"))) >= 2):
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=300)
    rows = sum(pq.read_table(p).num_rows for p in parts.glob("*.parquet"))
    assert proc.returncode in (0, 130), err
    if proc.returncode == 130:  # stopped midway (not already finished)
        assert "interrupted" in err and 4 <= rows < 40
    again = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert again.returncode == 0, again.stderr
    assert f"{rows} done before, {40 - rows} to run" in again.stderr
    done = pq.read_table(out / "results.parquet").to_pandas()
    assert list(done["index"]) == list(range(40)) and done["run_id"].is_unique
    assert (done["status"] == "ok").all()


def test_first_order_index_sees_what_rank_correlation_misses():
    from scipy.stats import spearmanr

    from pliant.studies.report import first_order_index

    rng = np.random.default_rng(5)
    x1, x2, x3 = rng.uniform(-1, 1, (3, 2000))
    y = x1 ** 2 + 0.3 * x2  # x1 acts, but not monotonically; x3 not at all
    assert abs(spearmanr(x1, y).statistic) < 0.1
    s1, s2, s3 = (first_order_index(x, y) for x in (x1, x2, x3))
    # exact: Var(x1²) = 4/45, Var(0.3 x2) = 0.03 → S1 = 0.748, S2 = 0.252
    assert s1 == pytest.approx(0.748, abs=0.05) and s2 == pytest.approx(0.252, abs=0.05)
    assert s3 < 0.02


def test_one_runs_envelope_lies_within_the_studys(done, tmp_path):
    from pliant.studies import run_envelope

    h = done.envelope["voxel_m"]
    run_id = done.frame.loc[done.frame["status"] == "ok", "run_id"].iloc[-1]
    own = run_envelope(done.replay_scene(run_id), str(tmp_path), voxel=h)["h"]
    union = np.load(os.path.join(done.out, "envelope", "voxels-h.npy"))
    assert 0 < len(own) < len(union)
    assert np.isin(own, union).all()
    assert (tmp_path / "h.stl").stat().st_size > 1000 and (tmp_path / "envelope.glb").is_file()


def test_batches_of_runs_give_the_same_rows_and_envelope(done, client, scene_path, tmp_path):
    """Several runs per Dask task (--batch) change only how the work is shipped: the
    same rows, the same voxels, and a batch's runs keep their own indices."""
    from pliant.studies.cluster import batch_size

    batched = pliant.study(study_dict(scene_path), str(tmp_path / "b"), client=client, progress=False,
                           batch=5)  # 24 runs: four batches of 5 and one of 4
    cols = ["run_id", "index", "status", "message", "feasible", "peak_hand_force_n", "steps",
            "min_bend_radius_ratio"]
    assert batched.frame[cols].equals(done.frame[cols])
    same = [np.load(os.path.join(r.out, "envelope", "voxels-h.npy")) for r in (done, batched)]
    assert len(same[0]) > 0 and np.array_equal(same[0], same[1])
    assert batch_size(24, 2) == 1 and batch_size(10_000, 2) == 32 and batch_size(300, 2, 3) == 3
    with pytest.raises(StudyError, match="batch = 0"):
        batch_size(10, 2, 0)


def test_sorted_unique_and_union_match_numpy():
    from pliant.studies import envelope

    rng = np.random.default_rng(5)
    a, b = rng.integers(-50, 50, 400), rng.integers(-50, 50, 300)
    assert np.array_equal(envelope.sorted_unique(a), np.unique(a))
    ua, ub = np.unique(a), np.unique(b)
    assert np.array_equal(envelope.union(ua, ub), np.union1d(ua, ub))
    assert len(envelope.sorted_unique(np.zeros(0, np.int64))) == 0


def test_voxels_are_exactly_those_within_reach_of_a_sample():
    """voxelize's shortcuts (sure core, nearest seed's sample, k-d tree for the rest) give
    exactly the voxels whose centre lies within the reach of a centre-line sample, by brute
    force over every sample, on a wandering hose of three frames."""
    from scipy.spatial.distance import cdist

    h, r = 0.004, 0.006
    rng = np.random.default_rng(11)
    base = np.cumsum(rng.normal(0, 0.01, (8, 3)), axis=0)
    frames = np.stack([base + k * rng.normal(0, 0.004, (8, 3)) for k in range(3)])
    keys = envelope.voxelize(frames, r, h)
    fine = h / 4
    pts = envelope.unpack(envelope.sorted_unique(envelope.pack(np.round(
        centreline_samples(frames, h / 2) / fine)))) * fine
    reach = r + math.sqrt(3) / 2 * (h + fine) + h / 4
    lo = np.floor((pts.min(axis=0) - reach) / h).astype(int) - 1
    hi = np.ceil((pts.max(axis=0) + reach) / h).astype(int) + 1
    ijk = np.stack(np.meshgrid(*[np.arange(a, b + 1) for a, b in zip(lo, hi)], indexing="ij"), -1).reshape(-1, 3)
    within = cdist(ijk * h, pts).min(axis=1) <= reach
    assert within.sum() > 100
    assert np.array_equal(keys, np.sort(envelope.pack(ijk[within])))


def test_sample_keys_equal_the_numpy_reference():
    """The Rust sample keys are those of the numpy formulation bit for bit (sampling,
    rounding ties to even, packing), on a wandering hose whose last frames repeat (the
    Rust side skips a sample equal to the one of the frame before) and on single nodes."""
    h = 0.005
    rng = np.random.default_rng(3)
    base = np.cumsum(rng.normal(0, 0.02, (12, 3)), axis=0)
    frames = np.stack([base + k * rng.normal(0, 0.003, (12, 3)) for k in range(40)] + [base] * 5)
    frames[7, 3] = [0.125, 0.25, -0.375]  # exact multiples of h/8: rounding ties
    for f in (frames, frames[:, :1], frames[:3]):
        want = envelope.sorted_unique(envelope.pack(np.round(centreline_samples(f, h / 2) / (h / 4))))
        assert np.array_equal(envelope.sample_keys(f, h), want)
    with pytest.raises(ValueError, match="non-finite"):
        envelope.sample_keys(np.full((2, 3, 3), np.nan), h)
    with pytest.raises(ValueError, match="too large"):
        envelope.sample_keys(np.array([[[0.0, 0, 0], [0.01, 0, 0]], [[5e3, 0, 0], [5e3, 0.01, 0]]]), h)
    with pytest.raises(ValueError, match="not a hose"):
        envelope.sample_keys(np.array([[[0.0, 0, 0], [100.0, 0, 0]]]), h)


def test_a_batch_dilates_its_united_samples_to_the_union_of_its_runs_voxels():
    """Dilating the united samples of several runs once gives exactly the union of each
    run's own voxels (the study's shortcut: batches unite their runs' samples, the study
    dilates the union of all once, cluster._dilate)."""
    h, r = 0.004, 0.006
    rng = np.random.default_rng(17)
    runs = []
    for _ in range(3):
        base = np.cumsum(rng.normal(0, 0.01, (8, 3)), axis=0)
        runs.append(np.stack([base + k * rng.normal(0, 0.003, (8, 3)) for k in range(4)]))
    each = [envelope.voxelize(f, r, h) for f in runs]
    united = envelope.sorted_unique(np.concatenate([envelope.sample_keys(f, h) for f in runs]))
    want = envelope.sorted_unique(np.concatenate(each))
    assert len(want) > max(len(e) for e in each)
    assert np.array_equal(envelope.voxels_of_samples(united, r, h), want)


def test_part_distances_match_independent_ones():
    """Clearances: a rotated box's signed distance equals the distance to its 12 triangles
    (a mesh part: the engine's BVH and triangle projection, not the box formula) outside
    and minus the nearest face's inside; a cylinder's matches a dense sampling of its
    surface; a mesh part's min_distance (pruned by its bounding box) equals the minimum
    over every point's distance; a sphere's is |x − c| − r."""
    rng = np.random.default_rng(8)
    R = geometry._rotation({"axis": [1, 2, 3], "angle_deg": 37})
    x0, size = np.array([0.1, 0.2, 0.3]), np.array([0.4, 0.3, 0.2])
    box = geometry.Part("b", "box", x0, R, size=size)
    pts = x0 + rng.normal(0, 0.4, (2000, 3))
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * size / 2
    faces = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    tri = (corners[np.array(faces)] @ R.T) + x0
    local = (pts - x0) @ R
    inside = (np.abs(local) < size / 2).all(axis=1)
    d = box.distance(pts)
    assert inside.sum() > 20 and (~inside).sum() > 1000
    as_mesh = geometry.Part("t", "mesh", x0, np.eye(3), triangles=tri)
    assert np.allclose(d[~inside], as_mesh.distance(pts[~inside]), atol=1e-12)
    assert np.allclose(d[inside], -(size / 2 - np.abs(local[inside])).min(axis=1), atol=1e-12)

    cyl = geometry.Part("c", "cylinder", x0, R, size=np.array([0.2, 0.5]))
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 720), np.linspace(-0.25, 0.25, 200))
    side = np.stack([0.2 * np.cos(u), 0.2 * np.sin(u), v], -1).reshape(-1, 3)
    rr, uu = np.meshgrid(np.linspace(0, 0.2, 100), np.linspace(0, 2 * np.pi, 720))
    cap = np.stack([rr * np.cos(uu), rr * np.sin(uu), np.full_like(rr, 0.25)], -1).reshape(-1, 3)
    surface = np.concatenate([side, cap, cap * [1, 1, -1]]) @ R.T + x0
    far = x0 + rng.normal(0, 0.5, (300, 3))
    far = far[cyl.distance(far) > 0.01]
    from scipy.spatial import cKDTree
    sampled = cKDTree(surface).query(far)[0]
    assert len(far) > 100 and np.abs(cyl.distance(far) - sampled).max() < 2e-3  # sampling 1.75 mm

    mesh = geometry.Part("m", "mesh", x0, np.eye(3), triangles=tri)
    offset = np.full(len(pts), 0.01)
    outside = pts[~inside]
    brute = (mesh.distance(outside) - offset[: len(outside)]).min()
    assert mesh.min_distance(outside, offset[: len(outside)]) == brute
    assert box.min_distance(pts, offset) == (d - offset).min()
    sphere = geometry.Part("s", "sphere", x0, R, size=np.array([0.15]))
    assert np.allclose(sphere.distance(pts), np.linalg.norm(pts - x0, axis=1) - 0.15, atol=1e-15)
    assert mesh.min_distance(outside[:0], offset[:0]) == np.inf
    with pytest.raises(ValueError, match="3 finite sizes"):
        geometry.Part("x", "box", x0, R, size=np.array([1.0, 2.0])).distance(pts)


def test_local_workers_start_without_a_malloc_trim_threshold(client):
    """Dask sets MALLOC_TRIM_THRESHOLD_=65536 in its workers, which switches off glibc's
    adaptive mmap threshold: each run then mapped and unmapped its large buffers (13 500
    page faults and 0.06 CPU-s per demo run instead of 1 800). The study's local cluster
    leaves it out and keeps Dask's other settings."""
    import dask

    assert dask.config.get("distributed.nanny.pre-spawn-environ")["MALLOC_TRIM_THRESHOLD_"] == 65536
    env = client.run(lambda: {k: os.environ.get(k) for k in ("MALLOC_TRIM_THRESHOLD_", "OMP_NUM_THREADS")})
    assert len(env) == 2
    for worker in env.values():
        assert worker == {"MALLOC_TRIM_THRESHOLD_": None, "OMP_NUM_THREADS": "1"}


def test_local_workers_run_no_statistical_profiler(client):
    """Dask's workers sample every thread's stack 100 times a second for the dashboard's
    Profile page (≈ 4 % of a worker's CPU on the demo study); the study's local cluster
    switches that off, here and not in the process that started it."""
    import dask

    assert dask.config.get("distributed.worker.profile.enabled") is True
    enabled = client.run(lambda: __import__("dask").config.get("distributed.worker.profile.enabled"))
    assert len(enabled) == 2 and all(v is False for v in enabled.values()), enabled


@pytest.mark.parametrize("kind", ["dev_zero", "fifo", "folder"])
def test_a_study_file_that_is_not_a_regular_file_is_refused(tmp_path, kind):
    # a FIFO or a link to /dev/zero hung the reader or ran out of memory
    path = tmp_path / "study.toml"
    if kind == "dev_zero":
        os.symlink("/dev/zero", path)
    elif kind == "fifo":
        if not hasattr(os, "mkfifo"):
            pytest.skip("no FIFOs here")
        os.mkfifo(path)
    else:
        path.mkdir()
    with pytest.raises(StudyError, match="not a regular file"):
        load_study(path)
