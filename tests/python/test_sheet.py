# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Sheet feature end to end: creation, parametric updates, files, errors, accuracy."""

import json
import math
import subprocess
from pathlib import Path

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.solve import errors, settings
from varsurf.solve.sheet import solve_sheet_on_face
from varsurf.app import actions
from scenes import (
    Sel,
    add_arc_sketch,
    add_face,
    add_line_sketch,
    add_polyline_sketch,
    curved_face,
    flat_face,
    poles_of,
)

# Deviations are measured by the extension on the result face, independently of the solver.
SMALL = settings.DEFAULT_TOLERANCE  # mm: "the sheet passes through the curve" within its tolerance


@pytest.fixture
def scene(doc, native):
    """A flat 11 x 11 pole base and two straight sketch lines above it that do not cross in plan:
    a diagonal rail 14 mm up and a side line 6 mm up (both met exactly by the B-spline space)."""
    surface = add_face(doc, flat_face())
    rail = add_line_sketch(doc, "Rail", 14.0, (25.0, 20.0), (75.0, 60.0))  # diagonal, pulls up
    side = add_line_sketch(doc, "Side", 6.0, (60.0, 12.0), (88.0, 34.0))
    doc.recompute()
    return doc, surface, rail, side


def max_pole_shift(a, b):
    return max(math.dist(p, q) for p, q in zip(a, b))


def assert_ok(sheet, zmin=-5.0, zmax=30.0):
    assert sheet.isValid(), sheet.getStatusString()
    assert "Invalid" not in sheet.State and "Error" not in sheet.State
    assert not sheet.Shape.isNull() and sheet.Shape.isValid()
    assert sheet.Status.startswith("OK"), sheet.Status
    # a sane sheet: over the base footprint, between the heights of base and curves
    bb = sheet.Shape.BoundBox
    assert -1.0 < bb.XMin and bb.XMax < 101.0 and -1.0 < bb.YMin and bb.YMax < 81.0, bb
    assert zmin < bb.ZMin and bb.ZMax < zmax, bb


def test_sheet_via_api_passes_through_its_curves(scene):
    doc, surface, rail, side = scene
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (side, ("Edge1",))])
    doc.recompute()
    assert_ok(sheet)
    assert list(sheet.CurveNames) == ["Rail:Edge1", "Side:Edge1"]
    assert len(sheet.MaxDeviations) == 2
    assert max(sheet.MaxDeviations) < SMALL, list(sheet.MaxDeviations)
    assert sheet.DegreeU == 3 and sheet.DegreeV == 3
    assert sheet.PoleCountU >= 6 and sheet.PoleCountV >= 6
    assert sheet.SolveTime > 0.0 and sheet.ConstraintRank > 0
    # the rail is above the base: the sheet was pulled up, the boundary stayed
    base_face, result = surface.Shape.Faces[0], sheet.Shape.Faces[0]
    assert result.BoundBox.ZMax > base_face.BoundBox.ZMax + 5.0
    for edge in base_face.Edges:  # FixBoundary: the base boundary lies on the result
        for k in range(5):
            p = edge.valueAt(edge.FirstParameter + k / 4 * (edge.LastParameter - edge.FirstParameter))
            assert result.distToShape(Part.Vertex(p))[0] < 1e-6
    # the extension's measure agrees with FreeCAD's own distance
    d = sheet.Shape.distToShape(rail.Shape.Edges[0])[0]
    assert d < SMALL


def test_command_selection_path_makes_the_same_sheet(scene):
    doc, surface, rail, side = scene
    by_api = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (side, "Edge1")])
    doc.recompute()
    selection = [Sel(surface, "Face1"), Sel(rail, "Edge1"), Sel(side, "Edge1")]
    base, curves = varsurf.selection_to_sheet_args(selection)
    assert base == (surface, "Face1")
    by_command = actions.run_sheet_command(selection)  # what VarSurf_Sheet.Activated runs
    assert by_command is not None and by_command.Name != by_api.Name
    assert_ok(by_command)
    assert max_pole_shift(poles_of(by_api), poles_of(by_command)) < 1e-12
    # one undo step removes exactly what the command made
    assert doc.UndoNames[0] == actions.TRANSACTION_CREATE
    name = by_command.Name
    doc.undo()
    assert doc.getObject(name) is None and doc.getObject(by_api.Name) is not None
    doc.redo()
    assert doc.getObject(name) is not None


def test_editing_a_sketch_moves_the_sheet(scene):
    doc, surface, rail, side = scene
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (side, "Edge1")])
    doc.recompute()
    before = poles_of(sheet)
    rail.setDatum(3, FreeCAD.Units.Quantity("68 mm"))  # move the rail's end point (y)
    doc.recompute()
    assert_ok(sheet)
    assert abs(rail.Shape.Edges[0].Vertexes[1].Point.y - 68.0) < 1e-9
    assert max_pole_shift(before, poles_of(sheet)) > 0.5  # the shape followed
    assert max(sheet.MaxDeviations) < SMALL
    # and lifting the whole sketch lifts the sheet
    top = sheet.Shape.BoundBox.ZMax
    rail.Placement = FreeCAD.Placement(FreeCAD.Vector(0, 0, 20.0), FreeCAD.Rotation())
    doc.recompute()
    assert_ok(sheet)
    assert sheet.Shape.BoundBox.ZMax > top + 3.0
    assert max(sheet.MaxDeviations) < SMALL


REOPEN_SCRIPT = r"""
import json, sys
sys.path.append('/usr/lib/freecad-python3/lib')
import FreeCAD
doc = FreeCAD.openDocument(sys.argv[1])
sheet = doc.getObject(sys.argv[2])
sheet.touch()
doc.recompute()
surface = sheet.Shape.Faces[0].Surface
print("RESULT" + json.dumps({
    "state": list(sheet.State),
    "type": sheet.Proxy.Type,
    "proxy_module": type(sheet.Proxy).__module__,
    "bend": sheet.Bend,
    "poles": [[p.x, p.y, p.z] for row in surface.getPoles() for p in row],
    "deviations": list(sheet.MaxDeviations),
}))
"""


def test_save_and_reopen_recomputes_identical_poles(scene, tmp_path):
    doc, surface, rail, side = scene
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (side, "Edge1")], bend=2.0)
    doc.recompute()
    poles = poles_of(sheet)
    name = sheet.Name
    deviations = list(sheet.MaxDeviations)
    path = str(tmp_path / "sheet.FCStd")
    doc.saveAs(path)

    # a fresh FreeCAD process (same HOME, so the workbench is found as a Mod)
    run = subprocess.run(
        ["/usr/bin/python3", "-c", REOPEN_SCRIPT, path, name],
        capture_output=True, text=True, timeout=180,
    )
    lines = [ln for ln in run.stdout.splitlines() if ln.startswith("RESULT")]
    assert run.returncode == 0 and lines, run.stdout[-2000:] + run.stderr[-2000:]
    data = json.loads(lines[-1][len("RESULT"):])
    assert data["type"] == "VarSurf::Sheet" and data["proxy_module"] == "varsurf.app.sheet"
    assert "Invalid" not in data["state"] and data["bend"] == 2.0
    assert max_pole_shift(poles, [tuple(p) for p in data["poles"]]) < 1e-9
    assert data["deviations"] == pytest.approx(deviations, abs=1e-9)

    # and in this process, after closing the document
    FreeCAD.closeDocument(doc.Name)
    reopened = FreeCAD.openDocument(path)
    try:
        again = reopened.getObject(name)
        assert again.Stretch == 0.0 and again.FixBoundary is True
        again.touch()
        reopened.recompute()
        assert_ok(again)
        assert max_pole_shift(poles, poles_of(again)) < 1e-9
    finally:
        FreeCAD.closeDocument(reopened.Name)
        FreeCAD.newDocument("VarSurfTest")  # the fixture closes a document of this name


def test_step_export_reimports_as_the_same_face(scene, tmp_path, native):
    doc, surface, rail, side = scene
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (side, "Edge1")])
    doc.recompute()
    path = str(tmp_path / "out" / "sheet.step")
    assert varsurf.export_step([sheet], path) == path
    text = Path(path).read_text(errors="replace")
    assert "AUTOMOTIVE_DESIGN" in text.upper() or "AP214" in text.upper()  # AP214 schema
    assert native.check_brep(native.read_step(path)).valid
    from step_check import assert_reads_back

    assert_reads_back(sheet.Shape, path, native)

    import Import

    fresh = FreeCAD.newDocument("StepCheck")
    try:
        Import.insert(path, fresh.Name)
        shapes = [o.Shape for o in fresh.Objects if hasattr(o, "Shape") and not o.Shape.isNull()]
        faces = [f for s in shapes for f in s.Faces]
        assert len(faces) == 1
        face = faces[0]
        assert face.isValid()
        assert face.Surface.TypeId == "Part::GeomBSplineSurface"
        assert face.Area == pytest.approx(sheet.Shape.Area, rel=1e-6)
    finally:
        FreeCAD.closeDocument(fresh.Name)


def test_curve_off_the_face_is_an_error_naming_the_curve(scene, console_errors):
    doc, surface, rail, side = scene
    far = add_line_sketch(doc, "Far", 10.0, (400.0, 300.0), (480.0, 350.0))
    doc.recompute()
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (far, "Edge1")])
    doc.recompute()
    assert not sheet.isValid()
    assert "Invalid" in sheet.State or "Error" in sheet.State
    message = sheet.getStatusString()
    assert "Far:Edge1" in message and "runs beyond the base face" in message
    assert sheet.Label in message
    assert "Far:Edge1" in sheet.Status and sheet.Status.startswith("Error")
    assert "Far:Edge1" in console_errors()  # the report view names it too
    # the rest of the document is unaffected and stays usable
    assert surface.isValid() and rail.isValid() and far.isValid()
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    assert box.isValid() and box.Shape.Volume > 0
    # fix the input: move the sketch over the face, the sheet recovers
    far.setDatum(0, FreeCAD.Units.Quantity("30 mm"))
    far.setDatum(1, FreeCAD.Units.Quantity("55 mm"))
    far.setDatum(2, FreeCAD.Units.Quantity("50 mm"))
    far.setDatum(3, FreeCAD.Units.Quantity("70 mm"))
    doc.recompute()
    assert_ok(sheet)
    assert max(sheet.MaxDeviations) < SMALL


def test_curve_in_the_plane_of_a_planar_face_has_zero_deviation(doc, native):
    plane = doc.addObject("Part::Plane", "Plane")
    plane.Length, plane.Width = 100.0, 80.0
    arc = add_arc_sketch(doc, "Arc", 0.0, (50.0, 40.0), 25.0, 10.0, 250.0)
    poly = add_polyline_sketch(doc, "Poly", 0.0, [(10, 10), (40, 60), (90, 30)])
    doc.recompute()
    sheet = varsurf.make_sheet((plane, "Face1"), [(arc, "Edge1"), (poly, ("Edge1", "Edge2"))])
    doc.recompute()
    assert_ok(sheet)
    assert list(sheet.CurveNames) == ["Arc:Edge1", "Poly:Edge1", "Poly:Edge2"]
    assert max(sheet.MaxDeviations) < 1e-7, list(sheet.MaxDeviations)
    assert abs(sheet.Shape.BoundBox.ZMax) < 1e-7 and abs(sheet.Shape.BoundBox.ZMin) < 1e-7

    # the same on a planar bicubic B-spline face, without a fixed boundary
    flat = add_face(doc, flat_face(z=5.0, spans=3), "Flat")
    lifted = add_arc_sketch(doc, "Arc5", 5.0, (50.0, 40.0), 25.0, 10.0, 250.0)
    doc.recompute()
    free = varsurf.make_sheet((flat, "Face1"), [(lifted, "Edge1")], fix_boundary=False)
    doc.recompute()
    assert_ok(free)
    assert max(free.MaxDeviations) < 1e-7
    assert all(abs(p[2] - 5.0) < 1e-7 for p in poles_of(free))


def test_weights_change_the_shape_and_are_validated(scene):
    doc, surface, rail, side = scene
    plate = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")])
    membrane = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")], stretch=1.0, bend=0.0)
    doc.recompute()
    assert_ok(plate)
    assert_ok(membrane)
    assert max_pole_shift(poles_of(plate), poles_of(membrane)) > 0.1
    membrane.Stretch = 0.0
    doc.recompute()
    assert not membrane.isValid()
    assert "Stretch and Bend are both 0" in membrane.getStatusString()


def test_solve_sheet_on_face_without_a_document(native):
    face = flat_face()
    edge = Part.LineSegment(FreeCAD.Vector(20, 20, 12), FreeCAD.Vector(80, 60, 12)).toShape()
    outcome = solve_sheet_on_face(face, [edge], names=["rail"])
    assert outcome.curve_names == ["rail"]
    assert outcome.max_deviation < SMALL
    assert outcome.shape.ShapeType == "Face" and outcome.shape.isValid()
    assert "rail: max deviation" in outcome.summary()
    off = Part.LineSegment(FreeCAD.Vector(300, 20, 12), FreeCAD.Vector(380, 60, 12)).toShape()
    with pytest.raises(errors.SheetError, match="offside runs beyond the base face"):
        solve_sheet_on_face(face, [edge, off], names=["rail", "offside"])


def test_curved_base_sheet_is_fair(doc, native):
    # No curve is exactly representable over a curved base: the sheet must meet it within the
    # tolerance and stay between the base and the curve instead of overshooting.
    surface = add_face(doc, curved_face())
    rail = add_line_sketch(doc, "Rail", 14.0, (25.0, 20.0), (75.0, 60.0))
    doc.recompute()
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")])
    doc.recompute()
    assert_ok(sheet, zmin=-2.0, zmax=20.0)
    assert max(sheet.MaxDeviations) < SMALL


def test_contradictory_curves_are_an_error_not_a_wild_sheet(doc, native, console_errors):
    # A rail 14 mm up and an arc 9 mm up that cross in plan: no surface holds both. The sheet is
    # refined up to MaxSpans, then put in error with a message naming the conflict.
    surface = add_face(doc, flat_face())
    rail = add_line_sketch(doc, "Rail", 14.0, (25.0, 20.0), (75.0, 60.0))
    arc = add_arc_sketch(doc, "Arc", 9.0, (50.0, 40.0), 24.0, 200.0, 340.0)
    doc.recompute()
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1"), (arc, "Edge1")], max_spans=32)
    doc.recompute()
    assert not sheet.isValid()
    message = sheet.getStatusString()
    assert "contradict" in message and "32 spans" in message, message
    assert "Rail:Edge1" in message or "Arc:Edge1" in message, message
    assert "contradict" in console_errors()
    # dropping one of the two curves makes the sheet valid again
    sheet.Curves = [(rail, ("Edge1",))]
    doc.recompute()
    assert_ok(sheet)


def test_exact_curves_are_met_to_rounding_where_the_tolerance_fit_stops(scene):
    doc, surface, rail, side = scene
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")], tolerance=0.05)
    doc.recompute()
    fitted = sheet.MaxDeviations[0]
    sheet.ExactCurves = ["Rail:Edge1"]
    doc.recompute()
    assert_ok(sheet)
    exact = sheet.MaxDeviations[0]
    assert exact < 1e-7 and exact < 0.1 * fitted, (fitted, exact)
    sheet.ExactCurves = ["Nope:Edge9"]
    doc.recompute()
    assert not sheet.isValid() and "Nope:Edge9" in sheet.getStatusString()


def test_anisotropic_weights_reproduce_isotropic_and_change_the_shape(scene):
    doc, surface, rail, side = scene
    iso = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")], stretch=0.3, bend=1.0)
    same = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")], name="Same")
    same.StretchTensor = [0.3, 0.0, 0.3]  # alpha = 0.3 I
    same.BendTensor = [1.0, 1.0, 1.0]     # beta_ij = 1: w_uu^2 + 2 w_uv^2 + w_vv^2
    aniso = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")], name="Aniso")
    aniso.BendTensor = [1.0, 1.0, 20.0]   # much stiffer across v
    doc.recompute()
    for s in (iso, same, aniso):
        assert_ok(s)
    assert max_pole_shift(poles_of(iso), poles_of(same)) < 1e-9
    assert max_pole_shift(poles_of(iso), poles_of(aniso)) > 0.1
    aniso.BendTensor = [1.0, 2.0]
    doc.recompute()
    assert not aniso.isValid() and "BendTensor takes three" in aniso.getStatusString()


def test_a_sheet_hides_only_what_it_replaces(doc, native):
    """A sheet on a face made for it (a Part Plane) hides it; one on a face of a Part Box leaves
    the box shown, walls and all, as Surface Filling leaves its inputs. A Solid hides its sheets
    (it shows their faces). Headless: FreeCAD saves this visibility with the document."""
    plane = doc.addObject("Part::Plane", "Plane")
    plane.Length, plane.Width = 50, 40
    box = doc.addObject("Part::Box", "Box")
    box.Placement.Base = FreeCAD.Vector(100, 0, 0)
    arc = doc.addObject("Part::Feature", "Arc")
    arc.Shape = Part.Arc(FreeCAD.Vector(100, 5, 10), FreeCAD.Vector(105, 5, 12), FreeCAD.Vector(110, 5, 10)).toShape()
    line = doc.addObject("Part::Feature", "Line")
    line.Shape = Part.LineSegment(FreeCAD.Vector(10, 10, 2), FreeCAD.Vector(40, 30, 2)).toShape()
    doc.recompute()
    top = next(i for i, f in enumerate(box.Shape.Faces) if abs(f.CenterOfMass.z - 10) < 1e-9)
    on_plane = varsurf.make_sheet((plane, "Face1"), [(line, "Edge1")])
    on_box = varsurf.make_sheet((box, f"Face{top + 1}"), [(arc, "Edge1")])
    doc.recompute()
    assert on_box.isValid(), on_box.getStatusString()
    assert not plane.Visibility and box.Visibility and arc.Visibility and on_plane.Visibility and on_box.Visibility
    solid = varsurf.make_solid([on_box])
    assert not on_box.Visibility and solid.Visibility and box.Visibility
