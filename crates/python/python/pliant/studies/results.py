"""A finished (or resumed-to-the-end) study: all rows in one Parquet file, the envelope
meshes with their clearances, and the report."""

from __future__ import annotations

import glob
import json
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional

import numpy as np

from . import envelope
from .runner import column_name
from .spec import Study


@dataclass
class StudyResult:
    """What ``pliant.study`` returns: the output folder and the rows as a DataFrame."""

    out: str
    frame: Any  # pandas.DataFrame, one row per run
    study: Study = field(repr=False)

    @property
    def results(self) -> str:
        return os.path.join(self.out, "results.parquet")

    @property
    def report(self) -> str:
        return os.path.join(self.out, "report.html")

    @property
    def envelope(self) -> Dict[str, Any]:
        with open(os.path.join(self.out, "envelope", "envelope.json")) as f:
            return json.load(f)

    @property
    def agreement(self) -> Optional[Dict[str, Any]]:
        """The verdicts' agreement with a reference solver (``agreement.json``), or None
        when the study was not checked (``check_agreement``)."""
        from . import agreement

        return agreement.read(self.out)

    def replay_scene(self, run_id: str) -> str:
        """The run's scene file: ``pliant run`` or ``pliant serve`` it to see the run."""
        return os.path.join(self.out, "runs", run_id + ".json")


def run_envelope(scene_file: str, out: str, voxel: Optional[float] = None,
                 hoses: Optional[List[str]] = None) -> Dict[str, np.ndarray]:
    """The swept volume of one run over its timeline (e.g. a study's ``runs/<id>.json``):
    runs it and writes ``<hose>.stl`` and ``envelope.glb`` into ``out``; returns the voxel
    keys per hose (same grid as the study's for the same voxel size)."""
    import pliant

    from .variant import _toml, hose_radii

    with open(scene_file) as f:
        text = f.read()
    scene = pliant.load_scene(scene_file)
    raw = json.loads(text) if scene_file.endswith(".json") else _toml.loads(text)
    radii = hose_radii(raw)
    h = voxel or min(0.005, min(radii.values()) / 2)
    result = pliant.run_timeline(scene)
    os.makedirs(out, exist_ok=True)
    keys, meshes = {}, {}
    for hose in hoses or list(radii):
        keys[hose] = envelope.voxelize(np.asarray(result.positions(hose)), radii[hose], h)
        meshes[hose] = envelope.mesh(keys[hose], h)
        envelope.write_stl(os.path.join(out, f"{column_name(hose)}.stl"), *meshes[hose], name=f"pliant run envelope {hose}")
    envelope.write_glb(os.path.join(out, "envelope.glb"), meshes)
    return keys


def read_rows(out: str, schema=None):
    """All rows written so far (parts), sorted by run index, as a pyarrow Table."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    paths = sorted(glob.glob(os.path.join(out, "parts", "part-*.parquet")))
    tables = [pq.read_table(p, schema=schema) for p in paths]
    if not tables:
        return pa.Table.from_pylist([], schema=schema)
    table = pa.concat_tables(tables)
    # a run resumed after a crash between its row and the next flush may appear twice
    _, first = np.unique(np.asarray(table.column("index").to_pylist()), return_index=True)
    return table.take(first)


def envelope_outputs(study: Study, out: str, union: Dict[str, np.ndarray], voxel: float,
                     parts, frame) -> Dict[str, Any]:
    """Meshes (STL per hose, one GLB) and clearances; envelope/envelope.json says what."""
    folder = os.path.join(out, "envelope")
    meshes, info = {}, {"voxel_m": voxel, "method": "voxel occupancy, marching cubes (see docs/study.md)", "hoses": {}}
    for hose, keys in union.items():
        if len(keys) == 0:
            continue
        verts, faces = envelope.mesh(keys, voxel)
        meshes[hose] = (verts, faces)
        stl = os.path.join(folder, f"{column_name(hose)}.stl")
        envelope.write_stl(stl, verts, faces, name=f"pliant envelope {hose}")
        mesh_clearance = {p.name: _finite(np.nanmin(p.distance(verts))) for p in parts if p.kind != "unsupported"}
        lo, hi = verts.min(axis=0), verts.max(axis=0)
        info["hoses"][hose] = {
            "stl": os.path.basename(stl), "voxels": int(len(keys)), "volume_m3": float(len(keys) * voxel ** 3),
            "bounds_m": [lo.tolist(), hi.tolist()], "triangles": int(len(faces)),
            "closed": envelope.is_closed(faces), "mesh_clearance_m": mesh_clearance,
        }
    if meshes:
        envelope.write_glb(os.path.join(folder, "envelope.glb"), meshes)
        info["glb"] = "envelope.glb"
    tube = {}
    for p in parts:
        col = column_name("clearance", p.name, "m")
        if col in frame and frame[col].notna().any():
            i = frame[col].idxmin()
            tube[p.name] = {"clearance_m": float(frame[col].min()), "run_id": frame.loc[i, "run_id"]}
        else:
            tube[p.name] = {"clearance_m": None, "run_id": None}
    info["tube_clearance"] = tube
    with open(os.path.join(folder, "envelope.json"), "w") as f:
        json.dump(info, f, indent=2)
    return info


def _finite(x) -> Any:
    x = float(x)
    return x if np.isfinite(x) else None


def finish(study: Study, layout, schema, union, voxel, parts, log: Callable[[str], None]):
    """Writes results.parquet, the envelope and report.html; returns the rows (pandas)."""
    import pyarrow.parquet as pq

    from . import agreement
    from .report import write_report

    table = read_rows(layout.out, schema)
    pq.write_table(table, os.path.join(layout.out, "results.parquet"))
    frame = table.to_pandas()
    info = envelope_outputs(study, layout.out, union, voxel, parts, frame)
    write_report(study, layout.out, frame, info, agreement.read(layout.out))
    log(f"{len(frame)} runs in {os.path.join(layout.out, 'results.parquet')}; "
        f"report {os.path.join(layout.out, 'report.html')}")
    return frame
