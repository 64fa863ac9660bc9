# SPDX-License-Identifier: LGPL-2.1-or-later
"""A Sheet without a base face: it starts from the best-fit plane of its curves (free boundary)."""

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.solve import errors, settings
from varsurf.solve.sheet import solve_sheet_from_curves

V = FreeCAD.Vector


def hypar(x, y):
    # An antisymmetric saddle over 100 x 80 mm: z(100 - x, y) = -z(x, y).
    return (x - 50.0) * (y - 40.0) / 100.0


def frame(doc):
    """Four straight edges of the saddle's boundary (straight lines lie on a hyperbolic paraboloid)."""
    corners = [(0, 0), (100, 0), (100, 80), (0, 80)]
    edges = []
    for k in range(4):
        (x0, y0), (x1, y1) = corners[k], corners[(k + 1) % 4]
        edges.append(Part.LineSegment(V(x0, y0, hypar(x0, y0)), V(x1, y1, hypar(x1, y1))).toShape())
    obj = doc.addObject("Part::Feature", "Frame")
    obj.Shape = Part.Compound(edges)
    doc.recompute()
    return obj


def test_sheet_from_a_saddle_frame_meets_it_and_respects_its_symmetry(doc, native):
    obj = frame(doc)
    sheet = varsurf.make_sheet(None, [obj])
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert len(sheet.MaxDeviations) == 4
    assert max(sheet.MaxDeviations) <= settings.DEFAULT_TOLERANCE, list(sheet.MaxDeviations)
    face = sheet.Shape.Faces[0]
    assert face.isValid()
    # The frame is antisymmetric under x -> 100 - x (z -> -z), so the fair sheet is too: zero at
    # the centre. The best-fit plane is z = 0 and covers the frame with a margin.
    u, v = face.Surface.parameter(V(50.0, 40.0, 0.0))
    centre = face.Surface.value(u, v)
    assert abs(centre.x - 50.0) < 1e-6 and abs(centre.y - 40.0) < 1e-6
    assert abs(centre.z) < 1e-6, centre
    bb = sheet.Shape.BoundBox
    assert bb.XMin < -1.0 and bb.XMax > 101.0 and bb.YMin < -1.0 and bb.YMax > 81.0, bb
    # Between the frame's edges the sheet follows the saddle's sign pattern.
    for x, y in ((25.0, 20.0), (75.0, 60.0), (25.0, 60.0), (75.0, 20.0)):
        u, v = face.Surface.parameter(V(x, y, 0.0))
        assert face.Surface.value(u, v).z * hypar(x, y) > 0.0, (x, y)


def test_curves_on_one_line_cannot_make_a_sheet(doc, native):
    obj = doc.addObject("Part::Feature", "Line")
    obj.Shape = Part.Compound([Part.LineSegment(V(0, 0, 0), V(10, 0, 0)).toShape(),
                               Part.LineSegment(V(20, 0, 0), V(30, 0, 0)).toShape()])
    doc.recompute()
    sheet = varsurf.make_sheet(None, [obj])
    doc.recompute()
    assert not sheet.isValid()
    assert "lie on one line" in sheet.getStatusString()


def test_make_sheet_without_base_or_curves_is_refused(doc, native):
    with pytest.raises(ValueError, match="needs curves"):
        varsurf.make_sheet(None, [])


@pytest.mark.parametrize("degree, spans", [(2, 6), (5, 4)])
def test_chosen_degree_and_span_count(doc, native, degree, spans):
    obj = frame(doc)
    sheet = varsurf.make_sheet(None, [obj], degree=degree, min_spans=spans)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert (sheet.DegreeU, sheet.DegreeV) == (degree, degree)
    # The frame's straight edges are met on any span count, so the spans are not doubled.
    assert (sheet.PoleCountU, sheet.PoleCountV) == (spans + degree, spans + degree)
    assert max(sheet.MaxDeviations) <= settings.DEFAULT_TOLERANCE, list(sheet.MaxDeviations)
    surface = sheet.Shape.Faces[0].Surface
    assert (surface.UDegree, surface.VDegree) == (degree, degree)


def test_degree_out_of_range_is_refused(doc, native):
    obj = frame(doc)
    with pytest.raises(errors.SheetError, match="Degree must be an integer in 2..9"):
        solve_sheet_from_curves(list(obj.Shape.Edges), degree=1)
    sheet = varsurf.make_sheet(None, [obj], degree=40)
    assert sheet.Degree == settings.MAX_DEGREE  # the property clamps to its range


@pytest.mark.parametrize("seed", range(6))
def test_the_start_plane_faces_the_same_way_whatever_the_order_of_the_curves(seed):
    """The best-fit plane's axes are an SVD's, whose signs are its library's choice (and change
    with the points' order and the processor): each axis points to +z (else +y, else +x), so the
    curves in any order and direction give the same start face, poles for poles."""
    import random

    from varsurf.solve.plane_fit import plane_face_for_curves

    rng = random.Random(seed)
    axis = FreeCAD.Vector(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
    if seed == 0:
        axis = FreeCAD.Vector(0, 0, 1)  # curves in the xy plane: the face looks up +z
    rotation = FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), axis)
    centre = FreeCAD.Vector(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50))
    corners = [centre + rotation.multVec(FreeCAD.Vector(x, y, 0)) for x, y in ((0, 0), (60, 5), (55, 40), (-5, 30))]
    edges = [Part.LineSegment(corners[k], corners[(k + 1) % 4]).toShape() for k in range(4)]
    reference = plane_face_for_curves(edges).Surface
    normal = reference.normal(0.5, 0.5)
    for axis_of in (reference.getPoles()[-1][0] - reference.getPoles()[0][0],
                    reference.getPoles()[0][-1] - reference.getPoles()[0][0]):
        significant = [c for c in (axis_of.z, axis_of.y, axis_of.x) if abs(c) > 1e-6 * axis_of.Length]
        assert significant[0] > 0, axis_of
    if seed == 0:
        assert normal.z == pytest.approx(1.0)
    for k in range(1, 4):
        shuffled = edges[k:] + edges[:k]
        shuffled = [e.reversed() if (k + i) % 2 else e for i, e in enumerate(shuffled)]
        other = plane_face_for_curves(list(reversed(shuffled))).Surface
        worst = max((a - b).Length for ra, rb in zip(reference.getPoles(), other.getPoles()) for a, b in zip(ra, rb))
        assert worst <= 1e-9, (k, worst)
