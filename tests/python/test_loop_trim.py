# SPDX-License-Identifier: LGPL-2.1-or-later
"""A sheet made from curves alone ends on the closed loop among them, as Surface Filling's face
ends on its boundary edges: five wavy sides of a pentagon and two interior curves, in any order
and orientation, against Part's own filling of the same loop."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from step_check import assert_reads_back

V = FreeCAD.Vector
RADIUS = 30.0


def _corners():
    return [V(RADIUS * math.cos(2 * math.pi * k / 5), RADIUS * math.sin(2 * math.pi * k / 5), 0.0) for k in range(5)]


def _side(a, b, lift):
    """From corner a to corner b, rising by ``lift`` in its middle."""
    d = b - a
    curve = Part.BSplineCurve()
    curve.buildFromPoles([a, a + d * (1 / 3) + V(0, 0, lift), a + d * (2 / 3) + V(0, 0, lift), b])
    return curve.toShape()


def _loop():
    c = _corners()
    return [_side(c[k], c[(k + 1) % 5], 4.0 * (-1) ** k) for k in range(5)]


def _interior():
    return [Part.LineSegment(V(-12, -4, 2.0), V(12, -4, 2.0)).toShape(),
            Part.LineSegment(V(-4, 6, -1.5), V(8, 12, -1.5)).toShape()]


def _sheet(doc, edges, **kwargs):
    objs = []
    for k, edge in enumerate(edges):
        o = doc.addObject("Part::Feature", f"Curve{k}")
        o.Shape = edge
        objs.append((o, "Edge1"))
    doc.recompute()
    sheet = varsurf.make_sheet(None, objs, tolerance=0.001, **kwargs)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    return sheet


def test_the_sheet_ends_on_its_loop_like_a_filling(doc, native, tmp_path):
    loop, interior = _loop(), _interior()
    sheet = _sheet(doc, loop + interior)
    face = sheet.Shape.Faces[0]
    assert len(sheet.Shape.Faces) == 1 and len(face.Edges) == 5
    assert sorted(sheet.BoundaryCurves) == sorted(f"Curve{k}:Edge1" for k in range(5))
    # Each boundary edge lies on its curve (within the sheet's tolerance), measured by OCCT.
    for edge in face.Edges:
        assert min(max(c.distToShape(Part.Vertex(p))[0] for p in edge.discretize(40)) for c in loop) <= 0.001
    # Every curve, boundary and interior, on the sheet.
    assert max(sheet.MaxDeviations) <= 0.001
    assert sheet.Shape.isValid() and sheet.Shape.check(True) is None
    # The same loop filled by OCCT's plate (Part.makeFilledFace, what Surface Filling builds on):
    # the two faces cover nearly the same area (measured: 2217 and 2196 mm², 1.0 % apart; the
    # untrimmed rectangle has 4795).
    filling = Part.makeFilledFace(loop)
    assert face.Area == pytest.approx(filling.Area, rel=0.05)
    path = tmp_path / "pentagon.step"
    varsurf.export_step([sheet], str(path))
    assert_reads_back(sheet.Shape, path, native)


def test_order_and_orientation_of_the_curves_do_not_matter(doc, native):
    loop, interior = _loop(), _interior()
    first = _sheet(doc, loop + interior)
    shuffled = [loop[3], loop[0].reversed(), interior[1], loop[4], loop[1].reversed(), interior[0], loop[2]]
    second = _sheet(doc, shuffled)
    assert len(second.Shape.Faces[0].Edges) == 5
    assert second.Shape.Area == pytest.approx(first.Shape.Area, rel=1e-6)


def test_without_a_loop_or_when_turned_off_the_sheet_is_its_rectangle(doc, native, tmp_path):
    loop, interior = _loop(), _interior()
    off = _sheet(doc, loop + interior)
    off.TrimToLoop = False
    doc.recompute()
    assert len(off.Shape.Faces[0].Edges) == 4 and off.BoundaryCurves == []
    open_curves = _sheet(doc, loop[:4] + interior)  # four sides: no closed loop
    assert len(open_curves.Shape.Faces[0].Edges) == 4 and open_curves.BoundaryCurves == []
    # A file from before TrimToLoop keeps its rectangle when it is opened again.
    trimmed = _sheet(doc, loop + interior)
    trimmed.removeProperty("TrimToLoop")
    path = str(tmp_path / "older.FCStd")
    doc.saveAs(path)
    again = FreeCAD.openDocument(path)
    try:
        sheet = again.getObject(trimmed.Name)
        assert sheet.TrimToLoop is False
        sheet.touch()
        again.recompute()
        assert len(sheet.Shape.Faces[0].Edges) == 4
    finally:
        FreeCAD.closeDocument(again.Name)
