# SPDX-License-Identifier: LGPL-2.1-or-later
"""Sheets on cylinders, cones and spheres pass OCCT's Boolean argument check.

OCCT converts these surfaces with quadratic arcs joined at double knots (C0 by multiplicity, so
``check(True)`` reports "BOPAlgo GeomAbs_C0" on every face built on them, Part's own ``toNurbs``
included); VarSurf converts them with knot-smooth exact arcs. With the base as rest shape and no
curves the sheet is its base face: within 1e-9 of the face's size of it both ways (OCCT's
distToShape from points sampled on each onto the other), the same area (integrated by OCCT to
1e-10: Part's Area is approximate on rational faces), and check(True) passes.
"""

import math

import pytest

import Part
from FreeCAD import Vector

from brep_measure import farthest, inside_points
from varsurf.solve.sheet import solve_sheet_on_face


def _lateral(shape, kind):
    return next(f for f in shape.Faces if f.Surface.TypeId == kind)


def _drill(shape, kind, radius, base, direction):
    """`shape` with a cylinder of `radius` cut through it: its `kind` face with the hole."""
    return _lateral(shape.cut(Part.makeCylinder(radius, 200, base, direction)), kind)


#: Partial and trimmed faces of Part primitives, placed off the origin as a user places them.
FACES = {
    "half cylinder": lambda: _lateral(
        Part.makeCylinder(10, 30, Vector(5, -3, 2), Vector(0, 0, 1), 180), "Part::GeomCylinder"),
    "tilted cylinder, 120 degrees": lambda: _lateral(
        Part.makeCylinder(4, 25, Vector(1, 2, 3), Vector(1, 1, 1), 120), "Part::GeomCylinder"),
    "cone, 200 degrees": lambda: _lateral(
        Part.makeCone(20, 8, 30, Vector(), Vector(0, 0, 1), 200), "Part::GeomCone"),
    "sphere patch": lambda: _lateral(
        Part.makeSphere(25, Vector(), Vector(0, 0, 1), -30, 60, 150), "Part::GeomSphere"),
    "drilled half cylinder": lambda: _drill(
        Part.makeCylinder(10, 30, Vector(), Vector(0, 0, 1), 180), "Part::GeomCylinder",
        3, Vector(0, -100, 15), Vector(0, 1, 0)),
    "drilled cone, 180 degrees": lambda: _drill(
        Part.makeCone(20, 10, 40, Vector(), Vector(0, 0, 1), 180), "Part::GeomCone",
        5, Vector(0, -100, 20), Vector(0, 1, 0)),
    "drilled sphere patch": lambda: _drill(
        Part.makeSphere(25, Vector(), Vector(0, 0, 1), -30, 60, 150), "Part::GeomSphere",
        4, Vector(0, 0, 0), Vector(math.cos(1.3), math.sin(1.3), 0.3)),
}

#: Whole (closed) faces: no longer C0 (see test_whole_faces_are_not_c0 for what remains).
WHOLE = {
    "cylinder": lambda: _lateral(Part.makeCylinder(5, 10), "Part::GeomCylinder"),
    "cone": lambda: _lateral(Part.makeCone(5, 2, 10), "Part::GeomCone"),
    "sphere": lambda: Part.makeSphere(5).Faces[0],
}


def _check_errors(shape):
    try:
        shape.check(True)
    except ValueError as error:
        return str(error)
    return ""


def _area(native, face):
    return native.mass_properties(face.exportBrepToString(), 1e-10)[0]


def test_occts_own_conversion_is_refused_by_its_check():
    # Why the conversion is VarSurf's own: Part's toNurbs of a cylinder fails the same check.
    assert "GeomAbs_C0" in _check_errors(Part.makeCylinder(5, 10).Faces[0].toNurbs())


@pytest.mark.parametrize("scene", sorted(FACES))
def test_sheet_on_a_partial_or_trimmed_face_is_the_face_and_passes_the_check(scene, native):
    base = FACES[scene]()
    result = solve_sheet_on_face(base, [], rest="base").shape
    assert _check_errors(result) == ""
    size = base.BoundBox.DiagonalLength
    assert farthest(inside_points(result, 30, 1), base) <= 1e-9 * size
    assert farthest(inside_points(base, 30, 2), result) <= 1e-9 * size
    assert _area(native, result) == pytest.approx(_area(native, base), rel=1e-9)
    assert len(result.Wires) == len(base.Wires)


@pytest.mark.parametrize("scene", sorted(WHOLE))
def test_whole_faces_are_not_c0(scene, native):
    base = WHOLE[scene]()
    result = solve_sheet_on_face(base, [], rest="base").shape
    surface = result.Faces[0].Surface
    # Knot-smooth in both directions: no interior knot as multiple as the degree.
    for mults, degree in ((surface.getUMultiplicities(), surface.UDegree),
                          (surface.getVMultiplicities(), surface.VDegree)):
        assert max(mults[1:-1]) < degree
    assert "GeomAbs_C0" not in _check_errors(result)
    size = base.BoundBox.DiagonalLength
    assert farthest(inside_points(result, 30, 1), base) <= 1e-9 * size
    assert farthest(inside_points(base, 30, 2), result) <= 1e-9 * size
    assert _area(native, result) == pytest.approx(_area(native, base), rel=1e-9)


def test_a_sheet_pulled_off_a_half_cylinder_passes_the_check(native):
    base = FACES["half cylinder"]()
    # An arc 1.5 mm outside the cylinder (radius 10 about (5, -3)), half-way up, over 40..140 deg.
    arc = Part.ArcOfCircle(Part.Circle(Vector(5, -3, 17), Vector(0, 0, 1), 11.5),
                           math.radians(40), math.radians(140)).toShape()
    outcome = solve_sheet_on_face(base, [arc], rest="base")
    result = outcome.shape
    assert outcome.max_deviation < 0.01
    assert result.distToShape(arc)[0] < 0.01
    assert _check_errors(result) == ""


@pytest.mark.parametrize("kind", ["cylinder", "cone"])
def test_a_solid_of_sheets_on_a_half_primitive_passes_the_check(kind, doc, native):
    """Sheets on the four faces of a half cylinder (or cone), joined along the edges they share
    (half circles among them: a join curve along a circle was C0 too), make a solid that passes
    check(True) and holds the primitive's volume."""
    import varsurf

    shape = (Part.makeCylinder(10, 30, Vector(), Vector(0, 0, 1), 180) if kind == "cylinder"
             else Part.makeCone(10, 4, 20, Vector(), Vector(0, 0, 1), 180))
    feature = doc.addObject("Part::Feature", "Half")
    feature.Shape = shape
    doc.recompute()

    def shared_edges(face):
        return [(feature, f"Edge{k + 1}") for k, edge in enumerate(shape.Edges)
                if any(edge.isSame(own) for own in face.Edges)]

    sheets = [varsurf.make_sheet((feature, f"Face{i + 1}"), shared_edges(face), name=f"S{i}")
              for i, face in enumerate(shape.Faces)]
    solid = varsurf.make_solid(sheets, name="HalfSolid")
    doc.recompute()
    assert solid.Status.startswith("OK: solid"), solid.Status
    assert _check_errors(solid.Shape) == ""
    volume = native.mass_properties(solid.Shape.exportBrepToString(), 1e-10)[1]
    half = (math.pi * 10 ** 2 * 30 / 2 if kind == "cylinder"
            else math.pi * 20 * (10 ** 2 + 10 * 4 + 4 ** 2) / 6)  # half a frustum
    assert volume == pytest.approx(half, rel=1e-9)
