# SPDX-License-Identifier: LGPL-2.1-or-later
"""A Solid follows its Sheets: it is in error, naming the sheet, while one of them is, and is
rebuilt once the sheet is repaired; its tolerance follows theirs, so a 12 m model joins as a
100 mm one does."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from scenes import recompute_all, reopened

V = FreeCAD.Vector


def _feature(doc, name, shape):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shape
    return obj


def _arc(doc, name, a, apex, b):
    return _feature(doc, name, Part.Edge(Part.Arc(V(*a), V(*apex), V(*b))))


def _pillow_with_a_flat_top(doc):
    """The pillow of the examples with no pressure on its top: a wavy elliptic rim (80 x 50 mm)
    both sheets contain, the bottom inflated downward."""
    points = [V(40 * math.cos(t), 25 * math.sin(t), 4 * math.sin(2 * t))
              for t in (2 * math.pi * k / 64 for k in range(64))]
    curve = Part.BSplineCurve()
    curve.interpolate(points, PeriodicFlag=True)
    rim = _feature(doc, "Rim", curve.toShape())
    sheets = []
    for name, pressure in (("Top", 0.0), ("Bottom", -0.1)):
        base = _feature(doc, name + "Base", Part.makePlane(120, 90, V(-60, -45, 0)))
        doc.recompute()
        sheet = varsurf.make_sheet((base, "Face1"), [(rim, "Edge1")], name=name)
        sheet.Stretch, sheet.Pressure = 1.0, pressure
        sheets.append(sheet)
    solid = varsurf.make_solid(sheets, name="Pillow")
    doc.recompute()
    assert solid.isValid() and solid.Closed, solid.Status
    return solid, sheets[0], sheets[1]


def test_a_solid_is_in_error_while_a_sheet_is_and_follows_its_repair(doc, native, console_errors):
    solid, top, bottom = _pillow_with_a_flat_top(doc)
    volume = solid.Shape.Volume
    # Two arcs over the top that cross in plan at the centre but at heights 6 and 2 mm: no sheet
    # contains both.
    across = _arc(doc, "Across", (-20, 0, 0), (0, 0, 6), (20, 0, 0))
    along = _arc(doc, "Along", (0, -12, 0), (0, 0, 2), (0, 12, 0))
    top.Curves = list(top.Curves) + [(across, "Edge1"), (along, "Edge1")]
    console_errors()
    doc.recompute()
    assert not top.isValid() and "contradict" in top.Status, top.Status
    assert not solid.isValid(), solid.Status
    assert solid.Status.startswith("Error: Top is in error (") and "contradict" in solid.Status, solid.Status
    assert not solid.Closed
    assert "VarSurf: Pillow: Top is in error" in console_errors()
    assert bottom.isValid() and bottom.Status.startswith("OK")  # the other sheet is untouched
    # Recomputing again changes nothing: the Solid stays in error with the sheet.
    recompute_all(doc)
    assert not top.isValid() and not solid.isValid() and "Top is in error" in solid.Status
    # Repaired: the second arc is taken off the top. The Solid is rebuilt from the repaired sheet
    # (not its last good result): its top passes through the first arc.
    top.Curves = [link for link in top.Curves if link[0] is not along]
    doc.recompute()
    assert top.isValid() and top.Status.startswith("OK"), top.Status
    assert solid.isValid() and solid.Closed and solid.Status.startswith("OK: solid"), solid.Status
    assert solid.Shape.distToShape(Part.Vertex(V(0, 0, 6)))[0] <= top.Tolerance.Value
    for p in across.Shape.discretize(20):
        assert solid.Shape.distToShape(Part.Vertex(p))[0] <= top.Tolerance.Value
    assert solid.Shape.isValid() and solid.Shape.Volume > volume + 100.0  # the top lifted over the arc
    # A sheet in error among several: each is named.
    bottom.Tolerance = 1e9
    doc.recompute()
    assert not bottom.isValid() and "Bottom is in error" in solid.Status and not solid.isValid()
    bottom.Tolerance = 0.01
    doc.recompute()
    assert solid.isValid() and solid.Status.startswith("OK"), solid.Status


SCALE = 150.0  # the 80 x 50 mm pillow of the examples, 12 m long


def _pillow(doc, scale):
    """The pillow example scaled: a wavy elliptic rim, two flat bases, two sheets pushed apart
    by a pressure (scaled so that the stretch holds it alike), the sheets' tolerance left to
    follow the model's size."""
    points = [V(40 * math.cos(t), 25 * math.sin(t), 4 * math.sin(2 * t)) * scale
              for t in (2 * math.pi * k / 64 for k in range(64))]
    curve = Part.BSplineCurve()
    curve.interpolate(points, PeriodicFlag=True)
    rim = _feature(doc, "Rim", curve.toShape())
    sheets = []
    for name, pressure in (("Top", 0.1), ("Bottom", -0.1)):
        base = _feature(doc, name + "Base", Part.makePlane(120 * scale, 90 * scale, V(-60, -45, 0) * scale))
        doc.recompute()
        sheet = varsurf.make_sheet((base, "Face1"), [(rim, "Edge1")], name=name)
        sheet.Stretch = 1.0
        sheet.Pressure = pressure / scale
        sheets.append(sheet)
    solid = varsurf.make_solid(sheets, name="Pillow")
    doc.recompute()
    return solid, rim


def test_a_12_m_solid_joins_within_its_sheets_tolerance(doc, native, tmp_path):
    solid, rim = _pillow(doc, SCALE)
    sheets = list(solid.Sheets)
    own = max(s.Tolerance.Value for s in sheets)
    assert own == pytest.approx(2.0)  # 1e-4 of the 22.5 m base, rounded down
    assert all(s.isValid() and s.Status.startswith("OK") for s in sheets), [s.Status for s in sheets]
    assert solid.isValid() and solid.Closed, solid.Status
    assert solid.ToleranceFromSheets and solid.Tolerance.Value == pytest.approx(2 * own, rel=1e-12)
    gaps = list(solid.SeamGaps)
    # The sheets pass farther from the rim than a fixed 0.02 mm would allow, within their own
    # tolerance, and the seam lies on the rim as closely.
    assert 0.02 < max(gaps) <= own, gaps
    for edge in solid.Shape.Edges:
        for p in edge.discretize(40):
            assert rim.Shape.distToShape(Part.Vertex(p))[0] <= own
    assert solid.Shape.isValid() and solid.MaxEdgeTolerance <= own

    # A Tolerance typed by hand is the user's: below the sheets' own, the join fails and says why.
    solid.Tolerance = 0.02
    doc.recompute()
    assert not solid.ToleranceFromSheets and not solid.isValid()
    assert "from a join curve" in solid.Status and "below its sheets' own, up to 2 mm" in solid.Status, solid.Status
    solid.ToleranceFromSheets = True
    doc.recompute()
    assert solid.isValid() and solid.Tolerance.Value == pytest.approx(4.0), solid.Status

    # The Solid follows the sheets' tolerance when they change.
    for s in sheets:
        s.Tolerance = 1.0
    doc.recompute()
    assert solid.isValid() and solid.Tolerance.Value == pytest.approx(2.0), solid.Status
    assert max(solid.SeamGaps) <= 1.0

    # Saved and reopened, it still follows; a Solid from before it could (no such property)
    # keeps the Tolerance it was saved with.
    name = solid.Name
    solid.removeProperty("ToleranceFromSheets")
    solid.Tolerance = 3.0
    with reopened(doc, tmp_path / "pillow12m.FCStd") as again:
        old = again.getObject(name)
        assert not old.ToleranceFromSheets and old.Tolerance.Value == pytest.approx(3.0)
        recompute_all(again)
        assert old.isValid() and old.Tolerance.Value == pytest.approx(3.0), old.Status


def _line(doc, name, a, b):
    return _feature(doc, name, Part.LineSegment(V(*a), V(*b)).toShape())


def test_a_sheet_of_an_open_shell_keeps_its_interior_curves(doc, native):
    # Two flat sheets side by side, x in [5, 50] and [50, 95], y in [5, 55], sharing the seam
    # x = 50; their own edges complete their loops. An arc across plate A's interior shapes it
    # but does not bound it.
    seam = _line(doc, "Seam", (50, 5, 0), (50, 55, 0))
    own_a = [_line(doc, "A1", (50, 55, 0), (5, 55, 0)), _line(doc, "A2", (5, 55, 0), (5, 5, 0)),
             _line(doc, "A3", (5, 5, 0), (50, 5, 0))]
    own_b = [_line(doc, "B1", (50, 55, 0), (95, 55, 0)), _line(doc, "B2", (95, 55, 0), (95, 5, 0)),
             _line(doc, "B3", (95, 5, 0), (50, 5, 0))]
    base_a = _feature(doc, "BaseA", Part.makePlane(60, 70, V(-5, -5, 0)))
    base_b = _feature(doc, "BaseB", Part.makePlane(60, 70, V(45, -5, 0)))
    doc.recompute()
    a = varsurf.make_sheet((base_a, "Face1"), [(o, "Edge1") for o in [seam] + own_a], name="PlateA")
    b = varsurf.make_sheet((base_b, "Face1"), [(o, "Edge1") for o in [seam] + own_b], name="PlateB")
    solid = varsurf.make_solid([a, b], name="Plates")
    doc.recompute()
    assert solid.isValid() and solid.Status.startswith("OK: open shell"), solid.Status
    assert solid.Shape.Area == pytest.approx(2 * 45 * 50, rel=1e-6)  # two flat 45 x 50 mm faces
    arc = _arc(doc, "Across", (15, 30, 0), (27.5, 30, 6), (40, 30, 0))
    a.Curves = list(a.Curves) + [(arc, "Edge1")]
    doc.recompute()
    assert a.isValid() and solid.isValid() and solid.Status.startswith("OK: open shell"), solid.Status
    assert len(solid.Shape.Faces) == 2 and solid.Shape.isValid()
    for p in arc.Shape.discretize(20):
        assert solid.Shape.distToShape(Part.Vertex(p))[0] <= a.Tolerance.Value
    # Still bounded by the seam and its own edges (the arc's ends are no corners), lifted inside.
    corners = {(x, y) for x in (5, 50, 95) for y in (5, 55)}
    found = {(round(v.X, 6), round(v.Y, 6)) for v in solid.Shape.Vertexes}
    assert found == corners and all(abs(v.Z) < 1e-9 for v in solid.Shape.Vertexes), found
    assert solid.Shape.Area > 2 * 45 * 50 + 10.0
