# SPDX-License-Identifier: LGPL-2.1-or-later
"""Surface and curve attractors, regions bounded by closed edges, and ribbons that follow a
second edge or the sheet's own base: each measured on the solved surface."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from scenes import add_shape, poles_of, railed_sheet, residual_of

V = FreeCAD.Vector


@pytest.fixture
def sheet(doc, native):
    return railed_sheet(doc)


def polygon(points):
    return Part.makePolygon([V(*p) for p in list(points) + [points[0]]])


def test_surface_attractor_pulls_the_region_onto_a_face(sheet):
    doc = sheet.Document
    roof = add_shape(doc, "Roof", Part.makePlane(60, 50, V(30, 15, 9)))
    doc.recompute()
    c = varsurf.make_constraint(sheet, "SurfaceAttractor", reference=(roof, "Face1"),
                                region=(0.55, 0.75, 0.4, 0.6), weight=1e-6)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    weak = residual_of(sheet, c)
    residuals = [weak]
    for strength in (1e-3, 1.0, 1e2, 1e4):
        c.Weight = strength
        doc.recompute()
        assert sheet.isValid(), sheet.getStatusString()
        residuals.append(residual_of(sheet, c))
    assert residuals == sorted(residuals, reverse=True), residuals
    assert residuals[-1] < 0.01 * weak, residuals  # interpolation in the limit
    # measured independently: the region's middle lies on the roof
    middle = sheet.Shape.Faces[0].Surface.value(*_middle(sheet, 0.65, 0.5))
    assert abs(middle.z - 9.0) < 0.1, middle


def test_surface_attractor_on_a_plane_face_equals_the_plane_attractor(sheet):
    # dist(w, plane)^2 is the plane attractor's energy: the two solves must give the same sheet.
    doc = sheet.Document
    roof = add_shape(doc, "Roof", Part.makePlane(60, 50, V(30, 15, 9)))
    doc.recompute()
    c = varsurf.make_constraint(sheet, "PlaneAttractor", origin=(0, 0, 9), vector=(0, 0, 1),
                                region=(0.55, 0.75, 0.4, 0.6), weight=0.3)
    doc.recompute()
    expected = poles_of(sheet)
    c.Kind = "SurfaceAttractor"
    c.Reference = (roof, "Face1")
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert max(math.dist(p, q) for p, q in zip(expected, poles_of(sheet))) < 1e-7


def _middle(sheet, u, v):
    u0, u1, v0, v1 = sheet.Shape.Faces[0].ParameterRange
    return u0 + u * (u1 - u0), v0 + v * (v1 - v0)


def test_curve_attractor_pulls_the_region_onto_an_edge(sheet):
    doc = sheet.Document
    # A line 6 mm up along x over the region's middle row (y = 40).
    wire = add_shape(doc, "Wire", Part.LineSegment(V(50, 40, 6), V(80, 40, 6)).toShape())
    doc.recompute()
    c = varsurf.make_constraint(sheet, "CurveAttractor", curve=(wire, "Edge1"),
                                region=(0.55, 0.75, 0.45, 0.55), weight=1e-3)
    doc.recompute()
    weak = residual_of(sheet, c)
    c.Weight = 1e4
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    strong = residual_of(sheet, c)
    assert strong < 0.05 * weak, (weak, strong)
    p = sheet.Shape.Faces[0].Surface.value(*_middle(sheet, 0.65, 0.5))
    assert abs(p.z - 6.0) < 0.3, p


def test_a_rectangular_loop_acts_like_the_same_rectangle(sheet):
    doc = sheet.Document
    # x = 100 u, y = 80 v on this base: the loop is the region (0.1, 0.5, 0.1, 0.5) exactly.
    loop = add_shape(doc, "Loop", polygon([(10, 8, -3), (50, 8, -3), (50, 40, -3), (10, 40, -3)]))
    doc.recompute()
    c = varsurf.make_constraint(sheet, "PointAttractor", origin=(30, 24, 12), region=(0.1, 0.5, 0.1, 0.5),
                                weight=0.1)
    doc.recompute()
    rectangle = poles_of(sheet)
    residual = residual_of(sheet, c)
    c.RegionLoop = (loop, [])
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert max(math.dist(p, q) for p, q in zip(rectangle, poles_of(sheet))) < 1e-8
    assert abs(residual_of(sheet, c) - residual) < 0.05 * residual  # sampled differently


def test_a_triangular_loop_freezes_only_what_it_encloses(sheet):
    doc = sheet.Document
    pin = add_shape(doc, "Pin", Part.Vertex(V(80, 60, 10)))
    varsurf.make_constraint(sheet, "Point", location=(pin, "Vertex1"))
    tri = add_shape(doc, "Triangle", polygon([(45, 10, 0), (95, 10, 0), (70, 45, 0)]))
    doc.recompute()
    f = varsurf.make_constraint(sheet, "FrozenRegion", region_loop=(tri, []))
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert residual_of(sheet, f) < 1e-9
    face = sheet.Shape.Faces[0]
    assert abs(face.Surface.value(*_middle(sheet, 0.7, 0.25)).z) < 1e-9  # inside: kept flat
    assert face.Surface.value(*_middle(sheet, 0.8, 0.75)).z > 5.0  # the pin still pulls


def test_bad_loops_are_reported(sheet, console_errors):
    doc = sheet.Document
    open_line = add_shape(doc, "Open", Part.makePolygon([V(10, 10, 0), V(50, 10, 0), V(30, 40, 0)]))
    bow = add_shape(doc, "Bow", polygon([(10, 10, 0), (50, 40, 0), (50, 10, 0), (10, 40, 0)]))
    doc.recompute()
    c = varsurf.make_constraint(sheet, "PointAttractor", origin=(30, 24, 12), region_loop=(open_line, []))
    doc.recompute()
    assert not sheet.isValid() and "one closed chain" in sheet.getStatusString()
    c.RegionLoop = (bow, [])
    doc.recompute()
    assert not sheet.isValid() and "crosses itself" in sheet.getStatusString()
    assert c.Label in sheet.getStatusString()


def test_ribbon_along_the_bases_own_normal_turned_by_an_angle(sheet):
    doc = sheet.Document
    seam = add_shape(doc, "Seam", Part.LineSegment(V(60, 25, 0), V(60, 55, 0)).toShape())
    doc.recompute()
    c = varsurf.make_constraint(sheet, "Ribbon", curve=(seam, "Edge1"), angle=15.0, weight=10.0)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert residual_of(sheet, c) < 1.0  # degrees, of a 15 degree turn
    # measured independently: the normal at the seam's middle is z turned 15 degrees about +y
    face = sheet.Shape.Faces[0]
    u, v = face.Surface.parameter(V(60, 40, 0))
    n = face.Surface.normal(u, v)
    assert abs(math.degrees(n.getAngle(V(0, 0, 1))) - 15.0) < 1.0, n


def test_ribbon_toward_a_second_edge_matches_the_strip(sheet):
    doc = sheet.Document
    seam = add_shape(doc, "Seam", Part.LineSegment(V(60, 25, 0), V(60, 55, 0)).toShape())
    rise = 20.0 * math.tan(math.radians(20.0))
    second = add_shape(doc, "Second", Part.LineSegment(V(80, 20, rise), V(80, 60, rise)).toShape())
    doc.recompute()
    c = varsurf.make_constraint(sheet, "Ribbon", curve=(seam, "Edge1"), reference=(second, "Edge1"),
                                weight=10.0)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert residual_of(sheet, c) < 1.0  # degrees, of the strip's 20 degree tilt
    face = sheet.Shape.Faces[0]
    u, v = face.Surface.parameter(V(60, 40, 0))
    assert abs(math.degrees(face.Surface.normal(u, v).getAngle(V(0, 0, 1))) - 20.0) < 1.0


def test_g0_join_makes_the_sheet_contain_an_edge(sheet):
    doc = sheet.Document
    lifted = add_shape(doc, "Lifted", Part.LineSegment(V(70, 20, 4), V(70, 60, 4)).toShape())
    doc.recompute()
    c = varsurf.make_constraint(sheet, "G0", curve=(lifted, "Edge1"))
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert residual_of(sheet, c) <= varsurf.DEFAULT_TOLERANCE
    assert sheet.Shape.distToShape(lifted.Shape)[0] < 1e-6  # measured by OCCT, independently
    assert sheet.ConstraintUnits[0] == "mm"
    assert sheet.JoinGaps[0] < 1e-6 and sheet.JoinAngles[0] == -1.0  # no neighbour face: gap only
