"""Tolerance envelopes (SPEC T2): the volume each hose sweeps over all runs and all
recorded instants, as a voxel occupancy set and as a closed triangle mesh (STL, GLB).

Method (shared with ``pliant run``'s swept envelopes, pliant_assembly::sweep): the
recorded centre line of a run (nodes at the record interval) is sampled at most h/2 apart
(h the voxel size, samples merged on an h/4 grid); a voxel (centre on the grid i·h) is
occupied when its centre lies within r + (√3/2)(h + h/4) + h/4 of a sample (r the hose's
outer radius), i.e. it touches the tube, allowing for the sampling. The union over runs is an exact set
operation, so the envelope does not depend on the order runs finish in. The mesh is the
0.5 iso-surface of the occupancy (marching cubes, scikit-image, Lewiner), closed because
the grid is padded: it contains every sampled centre-line point of every run while
r ≥ (√3/2) h, and is conservative by about one voxel.
"""

from __future__ import annotations

import json
import math
import struct
from typing import Dict, Tuple

import numpy as np

OFF = 1 << 20  # keys: (i + OFF) << 42 | (j + OFF) << 21 | (k + OFF)


def pack(ijk: np.ndarray) -> np.ndarray:
    ijk = ijk.astype(np.int64) + OFF
    return (ijk[:, 0] << 42) | (ijk[:, 1] << 21) | ijk[:, 2]


def unpack(keys: np.ndarray) -> np.ndarray:
    keys = np.asarray(keys, dtype=np.int64)
    mask = (1 << 21) - 1
    return np.stack([(keys >> 42) & mask, (keys >> 21) & mask, keys & mask], axis=1) - OFF


def sorted_unique(keys: np.ndarray, kind: str = "quicksort") -> np.ndarray:
    """np.unique of int64 keys by sorting (several times faster than its hash table on
    the ~10⁵ keys of a run)."""
    keys = np.sort(keys, kind=kind)
    if len(keys) < 2:
        return keys
    return keys[np.concatenate(([True], keys[1:] != keys[:-1]))]


def union(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Sorted union of two sorted key sets. numpy's stable sort of int64 is a timsort,
    which finds the two sorted runs and merges them in linear time — a quicksort of the
    concatenation costs O(n log n) each time a study's growing union takes a run."""
    return sorted_unique(np.concatenate([a, b]), kind="stable")


def sample_keys(frames: np.ndarray, h: float) -> np.ndarray:
    """Sorted keys of the centre-line samples of the frames (T, N, 3) [m]: every element
    of every frame sampled at n + 1 points at most h/2 apart (the same n for all, from the
    longest element), merged on the h/4 grid — what :func:`voxels_of_samples` dilates.
    Samples of several runs may be united (:func:`union`) first and dilated once: the
    voxel set is the same, because a voxel is in when it is within reach of *any* sample.
    (In Rust, ``pliant._pliant.centreline_sample_keys``; ValueError for frames no hose
    has.)"""
    from .._pliant import centreline_sample_keys

    return centreline_sample_keys(np.ascontiguousarray(frames, dtype=np.float64), float(h))


def voxelize(frames: np.ndarray, radius: float, h: float) -> np.ndarray:
    """Sorted keys of the voxels the tube of this radius around the frames touches."""
    return voxels_of_samples(sample_keys(frames, h), radius, h)


def voxels_of_samples(samples: np.ndarray, radius: float, h: float) -> np.ndarray:
    """Sorted keys of the voxels whose centre lies within reach of a sample (keys of
    :func:`sample_keys`): the tube of this radius around the sampled centre lines. (In
    Rust, ``pliant._pliant.swept_voxel_keys``, the voxels of ``pliant run``'s swept
    envelopes too; ValueError for a region too large for voxels of this size.)"""
    from .._pliant import swept_voxel_keys

    if len(samples) == 0:
        return np.zeros(0, np.int64)
    return swept_voxel_keys(np.ascontiguousarray(samples, dtype=np.int64), float(radius), float(h))


def mesh(keys: np.ndarray, h: float) -> Tuple[np.ndarray, np.ndarray]:
    """Closed surface (vertices [m] (V, 3), faces (F, 3)) around the occupied voxels."""
    from skimage.measure import marching_cubes

    ijk = unpack(keys)
    lo = ijk.min(axis=0) - 1
    shape = ijk.max(axis=0) - lo + 2
    vol = np.zeros(shape, dtype=np.float32)
    vol[tuple((ijk - lo).T)] = 1.0
    verts, faces, _, _ = marching_cubes(vol, 0.5, spacing=(h, h, h), allow_degenerate=False)
    return verts + lo * h, faces.astype(np.int64)


def winding_number(verts: np.ndarray, faces: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Generalised winding number of a closed mesh at each point (≈ ±1 inside, 0 outside)."""
    tri = verts[faces]
    out = np.zeros(len(points))
    for s in range(0, len(points), 64):
        p = points[s:s + 64, None, None, :]
        r = tri[None] - p  # (P, F, 3, 3)
        n = np.linalg.norm(r, axis=-1)
        a, b, c = r[..., 0, :], r[..., 1, :], r[..., 2, :]
        det = np.einsum("pfi,pfi->pf", a, np.cross(b, c))
        la, lb, lc = n[..., 0], n[..., 1], n[..., 2]
        den = la * lb * lc + (a * b).sum(-1) * lc + (b * c).sum(-1) * la + (c * a).sum(-1) * lb
        out[s:s + 64] = (2 * np.arctan2(det, den)).sum(axis=1) / (4 * math.pi)
    return out


def is_closed(faces: np.ndarray) -> bool:
    """Every edge shared by exactly two faces, once in each direction (watertight, oriented)."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    directed = np.unique(e, axis=0, return_counts=True)[1]
    undirected = np.unique(np.sort(e, axis=1), axis=0, return_counts=True)[1]
    return bool((directed == 1).all() and (undirected == 2).all())


def write_stl(path: str, verts: np.ndarray, faces: np.ndarray, name: str = "envelope") -> None:
    """Binary STL (metres)."""
    tri = verts[faces].astype(np.float32)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-30)
    rec = np.zeros(len(faces), dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    rec["n"], rec["v"] = normal, tri
    with open(path, "wb") as f:
        f.write(name.encode()[:80].ljust(80, b" "))
        f.write(struct.pack("<I", len(faces)))
        f.write(rec.tobytes())


def write_glb(path: str, meshes: Dict[str, Tuple[np.ndarray, np.ndarray]]) -> None:
    """Binary glTF 2.0 with one named mesh per hose (metres, z up as in the scene)."""
    bin_parts, views, accessors, gl_meshes, nodes = [], [], [], [], []
    offset = 0
    for name, (verts, faces) in meshes.items():
        for data, target, ctype, kind in (
            (verts.astype("<f4"), 34962, 5126, "VEC3"),
            (faces.astype("<u4").ravel(), 34963, 5125, "SCALAR"),
        ):
            blob = data.tobytes()
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob), "target": target})
            acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": len(data), "type": kind}
            if kind == "VEC3":
                acc.update(min=verts.min(axis=0).tolist(), max=verts.max(axis=0).tolist())
            accessors.append(acc)
            blob += b"\0" * (-len(blob) % 4)
            bin_parts.append(blob)
            offset += len(blob)
        gl_meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1}]})
        nodes.append({"name": name, "mesh": len(gl_meshes) - 1})
    binary = b"".join(bin_parts)
    doc = {
        "asset": {"version": "2.0", "generator": "pliant study"},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
        "meshes": gl_meshes, "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(binary)}],
    }
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(binary)))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(binary), 0x004E4942) + binary)
