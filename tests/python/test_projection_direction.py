# SPDX-License-Identifier: LGPL-2.1-or-later
"""Curves drawn above a curved base: projection along the sketch's normal or a chosen direction.

The reference for where a curve point belongs on the sheet is computed independently of the
solver: the line through the point along the projection direction is intersected with the base
face's surface by FreeCAD (Part.Line.intersect), and the result surface is evaluated there.
"""

import math

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.app import projection
from scenes import add_line_sketch, add_shape, reopened

V = FreeCAD.Vector


def wavy_loft():
    """A loft through four wavy rails, 100 x 90 mm, +-17 mm of waves: a line 25 mm above it
    projects orthogonally onto whichever wave flank is nearest, jumping between them."""
    def rail(y):
        points = [V(x, y, 12.0 * math.sin(x / 100.0 * 3.0 * math.pi) + 5.0 * math.sin(y / 20.0))
                  for x in range(0, 101, 5)]
        curve = Part.BSplineCurve()
        curve.interpolate(points)
        return curve.toShape()

    return Part.makeLoft([rail(y) for y in (0.0, 30.0, 60.0, 90.0)], False, False).Faces[0]


def foot_along(face, point, direction):
    """(u, v) where the line through point along direction meets the face: OCCT's boolean section
    of the face with a long segment of the line (not the solver's line/surface intersection)."""
    d = V(direction).normalize() * 500.0
    hits = face.section(Part.LineSegment(point - d, point + d).toShape()).Vertexes
    assert hits, "the line misses the base face"
    best = min((h.Point for h in hits), key=lambda q: (q - point).Length)
    return face.Surface.parameter(best)


@pytest.fixture
def loft_scene(doc, native):
    base = add_shape(doc, "Loft", wavy_loft())
    sketch = add_line_sketch(doc, "Above", 25.0, (15.0, 20.0), (85.0, 70.0))
    doc.recompute()
    return doc, base, sketch


def points_on(edge, n=9):
    a, b = edge.FirstParameter, edge.LastParameter
    return [edge.valueAt(a + (b - a) * k / (n - 1)) for k in range(n)]


def test_a_sketch_above_a_wavy_base_is_seen_along_its_normal(loft_scene):
    doc, base, sketch = loft_scene
    sheet = varsurf.make_sheet((base, "Face1"), [(sketch, "Edge1")], tolerance=0.01)
    doc.recompute()
    assert sheet.Projection == "Automatic"
    assert sheet.isValid() and sheet.Status.startswith("OK"), sheet.Status
    assert max(sheet.MaxDeviations) <= 0.01
    line = sketch.Shape.Edges[0]
    assert sheet.Shape.distToShape(line)[0] <= 0.01
    # Each point of the line sits on the sheet right above the base point below it: the sheet's
    # parametrization is the base's, so the result at the plan-view foot is the line point.
    result = sheet.Shape.Faces[0].Surface
    for p in points_on(line):
        u, v = foot_along(base.Shape.Faces[0], p, V(0, 0, -1))
        assert (result.value(u, v) - p).Length <= 0.01, (p, result.value(u, v))


def test_orthogonal_projection_names_the_real_cause(loft_scene, console_errors):
    doc, base, sketch = loft_scene
    sheet = varsurf.make_sheet((base, "Face1"), [(sketch, "Edge1")], tolerance=0.01)
    sheet.Projection = "Normal"
    doc.recompute()
    assert not sheet.isValid()
    message = console_errors()
    assert "Above:Edge1" in message and sheet.Label in message
    assert "jumps" in message and "runs beyond" not in message, message
    assert "Projection" in message, message  # says what to do


def test_a_chosen_oblique_direction(loft_scene):
    doc, base, sketch = loft_scene
    sheet = varsurf.make_sheet((base, "Face1"), [(sketch, "Edge1")], tolerance=0.01)
    sheet.Projection = "Direction"
    direction = V(0.25, -0.1, -1.0)
    sheet.ProjectionDirection = direction
    doc.recompute()
    assert sheet.isValid() and sheet.Status.startswith("OK"), sheet.Status
    result = sheet.Shape.Faces[0].Surface
    for p in points_on(sketch.Shape.Edges[0]):
        u, v = foot_along(base.Shape.Faces[0], p, direction)
        assert (result.value(u, v) - p).Length <= 0.01


def test_a_curve_beyond_the_face_in_the_chosen_view_is_refused(loft_scene, console_errors):
    doc, base, sketch = loft_scene
    sheet = varsurf.make_sheet((base, "Face1"), [(sketch, "Edge1")], tolerance=0.01)
    sheet.Projection = "Direction"
    sheet.ProjectionDirection = V(1.0, 0.0, -0.5)  # 25 mm up, 50 mm sideways: past x = 100
    doc.recompute()
    assert not sheet.isValid()
    message = console_errors()
    assert "Above:Edge1" in message and "beyond the face" in message, message
    sheet.ProjectionDirection = V(0, 0, 0)
    doc.recompute()
    assert not sheet.isValid()
    assert "ProjectionDirection is zero" in console_errors()
    sheet.ProjectionDirection = V(0, 0, 1)  # either sense of the line serves
    doc.recompute()
    assert sheet.isValid() and sheet.Status.startswith("OK"), sheet.Status


def test_sketches_standing_across_the_base_are_projected_orthogonally(doc, native):
    base = add_shape(doc, "Loft", wavy_loft())
    flat = add_line_sketch(doc, "Plan", 25.0, (15.0, 20.0), (85.0, 70.0))
    standing = doc.addObject("Sketcher::SketchObject", "Profile")
    standing.Placement = FreeCAD.Placement(V(0, 45, 0), FreeCAD.Rotation(V(1, 0, 0), 90))
    standing.addGeometry(Part.LineSegment(V(20, 10, 0), V(80, 12, 0)), False)
    doc.recompute()
    face = base.Shape.Faces[0]
    sheet = varsurf.make_sheet((base, "Face1"), [(flat, "Edge1")])
    found = projection.directions(sheet, face, [(flat, "Edge1"), (standing, "Edge1"), (base, "Edge1")])
    assert found[1] is None and found[2] is None
    assert abs(abs(found[0][2]) - 1.0) < 1e-12


def test_documents_from_before_projection_choices_keep_orthogonal_projection(loft_scene, tmp_path):
    doc, base, sketch = loft_scene
    sheet = varsurf.make_sheet((base, "Face1"), [(sketch, "Edge1")], tolerance=0.01)
    doc.recompute()
    sheet.removeProperty("Projection")
    sheet.removeProperty("ProjectionDirection")
    name = sheet.Name
    with reopened(doc, tmp_path / "older.FCStd") as again:
        restored = again.getObject(name)
        assert restored.Projection == "Normal"
        restored.touch()
        again.recompute()
        assert not restored.isValid()  # as that file computed it: the orthogonal projection jumps
