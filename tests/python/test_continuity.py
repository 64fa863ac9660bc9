# SPDX-License-Identifier: LGPL-2.1-or-later
"""The join measurement (varsurf.solve.continuity) against faces whose gap, angle and curvature
jump are known exactly, then on solved sheets joined G0 and G1 to their neighbours."""

import math

import FreeCAD
import Part
import pytest

from varsurf.solve import continuity

V = FreeCAD.Vector
LENGTH, WIDTH = 50.0, 30.0


def _edge():
    return Part.LineSegment(V(0, 0, 0), V(LENGTH, 0, 0)).toShape()


def _strip(angle_deg, z=0.0):
    """A plane strip from the x axis, leaving it at ``angle_deg`` from the -y direction (0: flat,
    on the y < 0 side), lifted by z."""
    a = math.radians(angle_deg)
    w = V(0, -math.cos(a), math.sin(a)) * WIDTH
    return Part.Face(Part.makePolygon([V(0, 0, z), V(LENGTH, 0, z), V(LENGTH, 0, z) + w, V(0, 0, z) + w,
                                       V(0, 0, z)]))


def _sheet():
    """The 'sheet' side: the plane strip y in [0, WIDTH]."""
    return Part.makePlane(LENGTH, WIDTH)


def _half_cylinder(radius, reverse=False):
    """A half cylinder along x touching the plane z = 0 along the x axis, on the y < 0 side."""
    face = Part.makeCylinder(radius, LENGTH, V(0, 0, radius), V(1, 0, 0), 360).Faces[0]
    half = face.common(Part.makeBox(LENGTH, 2 * radius, 2 * radius, V(0, -2 * radius, 0))).Faces[0]
    return half.reversed() if reverse else half


@pytest.mark.parametrize("angle", [0.0, 10.0, 45.0, 90.0])
def test_two_planes_meet_at_their_angle(angle):
    join = continuity.measure("hinge", _sheet(), _edge(), _strip(angle))
    assert join.samples >= 200
    assert join.gap < 1e-9
    assert join.angle == pytest.approx(angle, abs=1e-6)
    assert join.curvature_jump < 1e-6


def test_a_parallel_plane_shows_its_offset_as_the_gap():
    join = continuity.measure("step", _sheet(), _edge(), _strip(0.0, z=0.3))
    assert join.gap == pytest.approx(0.3, abs=1e-9)
    assert join.angle < 1e-6


@pytest.mark.parametrize("reverse", [False, True])
def test_a_plane_tangent_to_a_cylinder_is_g1_not_g2(reverse):
    """Tangent planes agree (0°); across the edge the cylinder bends at 1/R and the plane not at
    all: the whole curvature jumps (100 %), whichever way the cylinder's face is oriented."""
    join = continuity.measure("tangent", _sheet(), _edge(), _half_cylinder(20.0, reverse))
    assert join.gap < 1e-9
    assert join.angle < 1e-6
    assert join.curvature_jump == pytest.approx(100.0, abs=1e-6)


@pytest.mark.parametrize("reverse", [False, True])
def test_two_halves_of_one_cylinder_are_g2(reverse):
    radius = 15.0
    whole = Part.makeCylinder(radius, LENGTH, V(0, 0, radius), V(1, 0, 0), 360).Faces[0]
    upper = whole.common(Part.makeBox(LENGTH, 2 * radius, 2 * radius, V(0, 0, 0))).Faces[0]
    lower = whole.common(Part.makeBox(LENGTH, 2 * radius, 2 * radius, V(0, -2 * radius, 0))).Faces[0]
    join = continuity.measure("same", upper, _edge(), lower.reversed() if reverse else lower)
    assert join.gap < 1e-9 and join.angle < 1e-6
    assert join.curvature_jump < 1e-6


def test_curvatures_of_different_radii_jump_by_their_difference():
    """Two cylinders of radii 10 and 40 touching along a line, one inside the other's side:
    normal curvatures 1/10 and 1/40 on the same side, a jump of (1/10 - 1/40) / (1/10) = 75 %."""
    small = Part.makeCylinder(10.0, LENGTH, V(0, 0, 10.0), V(1, 0, 0), 360).Faces[0]
    small = small.common(Part.makeBox(LENGTH, 20, 20, V(0, 0, 0))).Faces[0]
    big = Part.makeCylinder(40.0, LENGTH, V(0, 0, 40.0), V(1, 0, 0), 360).Faces[0]
    big = big.common(Part.makeBox(LENGTH, 80, 80, V(0, -80, 0))).Faces[0]
    join = continuity.measure("radii", small, _edge(), big)
    assert join.angle < 1e-6
    assert join.curvature_jump == pytest.approx(75.0, abs=1e-6)


def test_without_a_neighbour_the_gap_is_from_the_edge_to_the_sheet():
    lifted = Part.LineSegment(V(0, 5, 0.2), V(LENGTH, 5, 0.2)).toShape()
    join = continuity.measure("G0", _sheet(), lifted)
    assert join.gap == pytest.approx(0.2, abs=1e-9)
    assert math.isnan(join.angle) and math.isnan(join.curvature_jump)


def _plane_through(axis_point, axis, tilt_axis, degrees, size=30.0):
    """A square face with one side on the line through ``axis_point`` along ``axis``, turned by
    ``degrees`` about that line from the plane z = 0 (``tilt_axis``: the in-plane side)."""
    rot = FreeCAD.Rotation(axis, degrees)
    side = rot.multVec(tilt_axis) * size
    a, b = axis_point, axis_point + axis * size
    return Part.Face(Part.makePolygon([a, b, b + side, a + side, a])), rot.multVec(V(0, 0, 1))


def test_two_g1_joins_meeting_where_their_faces_disagree_are_a_corner():
    along_x = Part.LineSegment(V(0, 0, 0), V(30, 0, 0)).toShape()
    along_y = Part.LineSegment(V(0, 0, 0), V(0, 30, 0)).toShape()
    face_x, normal_x = _plane_through(V(0, 0, 0), V(1, 0, 0), V(0, -1, 0), 10.0)
    face_y, normal_y = _plane_through(V(0, 0, 0), V(0, 1, 0), V(-1, 0, 0), -25.0)
    expected = math.degrees(math.acos(abs(normal_x.dot(normal_y))))  # from the rotations alone
    corners = continuity.incompatible_corners([("A", along_x, face_x), ("B", along_y, face_y)], 1e-6)
    assert len(corners) == 1 and (corners[0].first, corners[0].second) == ("A", "B")
    assert corners[0].point == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    assert corners[0].angle == pytest.approx(expected, abs=1e-9) and expected > 20.0
    assert "meet at (0, 0, 0)" in corners[0].message() and f"{expected:.3g}°" in corners[0].message()
    # Faces in one plane at the corner agree; edges that do not meet make no corner.
    flat_x, _ = _plane_through(V(0, 0, 0), V(1, 0, 0), V(0, -1, 0), 0.0)
    flat_y, _ = _plane_through(V(0, 0, 0), V(0, 1, 0), V(-1, 0, 0), 0.0)
    assert continuity.incompatible_corners([("A", along_x, flat_x), ("B", along_y, flat_y)], 1e-6) == []
    apart = Part.LineSegment(V(0, 5, 0), V(0, 30, 0)).toShape()
    assert continuity.incompatible_corners([("A", along_x, face_x), ("B", apart, face_y)], 1e-6) == []


def _wave_pair(tilt):
    """Two bicubic faces sharing their v = 0 boundary curve exactly (same first pole row) and
    leaving it at different slopes and bends: a seam with a real angle and curvature jump."""
    nu, nv = 7, 5
    knots_u, knots_v = [0.0, 0.25, 0.5, 0.75, 1.0], [0.0, 0.5, 1.0]
    mults_u, mults_v = [4, 1, 1, 1, 4], [4, 1, 4]

    def surface(tilt):
        poles = [[V(60.0 * i / (nu - 1), 40.0 * j / (nv - 1),
                    3.0 * math.sin(i) * math.cos(0.7 * j) + tilt * j * (1.0 + 0.2 * i)) for j in range(nv)]
                 for i in range(nu)]
        s = Part.BSplineSurface()
        s.buildFromPolesMultsKnots(poles, mults_u, mults_v, knots_u, knots_v, False, False, 3, 3)
        return s

    sheet, neighbour = surface(0.0), surface(tilt)
    return sheet.toShape(), neighbour.toShape(), sheet.vIso(0.0).toShape()


class _CountingSurface:
    """A Part surface whose global projections (parameter) are counted."""

    def __init__(self, surface):
        self._surface = surface
        self.global_calls = 0

    def parameter(self, point):
        self.global_calls += 1
        return self._surface.parameter(point)

    def __getattr__(self, name):
        return getattr(self._surface, name)


class _Face:
    def __init__(self, face):
        self.Surface = _CountingSurface(face.Surface)
        self.BoundBox = face.BoundBox


@pytest.mark.parametrize("tilt", [-4.0, 2.5])
def test_feet_seeded_along_the_edge_measure_what_the_global_projection_measures(tilt):
    """Each foot starts from the previous point's by Newton's method; it must measure the same
    gap, angle and curvature jump as OCCT's global projection of every point, while only the
    first point of each face is projected globally."""
    sheet, neighbour, edge = _wave_pair(tilt)
    size = 80.0
    reference = continuity.measure("seam", sheet, edge, neighbour, size=size, seeded=False)
    counted_sheet, counted_neighbour = _Face(sheet), _Face(neighbour)
    seeded = continuity.measure("seam", counted_sheet, edge, counted_neighbour, size=size)
    assert reference.angle > 3.0 and reference.curvature_jump > 10.0
    assert seeded.samples == reference.samples >= 200
    assert seeded.gap == pytest.approx(reference.gap, abs=1e-9)
    assert seeded.angle == pytest.approx(reference.angle, abs=1e-7)
    assert seeded.curvature_jump == pytest.approx(reference.curvature_jump, rel=1e-7)
    assert counted_sheet.Surface.global_calls == 1 and counted_neighbour.Surface.global_calls == 1


def test_a_foot_beyond_the_reach_is_projected_globally():
    """The parallel plane 0.3 away: every neighbour foot is farther than the seeded reach, so each
    is OCCT's (a local minimum found by Newton is not trusted to be the nearest point there)."""
    neighbour = _Face(_strip(0.0, z=0.3))
    join = continuity.measure("step", _sheet(), _edge(), neighbour, size=60.0)
    assert join.gap == pytest.approx(0.3, abs=1e-9)
    assert neighbour.Surface.global_calls == join.samples


@pytest.mark.parametrize("iso", ["boundary", "interior", "slanted"])
def test_feet_along_a_curve_are_the_global_projections(iso):
    """parameters_along (the neighbour's fields along a G2 curve) finds the same (u, v) as OCCT's
    global projection of every point, projecting only the first globally."""
    sheet, _neighbour, boundary = _wave_pair(-4.0)
    surface = sheet.Surface
    if iso == "boundary":
        points = boundary.discretize(Number=201)
    elif iso == "interior":
        points = surface.uIso(0.37).toShape().discretize(Number=201)
    else:  # a curve across the knot lines, on the surface
        points = [surface.value(0.05 + 0.9 * k / 200, 0.1 + 0.7 * (k / 200) ** 2) for k in range(201)]
    counted = _CountingSurface(surface)
    feet = continuity.parameters_along(counted, points, continuity.SEEDED_REACH * 80.0)
    assert counted.global_calls == 1
    for p, (u, v) in zip(points, feet):
        gu, gv = surface.parameter(p)
        assert (u, v) == pytest.approx((gu, gv), abs=1e-9)
