"""Writes route.step beside this file: two named hose routes for the route tests, made
with OpenCASCADE (run with the .venv python that has OCP; the output is committed).

- "hose_route": a B-spline edge interpolating a helix of radius 100 mm and pitch
  200 mm/turn, one turn, about the z axis, starting at (100, 0, 0) mm;
- "guide": a polyline wire (0,0,0) → (100,0,0) → (100,100,0) → (100,100,100) mm.

Units: millimetres (the file says so).
"""

import math
import os

from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakePolygon
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.collections import HArray1_gp_Pnt as TColgp_HArray1OfPnt
from OCP.gp import gp_Pnt
from OCP.STEPCAFControl import STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_AsIs
from OCP.TCollection import TCollection_ExtendedString
from OCP.TDataStd import TDataStd_Name
from OCP.TDocStd import TDocStd_Document
from OCP.XCAFDoc import XCAFDoc_DocumentTool

R, PITCH, N = 100.0, 200.0, 73


def helix(t):
    return gp_Pnt(R * math.cos(t), R * math.sin(t), PITCH * t / (2 * math.pi))


pts = TColgp_HArray1OfPnt(1, N)
for i in range(N):
    pts.SetValue(i + 1, helix(2 * math.pi * i / (N - 1)))
interp = GeomAPI_Interpolate(pts, False, 1e-6)
interp.Perform()
edge = BRepBuilderAPI_MakeEdge(interp.Curve()).Edge()

poly = BRepBuilderAPI_MakePolygon()
for p in [(0, 0, 0), (100, 0, 0), (100, 100, 0), (100, 100, 100)]:
    poly.Add(gp_Pnt(*p))
wire = poly.Wire()

doc = TDocStd_Document(TCollection_ExtendedString("route"))
tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
for shape, name in [(edge, "hose_route"), (wire, "guide")]:
    label = tool.AddShape(shape, False)
    TDataStd_Name.Set_s(label, TCollection_ExtendedString(name))
writer = STEPCAFControl_Writer()
writer.Transfer(doc, STEPControl_AsIs)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "route.step")
writer.Write(out)
print("wrote", out)
