"""STEP (AP203, AP214, AP242) to a triangle mesh per solid, with OpenCASCADE (`OCP`).

This file is self-contained (it imports only the standard library and ``OCP``): the
``pliant`` binary embeds it and runs it with the repository's Python interpreter to
fill its STEP cache, and ``python -m pliant.cad`` runs the same code.

Two jobs:

``mesh``
    Reads a STEP assembly with its product structure (XCAF: names and placements),
    tessellates every solid with a chord tolerance (``BRepMesh_IncrementalMesh``,
    linear deflection in metres, angular deflection 0.5 rad), and writes one binary glTF
    (``.glb``): one node per solid occurrence, named after the STEP product/instance
    (``assembly/part/solid``), its vertices in world coordinates **in metres** (OCCT
    converts the file's length unit, e.g. inches, to millimetres on reading; this module
    scales by 1e-3). The asset's ``extras.pliant`` records the source's SHA-256, the
    tolerance, the converter's version, the file's units, and the solids it skipped and
    why: nothing is dropped silently.

``curve``
    Samples one edge or wire of a STEP file (picked by name or index among the file's
    curves that are not face boundaries of a solid) into points within a chord tolerance,
    in metres, written as JSON.

Errors (file unreadable, truncated, entity not supported) exit with status 2 and one
line on stderr naming the entity (``#123 = TYPE``) or the line, when known.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import re
import struct
import sys
import time

#: Bumped whenever the output changes; part of the cache key with the source's hash.
CONVERTER_VERSION = "1"

#: Default chord tolerance (largest distance of a triangle from the surface) [m].
DEFAULT_TOLERANCE = 0.5e-3
#: Angular deflection between neighbouring triangle normals [rad].
ANGULAR_DEFLECTION = 0.5


class StepError(Exception):
    """A STEP file that cannot be converted; the message names the entity or line."""


# --------------------------------------------------------------------------- checks


_ENTITY = re.compile(rb"#(\d+)\s*=\s*([A-Za-z0-9_]*)")


def check_part21(data: bytes) -> None:
    """Checks the ISO 10303-21 frame before OCCT sees the file: header, DATA section,
    terminated last entity, END-ISO-10303-21. OCCT reads a truncated file silently (it
    drops what it cannot parse), so truncation is caught here, naming the last entity
    and its line."""
    head = data[:4096].lstrip()
    if not head.startswith(b"ISO-10303-21;"):
        raise StepError("not a STEP file: it does not start with ISO-10303-21;")
    if b"DATA;" not in data:
        raise StepError("no DATA section: the file is truncated or not a STEP file")
    tail = data.rstrip()
    if not tail.endswith(b"END-ISO-10303-21;"):
        last = None
        for m in _ENTITY.finditer(data, max(0, len(data) - 65536)):
            last = m
        if last is None:
            raise StepError("the file is truncated: it does not end with END-ISO-10303-21;")
        line = data.count(b"\n", 0, last.start()) + 1
        raise StepError(
            "the file is truncated: it ends inside or after entity #%s = %s (line %d) "
            "without END-ISO-10303-21;"
            % (last.group(1).decode(), last.group(2).decode() or "?", line)
        )


# ------------------------------------------------------------------------- reading


def _label_name(label) -> str:
    from OCP.TDataStd import TDataStd_Name

    attr = TDataStd_Name()
    if label.FindAttribute(TDataStd_Name.GetID_s(), attr):
        name = attr.Get().ToExtString().strip()
        # OCCT names an unnamed instance after the label it refers to: "=>[0:1:1:3]"
        return "" if name.startswith("=>") else name
    return ""


def _file_units(reader) -> list:
    from OCP.collections import Sequence_TCollection_AsciiString as TColStd_SequenceOfAsciiString

    names, a, s = (TColStd_SequenceOfAsciiString() for _ in range(3))
    try:
        reader.Reader().FileUnits(names, a, s)
        return sorted({names.Value(i).ToCString() for i in range(1, names.Length() + 1)})
    except Exception:  # pragma: no cover - informative only
        return []


def read_document(path: str):
    """Reads a STEP file into an XCAF document; returns (doc, reader)."""
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDocStd import TDocStd_Document

    with open(path, "rb") as f:
        data = f.read()
    check_part21(data)
    doc = TDocStd_Document(TCollection_ExtendedString("pliant"))
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    reader.SetColorMode(False)
    reader.SetLayerMode(False)
    reader.SetGDTMode(False)
    status = reader.ReadFile(path)
    if status != IFSelect_RetDone:
        raise StepError("OpenCASCADE cannot read the file (status %s)" % status)
    if not reader.Transfer(doc):
        raise StepError("OpenCASCADE read the file but transferred no shape from it")
    return doc, reader


def root_entities(reader) -> str:
    """The file's root entities by STEP type, e.g. "2 × PRODUCT_DEFINITION", for
    messages."""
    try:
        r = reader.Reader()
        counts = {}
        for i in range(1, r.NbRootsForTransfer() + 1):
            name = r.RootForTransfer(i).DynamicType().Name().split("_", 1)[-1]
            step = re.sub(r"(?<!^)(?=[A-Z])", "_", name).upper()
            counts[step] = counts.get(step, 0) + 1
        return ", ".join("%d × %s" % (n, t) for t, n in counts.items()) or "none"
    except Exception:  # pragma: no cover - informative only
        return "unknown"


def occurrences(doc):
    """Every solid occurrence of the assembly: (name, shape placed in the world).

    Walks the free shapes and their components; a leaf shape contributes each of its
    solids (or, with no solid, itself: shells and faces). Names join the path of
    instance (else product) names with "/", made unique with "#2", "#3", …"""
    from OCP.collections import Sequence_TDF_Label as TDF_LabelSequence
    from OCP.TopAbs import TopAbs_FACE, TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool
    from OCP.TDF import TDF_Label

    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    free = TDF_LabelSequence()
    tool.GetFreeShapes(free)
    out = []
    used = {}

    def unique(name):
        n = used.get(name, 0) + 1
        used[name] = n
        return name if n == 1 else "%s#%d" % (name, n)

    def walk(label, loc, path, depth):
        if depth > 64:
            raise StepError("the assembly is nested deeper than 64 levels (a cycle?)")
        if XCAFDoc_ShapeTool.IsAssembly_s(label):
            comps = TDF_LabelSequence()
            XCAFDoc_ShapeTool.GetComponents_s(label, comps, False)
            for i in range(1, comps.Length() + 1):
                comp = comps.Value(i)
                ref = TDF_Label()
                if not XCAFDoc_ShapeTool.GetReferredShape_s(comp, ref):
                    continue
                name = _label_name(comp) or _label_name(ref) or "component %d" % i
                sub = path if path and path[-1] == name else path + [name]
                walk(ref, loc.Multiplied(XCAFDoc_ShapeTool.GetLocation_s(comp)),
                     sub, depth + 1)
            return
        shape = XCAFDoc_ShapeTool.GetShape_s(label)
        if shape.IsNull():
            return
        solids = []
        ex = TopExp_Explorer(shape, TopAbs_SOLID)
        while ex.More():
            solids.append(ex.Current())
            ex.Next()
        base = "/".join(path) or "solid"
        if not solids:
            if not TopExp_Explorer(shape, TopAbs_FACE).More():
                return  # points, curves, axes: no surface to collide with
            out.append((unique(base), shape.Moved(loc), shape))
        for k, s in enumerate(solids):
            name = base if len(solids) == 1 else "%s/solid %d" % (base, k + 1)
            out.append((unique(name), s.Moved(loc), s))

    for i in range(1, free.Length() + 1):
        label = free.Value(i)
        name = _label_name(label)
        walk(label, TopLoc_Location(), [name] if name else [], 0)
    return out


# ------------------------------------------------------------------------ meshing


def triangulate(shape, mm_to_m: float):
    """Triangles of a meshed, placed shape: (flat positions [m], flat indices), and the
    number of faces that have no triangulation."""
    from OCP.BRep import BRep_Tool
    from OCP.TopAbs import TopAbs_FACE, TopAbs_REVERSED
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS

    pos, idx = [], []
    missing = 0
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        face = TopoDS.Face(ex.Current())
        ex.Next()
        loc = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(face, loc)
        if tri is None:
            missing += 1
            continue
        trsf = loc.Transformation()
        base = len(pos) // 3
        for i in range(1, tri.NbNodes() + 1):
            p = tri.Node(i).Transformed(trsf)
            pos.extend((p.X() * mm_to_m, p.Y() * mm_to_m, p.Z() * mm_to_m))
        flip = face.Orientation() == TopAbs_REVERSED
        for i in range(1, tri.NbTriangles() + 1):
            a, b, c = tri.Triangle(i).Get()
            if flip:
                b, c = c, b
            idx.extend((base + a - 1, base + b - 1, base + c - 1))
    return pos, idx, missing


def mesh_step(path: str, tolerance: float = DEFAULT_TOLERANCE) -> dict:
    """Reads and tessellates a STEP file: ``{"solids": [(name, positions, indices)],
    "skipped": [...], "units": [...], "seconds": t}``."""
    from OCP.BRepMesh import BRepMesh_IncrementalMesh

    if not (tolerance > 0 and math.isfinite(tolerance)):
        raise StepError("the chord tolerance must be > 0 (metres), not %r" % tolerance)
    t0 = time.perf_counter()
    doc, reader = read_document(path)
    mm_to_m = 1e-3  # OCCT's session unit is the millimetre; the file's unit is converted
    skipped = []
    solids = []
    meshed = {}  # hash → prototypes meshed (a prototype is shared by its instances)
    distinct = 0
    for name, placed, proto in occurrences(doc):
        bucket = meshed.setdefault(hash(proto), [])
        try:
            if not any(p.IsPartner(proto) for p in bucket):
                BRepMesh_IncrementalMesh(proto, tolerance / mm_to_m, False,
                                         ANGULAR_DEFLECTION, True)
                bucket.append(proto)
                distinct += 1
            pos, idx, missing = triangulate(placed, mm_to_m)
        except Exception as e:  # OCCT raises Standard_Failure subclasses
            skipped.append("%s: tessellation failed (%s)" % (name, e))
            continue
        if not idx:
            skipped.append("%s: no triangles (%d faces could not be tessellated)"
                           % (name, missing))
            continue
        if missing:
            skipped.append("%s: %d faces could not be tessellated (the rest is kept)"
                           % (name, missing))
        solids.append((name, pos, idx))
    if not solids:
        why = "; ".join(skipped) if skipped else "the file holds no solid or surface"
        raise StepError("no solid could be read: %s (the file's root entities: %s)"
                        % (why, root_entities(reader)))
    return {
        "solids": solids,
        "distinct": distinct,
        "skipped": skipped,
        "units": _file_units(reader),
        "seconds": time.perf_counter() - t0,
    }


# ---------------------------------------------------------------------------- GLB


def write_glb(out_path: str, solids, extras: dict) -> None:
    """A binary glTF 2.0: one mesh and one node per solid (positions f32 in metres,
    u32 indices), the asset's ``extras`` carrying ``extras``."""
    nodes, meshes, accessors, views = [], [], [], []
    blob = bytearray()
    for k, (name, pos, idx) in enumerate(solids):
        p = struct.pack("<%df" % len(pos), *pos)
        lo = [min(pos[j::3]) for j in range(3)]
        hi = [max(pos[j::3]) for j in range(3)]
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(p),
                      "target": 34962})
        blob += p
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126,
                          "count": len(pos) // 3, "type": "VEC3", "min": lo, "max": hi})
        i = struct.pack("<%dI" % len(idx), *idx)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(i),
                      "target": 34963})
        blob += i
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125,
                          "count": len(idx), "type": "SCALAR"})
        meshes.append({"name": name, "primitives": [
            {"attributes": {"POSITION": len(accessors) - 2},
             "indices": len(accessors) - 1, "mode": 4}]})
        nodes.append({"name": name, "mesh": k})
    doc = {
        "asset": {"version": "2.0", "generator": "pliant.cad %s" % CONVERTER_VERSION,
                  "extras": {"pliant": extras}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "accessors": accessors,
        "bufferViews": views, "buffers": [{"byteLength": len(blob)}],
    }
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    blob += b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(js) + 8 + len(blob)
    tmp = out_path + ".part"
    with open(tmp, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, total))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(blob), 0x004E4942) + bytes(blob))
    import os

    os.replace(tmp, out_path)  # readers never see a half-written cache file


def sha256_file(path: str) -> str:
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def convert(step: str, out: str, tolerance: float = DEFAULT_TOLERANCE) -> dict:
    """STEP → GLB; returns the summary (also stored in the GLB's extras)."""
    result = mesh_step(step, tolerance)
    summary = {
        "source_sha256": sha256_file(step),
        "tolerance_m": tolerance,
        "converter": CONVERTER_VERSION,
        "file_units": result["units"],
        "solids": len(result["solids"]),
        "distinct_solids": result["distinct"],
        "triangles": sum(len(i) // 3 for _, _, i in result["solids"]),
        "skipped": result["skipped"],
        "seconds": round(result["seconds"], 3),
    }
    write_glb(out, result["solids"], summary)
    return summary


# -------------------------------------------------------------------------- curves


def list_curves(doc):
    """The file's curves a hose may follow: free edges and wires (not face boundaries
    of a solid or shell), as (name, shape); unnamed ones are called "curve N"."""
    from OCP.collections import Sequence_TDF_Label as TDF_LabelSequence
    from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_WIRE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool
    from OCP.TDF import TDF_Label

    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    free = TDF_LabelSequence()
    tool.GetFreeShapes(free)
    out = []

    def collect(shape, name):
        if shape.IsNull():
            return
        if TopExp_Explorer(shape, TopAbs_FACE).More():
            # only the free wires/edges beside faces
            ex = TopExp_Explorer(shape, TopAbs_WIRE, TopAbs_FACE)
            while ex.More():
                out.append((name, ex.Current()))
                ex.Next()
            ex = TopExp_Explorer(shape, TopAbs_EDGE, TopAbs_WIRE)
            while ex.More():
                out.append((name, ex.Current()))
                ex.Next()
            return
        wires = TopExp_Explorer(shape, TopAbs_WIRE)
        while wires.More():
            out.append((name, wires.Current()))
            wires.Next()
        loose = []
        ex = TopExp_Explorer(shape, TopAbs_EDGE, TopAbs_WIRE)
        while ex.More():
            loose.append(ex.Current())
            ex.Next()
        if len(loose) > 1:
            # STEP stores a wire as a set of edges: join them again, in order
            from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeWire
            from OCP.TopoDS import TopoDS

            mw = BRepBuilderAPI_MakeWire()
            for e in loose:
                mw.Add(TopoDS.Edge(e))
            if mw.IsDone():
                loose = [mw.Wire()]
        out.extend((name, e) for e in loose)

    def walk(label, loc, name, depth):
        if depth > 64:
            return
        if XCAFDoc_ShapeTool.IsAssembly_s(label):
            comps = TDF_LabelSequence()
            XCAFDoc_ShapeTool.GetComponents_s(label, comps, False)
            for i in range(1, comps.Length() + 1):
                comp, ref = comps.Value(i), TDF_Label()
                if XCAFDoc_ShapeTool.GetReferredShape_s(comp, ref):
                    walk(ref, loc.Multiplied(XCAFDoc_ShapeTool.GetLocation_s(comp)),
                         _label_name(comp) or _label_name(ref), depth + 1)
            return
        shape = XCAFDoc_ShapeTool.GetShape_s(label).Moved(loc)
        collect(shape, _label_name(label) or name)
        subs = TDF_LabelSequence()
        XCAFDoc_ShapeTool.GetSubShapes_s(label, subs)
        for i in range(1, subs.Length() + 1):
            sub = subs.Value(i)
            nm = _label_name(sub)
            if nm:
                # a named sub-shape names the curve it holds
                s = XCAFDoc_ShapeTool.GetShape_s(sub).Moved(loc)
                for j, (n, c) in enumerate(out):
                    if c.IsSame(s):
                        out[j] = (nm, c)

    for i in range(1, free.Length() + 1):
        walk(free.Value(i), TopLoc_Location(), _label_name(free.Value(i)), 0)
    return [(n or "curve %d" % k, c) for k, (n, c) in enumerate(out)]


def sample_curve(shape, tolerance: float, mm_to_m: float = 1e-3) -> list:
    """Points along an edge or wire within ``tolerance`` [m] of it (chord deflection),
    in order, in metres."""
    from OCP.BRepAdaptor import BRepAdaptor_CompCurve, BRepAdaptor_Curve
    from OCP.GCPnts import GCPnts_QuasiUniformDeflection
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopoDS import TopoDS

    if shape.ShapeType() == TopAbs_EDGE:
        curve = BRepAdaptor_Curve(TopoDS.Edge(shape))
    else:
        curve = BRepAdaptor_CompCurve(TopoDS.Wire(shape))
    sampler = GCPnts_QuasiUniformDeflection(curve, tolerance / mm_to_m)
    if not sampler.IsDone() or sampler.NbPoints() < 2:
        raise StepError("the curve could not be sampled")
    pts = []
    for i in range(1, sampler.NbPoints() + 1):
        p = sampler.Value(i)
        q = (p.X() * mm_to_m, p.Y() * mm_to_m, p.Z() * mm_to_m)
        if not pts or any(abs(a - b) > 1e-12 for a, b in zip(q, pts[-1])):
            pts.append(q)
    return pts


def extract_curve(step: str, name=None, index=None, tolerance=1e-5) -> dict:
    """One curve of a STEP file by name or index, sampled (see :func:`sample_curve`)."""
    doc, _ = read_document(step)
    curves = list_curves(doc)
    names = [n for n, _ in curves]
    if not curves:
        raise StepError("the file holds no free curve (edge or wire outside a solid)")
    if name is not None:
        hits = [c for n, c in curves if n == name]
        if not hits:
            raise StepError("no curve named %r; the file's curves are: %s"
                            % (name, ", ".join(repr(n) for n in names)))
        shape = hits[0]
    else:
        if index is None or not 0 <= index < len(curves):
            raise StepError("curve index %r is out of range: the file has %d curves (%s)"
                            % (index, len(curves), ", ".join(repr(n) for n in names)))
        shape = curves[index][1]
    return {"points": sample_curve(shape, tolerance), "tolerance_m": tolerance,
            "curves": names, "converter": CONVERTER_VERSION}


# ----------------------------------------------------------------------------- CLI


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pliant.cad",
                                 description="STEP import for Pliant (OpenCASCADE)")
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("import", help="STEP → GLB, one named node per solid, metres")
    m.add_argument("step")
    m.add_argument("--out", required=True)
    m.add_argument("--tolerance", type=float, default=DEFAULT_TOLERANCE,
                   help="chord tolerance [m] (default %(default)s)")
    c = sub.add_parser("curve", help="sample one curve of a STEP file to JSON points [m]")
    c.add_argument("step")
    g = c.add_mutually_exclusive_group(required=True)
    g.add_argument("--name")
    g.add_argument("--index", type=int)
    c.add_argument("--tolerance", type=float, default=1e-5)
    c.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    try:
        if a.cmd == "import":
            summary = convert(a.step, a.out, a.tolerance)
            print(json.dumps(summary))
            for s in summary["skipped"]:
                print("warning: skipped %s" % s, file=sys.stderr)
        else:
            res = extract_curve(a.step, a.name, a.index, a.tolerance)
            tmp = a.out + ".part"
            with open(tmp, "w") as f:
                json.dump(res, f)
            import os

            os.replace(tmp, a.out)
            print(json.dumps({"points": len(res["points"]), "curves": res["curves"]}))
    except StepError as e:
        print("error: %s" % e, file=sys.stderr)
        return 2
    except OSError as e:
        print("error: %s" % e, file=sys.stderr)
        return 2
    except Exception as e:  # an OCCT exception: name it, never a bare traceback
        print("error: OpenCASCADE failed on the file: %s: %s" % (type(e).__name__, e),
              file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
