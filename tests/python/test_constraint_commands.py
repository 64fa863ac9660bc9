# SPDX-License-Identifier: LGPL-2.1-or-later
"""The constraint commands' headless path: selection check, macro lines, one transaction."""

import FreeCAD
import pytest

import varsurf
from varsurf.app import actions, macro, selection
from varsurf.solve import constraints
from scenes import Sel, add_face, add_line_sketch, flat_face


@pytest.fixture
def sheet(doc, native):
    doc.UndoMode = 1
    surface = add_face(doc, flat_face())
    rail = add_line_sketch(doc, "Rail", 5.0, (20.0, 15.0), (40.0, 20.0))
    doc.recompute()
    s = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")])
    doc.recompute()
    return s


@pytest.mark.parametrize("kind", [k for k in constraints.KINDS if k not in selection.VERTEX_KINDS
                                  and k not in constraints.CURVE_KINDS and k not in constraints.SHAPE_KINDS
                                  and k not in ("G0", "CurveMap", "RegionMap")])
def test_every_kind_from_a_selected_sheet(sheet, kind):
    doc = sheet.Document
    lines = []
    c = actions.run_constraint_command(kind, [Sel(sheet, "Face1")],
                                       do_command=lambda line: (lines.append(line), macro.exec_line(line)))
    assert c is not None and c.Kind == kind
    assert c in sheet.Constraints
    assert any("varsurf.make_constraint(" in line and repr(kind) in line for line in lines), lines
    if kind == "FrozenRegion":
        # The default region (the sheet's middle half) covers part of the rail, which must lift
        # the sheet 5 mm there: freezing it contradicts the rail, and the Sheet says so.
        assert not sheet.isValid()
        assert "contradict" in sheet.getStatusString()
    else:
        assert sheet.isValid(), sheet.getStatusString()
        assert list(sheet.ConstraintNames) == [c.Label]
    # one undo removes it
    name = c.Name
    doc.undo()
    assert name not in [o.Name for o in doc.Objects]


def test_curve_map_from_a_sheet_and_two_edges_in_picking_order(sheet):
    import Part

    doc = sheet.Document
    source, destination = doc.addObject("Part::Feature", "Source"), doc.addObject("Part::Feature", "Destination")
    source.Shape = Part.LineSegment(FreeCAD.Vector(50, 40, 0), FreeCAD.Vector(80, 60, 0)).toShape()
    destination.Shape = Part.Arc(FreeCAD.Vector(50, 40, 3), FreeCAD.Vector(65, 52, 9),
                                 FreeCAD.Vector(80, 60, 3)).toShape()
    doc.recompute()
    with pytest.raises(ValueError, match="exactly two edges"):
        selection.constraint_selection_to_args("CurveMap", [Sel(sheet), Sel(source, "Edge1")])
    c = actions.run_constraint_command("CurveMap", [Sel(sheet), Sel(source, "Edge1"), Sel(destination, "Edge1")])
    assert c is not None and c.Curve[0] == source and c.Reference[0] == destination
    assert sheet.isValid(), sheet.getStatusString()
    assert sheet.ConstraintResiduals[list(sheet.ConstraintNames).index(c.Label)] < float(sheet.Tolerance)


def test_region_map_from_a_sheet_and_a_face(sheet):
    import Part

    doc = sheet.Document
    patch = doc.addObject("Part::Feature", "Patch")
    patch.Shape = Part.makePlane(30.0, 20.0, FreeCAD.Vector(40.0, 30.0, 4.0))
    doc.recompute()
    with pytest.raises(ValueError, match="exactly one face"):
        selection.constraint_selection_to_args("RegionMap", [Sel(sheet), Sel(patch, "Edge1")])
    lines = []
    c = actions.run_constraint_command("RegionMap", [Sel(sheet), Sel(patch, "Face1")],
                                       do_command=lambda line: (lines.append(line), macro.exec_line(line)))
    assert c is not None and c.Reference[0] == patch
    assert any("region=(0.25, 0.75, 0.25, 0.75)" in line for line in lines), lines
    # The middle half of the sheet, mapped onto a 30 x 20 mm plane 4 mm up, cannot also hold the
    # rail 5 mm up that crosses it: the Sheet names the contradiction and the constraint.
    assert not sheet.isValid()
    assert "contradict" in sheet.getStatusString() and c.Label in sheet.getStatusString()


def test_point_from_a_sheet_and_a_vertex(sheet):
    doc = sheet.Document
    pin = doc.addObject("Part::Vertex", "Pin")
    pin.X, pin.Y, pin.Z = 60.0, 50.0, 9.0
    doc.recompute()
    c = actions.run_constraint_command("Point", [Sel(sheet), Sel(pin, "Vertex1")])
    assert c is not None and c.Location[0] == pin
    assert sheet.ConstraintResiduals[0] < 1e-6


def test_point_from_a_whole_point_object(sheet):
    # A point object picked as a whole, without naming its vertex (as a Draft point usually is:
    # a feature whose shape is one vertex; Draft itself needs the GUI's PySide to import).
    import Part

    doc = sheet.Document
    point = doc.addObject("Part::Feature", "Point")
    point.Shape = Part.Vertex(FreeCAD.Vector(60.0, 50.0, 9.0))
    doc.recompute()
    c = actions.run_constraint_command("Point", [Sel(sheet), Sel(point)])
    assert c is not None and c.Location[0] == point
    assert sheet.isValid(), sheet.getStatusString()
    assert sheet.ConstraintResiduals[0] < 1e-6
    assert sheet.Shape.distToShape(point.Shape)[0] < 1e-6


@pytest.mark.parametrize("selection, text", [
    (lambda s, p: [], "0 Sheets"),
    (lambda s, p: [Sel(p, "Vertex1")], "0 Sheets"),
    (lambda s, p: [Sel(s)], "needs a vertex"),
    (lambda s, p: [Sel(s), Sel(s.Base[0])], "not a Sheet"),
])
def test_bad_selections_create_nothing(sheet, selection, text, console_errors):
    doc = sheet.Document
    pin = doc.addObject("Part::Vertex", "Pin")
    doc.recompute()
    before = len(doc.Objects)
    messages = []
    c = actions.run_constraint_command("Point", selection(sheet, pin), on_error=messages.append)
    assert c is None and len(doc.Objects) == before
    assert text in messages[0]
    assert text in console_errors()


def test_g1_from_a_sheet_an_edge_and_a_face(sheet):
    import Part

    doc = sheet.Document
    seam = doc.addObject("Part::Feature", "Seam")
    seam.Shape = Part.LineSegment(FreeCAD.Vector(60, 25, 0), FreeCAD.Vector(60, 55, 0)).toShape()
    face = doc.addObject("Part::Feature", "Flat")
    face.Shape = Part.makePlane(30, 40, FreeCAD.Vector(60, 20, 0))
    doc.recompute()
    lines = []
    c = actions.run_constraint_command("G1", [Sel(sheet), Sel(seam, "Edge1"), Sel(face, "Face1")],
                                       do_command=lambda line: (lines.append(line), macro.exec_line(line)))
    assert c is not None and c.Kind == "G1" and c.Curve[0] == seam and c.Reference[0] == face
    assert any("curve=" in line and "reference=" in line for line in lines), lines
    assert sheet.isValid(), sheet.getStatusString()
    assert sheet.ConstraintResiduals[0] < 1.0
    messages = []
    assert actions.run_constraint_command("G1", [Sel(sheet), Sel(seam, "Edge1")], on_error=messages.append) is None
    assert "exactly one edge and one face" in messages[0]


def _scene(doc):
    """A seam on the base, a second edge 20 mm over and 7 up, a roof face 9 mm up, a flat face
    containing the seam, and a closed triangle of edges over the base."""
    import types

    import Part

    o = types.SimpleNamespace()
    o.seam = doc.addObject("Part::Feature", "Seam")
    o.seam.Shape = Part.LineSegment(FreeCAD.Vector(60, 25, 0), FreeCAD.Vector(60, 55, 0)).toShape()
    o.second = doc.addObject("Part::Feature", "Second")
    o.second.Shape = Part.LineSegment(FreeCAD.Vector(80, 25, 7), FreeCAD.Vector(80, 55, 7)).toShape()
    o.roof = doc.addObject("Part::Feature", "Roof")
    o.roof.Shape = Part.makePlane(60, 40, FreeCAD.Vector(20, 20, 9))
    o.flat = doc.addObject("Part::Feature", "Flat")
    o.flat.Shape = Part.makePlane(30, 40, FreeCAD.Vector(60, 20, 0))
    o.loop = doc.addObject("Part::Feature", "Loop")
    o.loop.Shape = Part.makePolygon([FreeCAD.Vector(*p) for p in
                                     [(55, 30, 0), (85, 30, 0), (70, 60, 0), (55, 30, 0)]])
    doc.recompute()
    return o


LOOP_EDGES = lambda o: [Sel(o.loop, "Edge1"), Sel(o.loop, "Edge2"), Sel(o.loop, "Edge3")]  # noqa: E731


@pytest.mark.parametrize("kind, picks, expect", [
    ("Ribbon", lambda o: [Sel(o.seam, "Edge1")], dict(curve="Seam")),
    ("Ribbon", lambda o: [Sel(o.seam, "Edge1"), Sel(o.second, "Edge1")], dict(curve="Seam", reference="Second")),
    ("Ribbon", lambda o: [Sel(o.seam, "Edge1"), Sel(o.flat, "Face1")], dict(curve="Seam", reference="Flat")),
    ("CurveAttractor", lambda o: [Sel(o.second, "Edge1")], dict(curve="Second")),
    ("G0", lambda o: [Sel(o.second, "Edge1")], dict(curve="Second")),
    ("SurfaceAttractor", lambda o: [Sel(o.roof, "Face1")], dict(reference="Roof")),
    ("SurfaceAttractor", lambda o: [Sel(o.roof, "Face1")] + LOOP_EDGES(o), dict(reference="Roof", region_loop="Loop")),
    ("PointAttractor", LOOP_EDGES, dict(region_loop="Loop")),
    ("FrozenRegion", LOOP_EDGES, dict(region_loop="Loop")),
])
def test_kinds_that_take_edges_and_faces(sheet, kind, picks, expect):
    doc = sheet.Document
    o = _scene(doc)
    lines = []
    c = actions.run_constraint_command(kind, [Sel(sheet)] + picks(o),
                                       do_command=lambda line: (lines.append(line), macro.exec_line(line)))
    assert c is not None and c.Kind == kind
    for prop, label in dict(curve="Curve", reference="Reference", region_loop="RegionLoop").items():
        link = getattr(c, label)
        assert (link[0].Name if link else None) == expect.get(prop), (prop, link)
        assert (prop + "=" in lines[1]) == (prop in expect), lines[1]
    assert sheet.isValid(), sheet.getStatusString()
    assert list(sheet.ConstraintNames) == [c.Label]
    if "region_loop" in expect:
        assert "region=" not in lines[1]


@pytest.mark.parametrize("kind, picks, text", [
    ("CurveAttractor", lambda o: [], "exactly one edge"),
    ("CurveAttractor", lambda o: [Sel(o.roof, "Face1")], "exactly one edge"),
    ("SurfaceAttractor", lambda o: [Sel(o.seam, "Edge1")], "exactly one face"),
    ("Ribbon", lambda o: [], "one edge and at most"),
    ("Ribbon", lambda o: [Sel(o.seam, "Edge1"), Sel(o.second, "Edge1"), Sel(o.flat, "Face1")], "one edge and at most"),
    ("Director", lambda o: [Sel(o.roof, "Face1")], "cannot be used here"),
    ("Director", lambda o: [Sel(o.loop, "Edge1"), Sel(o.seam, "Edge1")], "one object"),
    ("Normal", lambda o: [Sel(o.seam, "Edge1")], "cannot be used here"),
])
def test_bad_selections_of_edge_and_face_kinds(sheet, kind, picks, text):
    doc = sheet.Document
    o = _scene(doc)
    before = len(doc.Objects)
    messages = []
    assert actions.run_constraint_command(kind, [Sel(sheet)] + picks(o), on_error=messages.append) is None
    assert len(doc.Objects) == before
    assert text in messages[0], messages
