"""The Solid feature: sheets joined along shared curves, trimmed and sewn into a solid; the
pillow example, STEP and save/reopen round trips, edits, and bad inputs."""

import math
import sys
from pathlib import Path

import FreeCAD
import Part
import pytest

import varsurf

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples"))
import pillow  # noqa: E402

V = FreeCAD.Vector


@pytest.fixture
def solid(doc, native):
    s = pillow.build(doc)
    assert s.isValid(), s.getStatusString()
    return s


def test_pillow_is_a_valid_closed_solid(solid):
    shape = solid.Shape
    assert solid.Closed and solid.Status.startswith("OK: solid")
    assert shape.ShapeType == "Solid" and len(shape.Faces) == 2
    assert shape.isValid() and shape.check(True) is None
    assert shape.Volume > 1000.0  # mm^3, outward oriented
    assert max(solid.SeamGaps) <= solid.Tolerance.Value
    # A pillow's rim is a thin lip: the faces meet at a small angle all along it.
    assert solid.SeamAngles and all(0.0 <= a < 45.0 for a in solid.SeamAngles), list(solid.SeamAngles)
    assert solid.MaxEdgeTolerance <= solid.Tolerance.Value
    # The seam: the two faces' shared edge lies on the rim (sampled, measured by OCCT).
    rim = solid.Document.getObject("Rim").Shape
    for edge in shape.Edges:
        for p in edge.discretize(50):
            assert rim.distToShape(Part.Vertex(p))[0] <= solid.Tolerance.Value


def test_step_and_save_round_trips(solid, native, tmp_path):
    doc = solid.Document
    shape = solid.Shape
    path = str(tmp_path / "pillow.step")
    varsurf.export_step([solid], path)
    from step_check import assert_reads_back

    back = assert_reads_back(shape, path, native)
    assert len(back.Solids) == 1
    from scenes import recompute_all, reopened

    name, volume = solid.Name, shape.Volume
    with reopened(doc, tmp_path / "pillow.FCStd") as again:
        s = again.getObject(name)
        assert s.Shape.Volume == pytest.approx(volume, rel=1e-12)
        recompute_all(again)
        assert s.isValid(), s.getStatusString()
        assert s.Shape.Volume == pytest.approx(volume, rel=1e-9)


def test_editing_the_shared_curve_updates_both_sheets(solid):
    doc = solid.Document
    rim = doc.getObject("Rim")
    before = solid.Shape.Volume
    rim.Shape = rim.Shape.copy().scale(1.2)  # a bigger rim
    doc.recompute()
    assert solid.isValid() and solid.Closed, solid.Status
    assert solid.Shape.isValid()
    assert solid.Shape.Volume > 1.3 * before  # area grows by 1.44


def test_bad_inputs_are_reported(doc, native, console_errors):
    rim = doc.addObject("Part::Feature", "Arc")
    rim.Shape = Part.Edge(Part.Arc(V(-30, 0, 0), V(0, 20, 2), V(30, 0, 0)))  # open: no loop
    lone = doc.addObject("Part::Feature", "Lone")
    lone.Shape = Part.LineSegment(V(-20, -20, 1), V(20, -20, 1)).toShape()
    sheets = []
    for name, curves in (("A", [(rim, "Edge1")]), ("B", [(rim, "Edge1")]), ("C", [(lone, "Edge1")])):
        base = doc.addObject("Part::Feature", name + "Base")
        base.Shape = Part.makePlane(120, 90, V(-60, -45, 0))
        doc.recompute()
        sheets.append(varsurf.make_sheet((base, "Face1"), curves, name=name))
    doc.recompute()
    open_loop = varsurf.make_solid(sheets[:2], name="OpenLoop")
    doc.recompute()
    status = open_loop.getStatusString()
    assert not open_loop.isValid() and "does not close" in status, status
    unshared = varsurf.make_solid([sheets[0], sheets[1], sheets[2]], name="Unshared")
    doc.recompute()
    # A and B fail on their open loop first; C shares nothing: either is reported, nothing built.
    assert not unshared.isValid() and unshared.Shape.isNull()
    empty = varsurf.make_solid([sheets[2]], name="Alone")
    doc.recompute()
    assert not empty.isValid() and "shares no curve" in empty.getStatusString()
    assert "VarSurf" in console_errors()
    with pytest.raises(ValueError):
        varsurf.make_solid([])


def test_solid_command_joins_selected_sheets_in_one_transaction(doc, native):
    from varsurf import api
    from scenes import Sel

    pillow.build(doc)  # makes a Pillow already; the command adds a second Solid of the same Sheets
    doc.UndoMode = 1
    top, bottom = doc.getObject("Top"), doc.getObject("Bottom")
    lines = []
    s = api.run_solid_command([Sel(top), Sel(bottom, "Face1")],
                              do_command=lambda l: (lines.append(l), api._exec_line(l)))
    assert s is not None and s.isValid() and s.Closed, s.Status
    assert any("varsurf.make_solid(" in l for l in lines), lines
    name = s.Name
    doc.undo()
    assert name not in [o.Name for o in doc.Objects]
    messages = []
    assert api.run_solid_command([Sel(top)], on_error=messages.append) is None
    assert "select two or more" in messages[0]
    rim = doc.getObject("Rim")
    assert api.run_solid_command([Sel(top), Sel(rim)], on_error=messages.append) is None
    assert "is not a Sheet" in messages[1]


def test_rounded_box_of_six_sheets_and_twelve_shared_curves(doc, native, tmp_path):
    import rounded_box

    solid = rounded_box.build(doc)
    assert solid.isValid() and solid.Closed, solid.Status
    shape = solid.Shape
    assert shape.ShapeType == "Solid" and len(shape.Faces) == 6
    assert shape.isValid() and shape.check(True) is None
    # Each of the twelve curves bounds two faces; the edges bow out, so the box is bigger than
    # the plain 100 mm cube but smaller than its bowed bounding box.
    assert 1.0e6 < shape.Volume < 112.0 ** 3
    # The seams are sharp: a bowed box meets at about 90 degrees (bulging faces open it a little).
    angles = list(solid.SeamAngles)
    assert len(angles) >= 24  # 12 curves, at least one edge each, (min, max) pairs
    assert all(60.0 < a < 130.0 for a in angles), angles
    path = str(tmp_path / "box.step")
    varsurf.export_step([solid], path)
    from step_check import assert_reads_back

    assert len(assert_reads_back(shape, path, native).Solids) == 1


def test_a_sheet_that_misses_a_join_curve_is_reported(solid):
    doc = solid.Document
    solid.Tolerance = 1e-5  # tighter than the sheets meet the rim (about 6e-4 mm)
    doc.recompute()
    assert not solid.isValid()
    assert "from a join curve" in solid.getStatusString(), solid.getStatusString()
    solid.Tolerance = 0.02
    doc.recompute()
    assert solid.isValid() and solid.Closed


def _line(doc, name, a, b):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = Part.LineSegment(V(*a), V(*b)).toShape()
    return obj


def test_two_sheets_meeting_at_an_angle_make_an_open_shell(doc, native):
    # Sheet A is the square x in [5, 50], y in [5, 55] at z = 0; sheet B continues it beyond the
    # seam x = 50, tilted up by 30 degrees. They share only the seam: their own edges complete
    # their loops and bound the open shell.
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    tilt = lambda x, y: (50 + (x - 50) * c, y, (x - 50) * s)  # noqa: E731
    seam = _line(doc, "Seam", (50, 5, 0), (50, 55, 0))
    own_a = [_line(doc, "A1", (50, 55, 0), (5, 55, 0)), _line(doc, "A2", (5, 55, 0), (5, 5, 0)),
             _line(doc, "A3", (5, 5, 0), (50, 5, 0))]
    own_b = [_line(doc, "B1", tilt(50, 55), tilt(95, 55)), _line(doc, "B2", tilt(95, 55), tilt(95, 5)),
             _line(doc, "B3", tilt(95, 5), tilt(50, 5))]
    base_a = doc.addObject("Part::Feature", "BaseA")
    base_a.Shape = Part.makePlane(70, 70, V(-5, -5, 0))
    base_b = doc.addObject("Part::Feature", "BaseB")
    base_b.Shape = Part.Face(Part.makePolygon([V(*tilt(x, y)) for x, y in
                                               ((45, -5), (105, -5), (105, 65), (45, 65), (45, -5))]))
    doc.recompute()
    a = varsurf.make_sheet((base_a, "Face1"), [(o, "Edge1") for o in [seam] + own_a], name="A")
    b = varsurf.make_sheet((base_b, "Face1"), [(o, "Edge1") for o in [seam] + own_b], name="B")
    solid = varsurf.make_solid([a, b], name="Hinge")
    doc.recompute()
    assert solid.isValid(), solid.getStatusString()
    assert not solid.Closed and "open shell" in solid.Status
    shape = solid.Shape
    assert len(shape.Faces) == 2 and shape.isValid()
    assert shape.Area == pytest.approx(2 * 45 * 50, rel=1e-4)  # two flat 45 x 50 mm faces
    angles = list(solid.SeamAngles)
    assert angles and all(abs(x - 150.0) < 0.05 for x in angles), angles
