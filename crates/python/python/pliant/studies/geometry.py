"""Distances from points to the scene's rigid parts [m], for clearances.

Primitives (box, sphere, cylinder) use their exact signed distance (negative inside; the
engine's cylinder is a prism of ``segments`` sides inscribed in the circle, so this
distance is up to r (1 − cos π/n) too large). OBJ and STL meshes use the exact unsigned
distance to their triangles (a point inside a closed mesh reads as its depth, not as a
negative number). glTF parts are not read here: their clearance is NaN. The distances are
measured in Rust (``crates/python/src/part_distance.rs``).
"""

from __future__ import annotations

import math
import os
import struct
from dataclasses import dataclass
from typing import Any, Dict, List, Optional

import numpy as np

from .. import _pliant
from .variant import length_factor

UNITS = {"m": 1.0, "mm": 1e-3}


@dataclass
class Part:
    """A part's shape in its local frame (metres) and its pose."""

    name: str
    kind: str  # box, sphere, cylinder, mesh, unsupported
    position: np.ndarray
    rotation: np.ndarray  # local → world
    size: Optional[np.ndarray] = None  # box edges; (radius, height) of a cylinder; (radius,) of a sphere
    triangles: Optional[np.ndarray] = None  # (F, 3, 3) in world coordinates

    def min_distance(self, points: np.ndarray, offset: np.ndarray) -> float:
        """min over points of (distance − offset), exactly (NaN if it cannot be told);
        measured in Rust (``pliant._pliant.part_clearance``: meshes measure only the points
        whose distance to the mesh's bounding box beats the best so far)."""
        if self.kind == "unsupported":
            return float("nan")
        if len(points) == 0:
            return np.inf
        d = _pliant.part_clearance(np.ascontiguousarray(points, float), np.ascontiguousarray(offset, float),
                                   *self._shape())
        return d if np.isfinite(d) else float("nan")

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance of each point (K, 3) to the part's surface; NaN if it cannot be told."""
        if self.kind == "unsupported":
            return np.full(len(points), np.nan)
        return _pliant.part_distances(np.ascontiguousarray(points, float), *self._shape())

    def _shape(self) -> tuple:
        """The arguments after the points of ``part_distances`` / ``part_clearance``."""
        size = [] if self.size is None else [float(v) for v in self.size]
        tri = None if self.triangles is None else np.ascontiguousarray(self.triangles, float)
        return self.kind, self.position.tolist(), self.rotation.tolist(), size, tri


def _rotation(rot: Optional[Dict[str, Any]]) -> np.ndarray:
    if not rot:
        return np.eye(3)
    k = np.asarray(rot["axis"], float)
    k = k / np.linalg.norm(k)
    a = math.radians(rot.get("angle_deg", 0.0))
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * K @ K


def read_mesh(path: str) -> np.ndarray:
    """Triangles (F, 3, 3) of an OBJ or STL file, in the file's units."""
    lower = path.lower()
    if lower.endswith(".obj"):
        verts: List[List[float]] = []
        faces: List[List[int]] = []
        with open(path) as f:
            for line in f:
                tok = line.split()
                if not tok:
                    continue
                if tok[0] == "v":
                    verts.append([float(x) for x in tok[1:4]])
                elif tok[0] == "f":
                    idx = [int(t.split("/")[0]) for t in tok[1:]]
                    idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                    faces += [[idx[0], idx[j], idx[j + 1]] for j in range(1, len(idx) - 1)]
        return np.asarray(verts)[np.asarray(faces)]
    with open(path, "rb") as f:
        data = f.read()
    if len(data) >= 84:
        (count,) = struct.unpack("<I", data[80:84])
        if 84 + 50 * count == len(data):  # binary STL
            rec = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
            return rec["v"].astype(float)
    nums = [list(map(float, line.split()[1:4])) for line in data.decode(errors="replace").splitlines()
            if line.strip().startswith("vertex")]
    return np.asarray(nums).reshape(-1, 3, 3)


def parts(scene: Dict[str, Any]) -> List[Part]:
    """The scene's parts (mesh paths absolute or relative to the current directory)."""
    unit = length_factor(scene)
    out = []
    for p in scene.get("parts", []):
        R = _rotation(p.get("rotation"))
        x = np.asarray(p.get("position", [0, 0, 0]), float) * unit
        if "box" in p:
            out.append(Part(p["name"], "box", x, R, size=np.asarray(p["box"]["size"], float) * unit))
        elif "sphere" in p:
            out.append(Part(p["name"], "sphere", x, R, size=np.array([p["sphere"]["radius"] * unit])))
        elif "cylinder" in p:
            c = p["cylinder"]
            out.append(Part(p["name"], "cylinder", x, R, size=np.array([c["radius"], c["height"]]) * unit))
        elif str(p.get("mesh", "")).lower().endswith((".obj", ".stl")) and os.path.isfile(p["mesh"]):
            s = UNITS[p.get("mesh_unit", scene.get("length_unit", "m"))]
            tri = read_mesh(p["mesh"]) * s
            out.append(Part(p["name"], "mesh", x, R, triangles=tri @ R.T + x))
        else:
            out.append(Part(p["name"], "unsupported", x, R))
    return out
