# SPDX-License-Identifier: LGPL-2.1-or-later
"""Curves on the base face's own boundary: with the base as rest shape, a sheet through the face's
own edges (or curves partly along its boundary, or touching it) is the base face itself.

Each scene is built the way a FreeCAD user builds it: Part primitives and their own edges. The
result is compared with the base by OpenCASCADE's distToShape from sampled points, both ways,
not by what the solver reports.
"""

import math

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.solve import errors, settings
from varsurf.solve.sheet import solve_sheet_on_face

V = FreeCAD.Vector
#: Relative to the base face's size: the result must be the base to rounding.
SAME = 1e-9
GRID = 9  # points per direction sampled on each face


def _grid(face, n=GRID):
    u0, u1, v0, v1 = face.ParameterRange
    return [face.valueAt(u0 + (u1 - u0) * i / (n - 1), v0 + (v1 - v0) * j / (n - 1))
            for i in range(n) for j in range(n)]


def _far(points, shape):
    return max(shape.distToShape(Part.Vertex(p))[0] for p in points)


def assert_is_face(result, face, curves=(), area=True):
    """`result` lies on `face` and covers it (distToShape both ways), and each curve lies on it.
    OCCT's area of a rational face is only good to ~1e-3 (a cylinder's NURBS form: 6300 mm² for
    6283), so `area` is compared on polynomial faces only."""
    size = face.BoundBox.DiagonalLength
    assert _far(_grid(result), face) <= SAME * size
    assert _far(_grid(face), result) <= SAME * size
    if area:
        assert result.Area == pytest.approx(face.Area, rel=1e-8)
    for edge in curves:
        assert _far(edge.discretize(50), result) <= SAME * size


def solve(face, edges, **options):
    options.setdefault("rest", "base")
    out = solve_sheet_on_face(face, edges, **options)
    size = face.BoundBox.DiagonalLength
    assert max(out.max_deviations) <= SAME * size, out.max_deviations
    return out


def box_top(placement=None):
    box = Part.makeBox(100, 60, 40)
    if placement is not None:
        box.Placement = placement
    top = max(box.Faces, key=lambda f: f.CenterOfMass.dot(box.Placement.Rotation.multVec(V(0, 0, 1))))
    return top


def interpolated_face():
    """A 70 x 70 mm saddle-like bicubic face interpolating a grid (Part.BSplineSurface)."""
    points = [[V(10.0 * i, 10.0 * j, 3.0 * ((i - 3) ** 2 - (j - 3) ** 2) / 9.0) for j in range(8)]
              for i in range(8)]
    surface = Part.BSplineSurface()
    surface.interpolate(points)
    return surface.toShape()


@pytest.mark.parametrize("placed", [False, True], ids=["box", "rotated box"])
def test_box_top_face_through_its_four_edges(native, placed):
    placement = FreeCAD.Placement(V(5, -7, 12), FreeCAD.Rotation(V(1, 2, 3), 35)) if placed else None
    top = box_top(placement)
    out = solve(top, top.Edges)
    assert_is_face(out.shape, top, top.Edges)
    assert (out.pole_count_u, out.pole_count_v) == (19, 19)  # no refinement was needed


def test_plane_through_its_own_edges(native):
    plane = Part.makePlane(100, 60)
    assert_is_face(solve(plane, plane.Edges).shape, plane, plane.Edges)
    # the upper sides (u = 100, v = 60) alone: their pre-images evaluate exactly on the bound
    assert_is_face(solve(plane, plane.Edges[2:]).shape, plane, plane.Edges[2:])


def test_plane_through_only_its_first_edge(native):
    plane = Part.makePlane(100, 60)
    out = solve(plane, [plane.Edges[0]])
    assert_is_face(out.shape, plane, [plane.Edges[0]])
    assert out.shape.CenterOfMass.distanceToPoint(plane.CenterOfMass) <= SAME * 100


def test_plane_boundary_edges_with_a_free_boundary(native):
    plane = Part.makePlane(100, 60)
    out = solve(plane, plane.Edges, fix_boundary=False)
    assert_is_face(out.shape, plane, plane.Edges)


def test_interpolated_bspline_face_through_its_four_edges(native):
    face = interpolated_face()
    out = solve(face, face.Edges)
    assert_is_face(out.shape, face, face.Edges)


def test_cylinder_face_through_its_two_circles(native):
    cylinder = Part.makeCylinder(20, 50)
    lateral = next(f for f in cylinder.Faces if isinstance(f.Surface, Part.Cylinder))
    circles = [e for e in lateral.Edges if isinstance(e.Curve, Part.Circle)]
    assert len(circles) == 2
    out = solve(lateral, circles)
    assert_is_face(out.shape, lateral, circles, area=False)
    # and through its seam line as well
    seam = [e for e in lateral.Edges if isinstance(e.Curve, Part.Line)]
    assert_is_face(solve(lateral, circles + seam).shape, lateral, seam, area=False)


def test_curve_partly_along_the_boundary(native):
    """A cubic whose first spans run exactly along the side y = 0, then turn into the face."""
    plane = Part.makePlane(100, 60)
    curve = Part.BSplineCurve()
    curve.buildFromPoles([V(10, 0, 0), V(25, 0, 0), V(40, 0, 0), V(55, 0, 0), V(70, 20, 0),
                          V(80, 45, 0)], False, 3)
    edge = curve.toShape()
    assert edge.distToShape(plane.Edges[1])[0] == 0.0  # it does touch the side
    out = solve(plane, [edge])
    assert_is_face(out.shape, plane, [edge])
    # and a polyline, one segment along the side and one inside, with the boundary free
    poly = Part.BSplineCurve()
    poly.buildFromPoles([V(10, 0, 0), V(50, 0, 0), V(70, 30, 0)], False, 1)
    out = solve(plane, [poly.toShape()], fix_boundary=False)
    assert_is_face(out.shape, plane, [poly.toShape()])


def test_curve_touching_the_boundary(native):
    """A circle inside the face touching two of its sides at one point each."""
    plane = Part.makePlane(100, 60)
    circle = Part.makeCircle(30, V(50, 30, 0))
    out = solve(plane, [circle])
    assert_is_face(out.shape, plane, [circle])


def test_sheet_feature_on_a_box_top_through_its_edges(doc, native):
    """The workbench's Sheet with its defaults (boundary kept, base as rest shape)."""
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 100, 60, 40
    doc.recompute()
    face_name = next(f"Face{i + 1}" for i, f in enumerate(box.Shape.Faces)
                     if f.CenterOfMass.z == pytest.approx(40.0))
    top = box.Shape.getElement(face_name)
    edge_names = [f"Edge{i + 1}" for i, e in enumerate(box.Shape.Edges)
                  if any(e.isSame(t) for t in top.Edges)]
    assert len(edge_names) == 4
    sheet = varsurf.make_sheet((box, face_name), [(box, tuple(edge_names))])
    doc.recompute()
    assert sheet.Status.startswith("OK"), sheet.Status
    assert max(sheet.MaxDeviations) <= SAME * 100
    assert_is_face(sheet.Shape.Faces[0], top, top.Edges)


@pytest.mark.parametrize("make", [lambda: Part.makeSphere(30), lambda: Part.makeCone(20, 0, 40)],
                         ids=["sphere", "cone"])
def test_seam_and_poles_of_a_revolved_face(native, make):
    """A sphere through its seam meridian (pole to pole), a cone through its base circle and its
    seam line (to the apex): at a pole every u is the same point, on the seam both sides are."""
    face = next(f for f in make().Faces if isinstance(f.Surface, (Part.Sphere, Part.Cone)))
    edges = [e for e in face.Edges if not e.Degenerated]
    out = solve(face, edges)
    assert_is_face(out.shape, face, edges, area=False)


def test_curve_off_a_kept_boundary_is_refused_by_name(native):
    """A curve 5 mm above the face's side: with the boundary kept the sheet cannot reach it (the
    solver would see it on fixed poles only), so the sheet says so at once; freed, it is met."""
    plane = Part.makePlane(100, 60)
    raised = plane.Edges[1].copy()
    raised.translate(V(0, 0, 5))
    with pytest.raises(errors.SheetError, match=r"Raised is 5 mm from the base face .* kept boundary"):
        solve_sheet_on_face(plane, [raised], names=["Raised"])
    out = solve_sheet_on_face(plane, [raised], fix_boundary=False)
    assert max(out.max_deviations) <= settings.DEFAULT_TOLERANCE


def test_circle_across_a_cylinders_seam_is_met(native):
    """A full circle on the cylinder starting a quarter turn from its seam: on the face, and its
    pre-image would have to run on both sides of the seam. The sheet is closed around the
    cylinder: the circle is cut where it crosses the seam, and the sheet is the cylinder."""
    lateral = Part.makeCylinder(20, 50).Faces[0]
    circle = Part.makeCircle(20, V(0, 0, 25), V(0, 0, 1), 90, 450)
    out = solve(lateral, [circle])
    assert max(out.max_deviations) <= 1e-7
    assert len(out.problem.curves) == 2  # the two pieces of the circle
    assert_is_face(out.shape, lateral, [circle], area=False)


def test_all_edges_of_a_tilted_cylinder(native):
    """A tilted cylinder through its circles and its seam line: every sample of the seam line is
    on both sides of the domain, and one side is kept for all of them."""
    face = Part.makeCylinder(13.285526245206562, 45.70221525307818,
                             V(-8.886992282996744, -83.94626090142185, 93.31127802138934),
                             V(-0.6149462685763374, -0.6097680893334128, 0.5000239634204728)).Faces[0]
    edges = [e for e in face.Edges if not e.Degenerated]
    out = solve(face, edges)
    assert_is_face(out.shape, face, edges, area=False)


def test_meridian_from_pole_to_pole(native):
    """A sphere through one of its meridians (a u iso line from pole to pole): at a pole the
    surface has no u-derivative, so the projection of the next point starts afresh there. (The
    boundary is free: a kept boundary through the poles is the trim's own business.)"""
    face = Part.makeSphere(9.00192319358614, V(12.748340273008907, -1.733946368217957, 63.43910048959043),
                           V(-0.6135081789830571, -0.7295477386550513, 0.30227108916367473)).Faces[0]
    meridian = Part.Edge(face.Surface.uIso(4.240174437777185), -math.pi / 2, math.pi / 2)
    out = solve(face, [meridian], fix_boundary=False)
    assert_is_face(out.shape, face, [meridian], area=False)
