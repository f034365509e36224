"""Distances from points to the scene's rigid parts [m], for clearances.

Primitives (box, sphere, cylinder) use their exact signed distance (negative inside; the
engine's cylinder is a prism of ``segments`` sides inscribed in the circle, so this
distance is up to r (1 − cos π/n) too large). OBJ and STL meshes use the exact unsigned
distance to their triangles (a point inside a closed mesh reads as its depth, not as a
negative number). glTF parts are not read here: their clearance is NaN.
"""

from __future__ import annotations

import math
import os
import struct
from dataclasses import dataclass
from typing import Any, Dict, List, Optional

import numpy as np

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
        """min over points of (distance − offset), exactly; meshes measure the 256 points
        nearest their bounding box, then the others in order of that distance until no
        closer one can follow."""
        if self.kind != "mesh":
            d = self.distance(points) - offset
            return float(np.nanmin(d)) if np.isfinite(d).any() else float("nan")
        if len(points) == 0:
            return np.inf
        lo, hi = self.triangles.reshape(-1, 3).min(axis=0), self.triangles.reshape(-1, 3).max(axis=0)
        gap = np.maximum(np.maximum(lo - points, points - hi), 0)
        bound = np.sqrt(np.einsum("ij,ij->i", gap, gap)) - offset
        # the 256 nearest by the bound first, then only the points that may beat them
        first = np.argpartition(bound, 255)[:256] if len(bound) > 256 else np.arange(len(bound))
        best = float((_mesh_distance(points[first], self.triangles) - offset[first]).min())
        rest = np.flatnonzero(bound < best)
        order = rest[np.argsort(bound[rest])]
        for s in range(0, len(order), 256):
            idx = order[s:s + 256]
            if bound[idx[0]] >= best:
                break
            best = min(best, float((_mesh_distance(points[idx], self.triangles) - offset[idx]).min()))
        return best

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance of each point (K, 3) to the part's surface; NaN if it cannot be told."""
        if self.kind == "unsupported":
            return np.full(len(points), np.nan)
        if self.kind == "mesh":
            return _mesh_distance(points, self.triangles)
        # coordinates in the part's frame, R^T (p − x), one contiguous column per axis
        x, y, z = self.rotation.T @ (points - self.position).T
        if self.kind == "sphere":
            return np.sqrt(x * x + y * y + z * z) - self.size[0]
        if self.kind == "box":
            qs = [np.abs(c) - s / 2 for c, s in zip((x, y, z), self.size)]
        else:
            r, h = self.size
            qs = [np.sqrt(x * x + y * y) - r, np.abs(z) - h / 2]
        # signed distance to the box (or the cylinder's (radius, height) rectangle):
        # |max(q, 0)| outside, max_i q_i (≤ 0) inside
        outside = sum(np.maximum(q, 0) ** 2 for q in qs)
        return np.sqrt(outside) + np.minimum(np.maximum.reduce(qs), 0)


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


def _mesh_distance(points: np.ndarray, tri: np.ndarray, chunk: int = 2048) -> np.ndarray:
    """Exact unsigned distance of points (K, 3) to triangles (F, 3, 3) (Ericson's
    closest-point regions, vectorised over points × triangles in chunks)."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    ab, ac = b - a, c - a
    best = np.full(len(points), np.inf)
    for s in range(0, len(points), chunk):
        p = points[s:s + chunk, None, :]
        closest = _closest_on_triangles(p, a, b, c, ab, ac)
        best[s:s + chunk] = np.sqrt(((p - closest) ** 2).sum(-1)).min(axis=1)
    return best


def _closest_on_triangles(p, a, b, c, ab, ac):
    dot = lambda u, v: (u * v).sum(-1)  # noqa: E731
    ap, bp, cp = p - a, p - b, p - c
    d1, d2 = dot(ab, ap), dot(ac, ap)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v = np.where(denom != 0, vb / denom, 0.0)
        w = np.where(denom != 0, vc / denom, 0.0)
        out = a + ab * v[..., None] + ac * w[..., None]  # inside the face
        # edges (later assignments win where regions overlap at vertices, as in Ericson)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        out = np.where(((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0))[..., None], b + (c - b) * t_bc[..., None], out)
        t_ac = d2 / (d2 - d6)
        out = np.where(((vb <= 0) & (d2 >= 0) & (d6 <= 0))[..., None], a + ac * t_ac[..., None], out)
        t_ab = d1 / (d1 - d3)
        out = np.where(((vc <= 0) & (d1 >= 0) & (d3 <= 0))[..., None], a + ab * t_ab[..., None], out)
        out = np.where(((d6 >= 0) & (d5 <= d6))[..., None], c + 0 * out, out)
        out = np.where(((d3 >= 0) & (d4 <= d3))[..., None], b + 0 * out, out)
        out = np.where(((d1 <= 0) & (d2 <= 0))[..., None], a + 0 * out, out)
    return out
