# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Curvature constraint (Du & Qin 4.7.3): the sheet's normal curvatures along u and v at a
point, signed toward the side its Vector names. Measured on the result face through OCCT's own
derivatives (not the solver's), on flat, cylindrical and sketch-bounded scenes; its sign, its
directions and scale (rigid motion: test_coupled_invariance.py); the command's start (the sheet's own curvature)."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.app import macro
from scenes import add_face, add_line_sketch, flat_face, poles_of
from step_check import assert_reads_back

V = FreeCAD.Vector
#: The solver iterates the curvature to 1e-4 of its value (SolveOptions.curvature_tolerance).
REL = 2e-4


def measured(sheet, uv, side):
    """Normal curvatures along u and v of the result face at normalized uv, signed toward `side`,
    from OCCT's derivatives."""
    surface = sheet.Shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    u, v = u0 + uv[0] * (u1 - u0), v0 + uv[1] * (v1 - v0)
    du, dv = surface.getDN(u, v, 1, 0), surface.getDN(u, v, 0, 1)
    n = du.cross(dv)
    n.normalize()
    if n.dot(V(*side)) < 0:
        n = -n
    return n.dot(surface.getDN(u, v, 2, 0)) / du.Length ** 2, n.dot(surface.getDN(u, v, 0, 2)) / dv.Length ** 2


def flat_sheet(doc, placement=None, scale=1.0):
    """A sheet over a flat 100 x 80 mm face (its boundary kept) through a low rail, optionally
    moved rigidly and scaled."""
    face = flat_face(100.0 * scale, 80.0 * scale)
    rail = Part.LineSegment(V(20, 15, 5) * scale, V(40, 20, 5) * scale).toShape()
    if placement is not None:
        face = face.transformGeometry(placement.toMatrix())
        rail = rail.transformGeometry(placement.toMatrix())
    base = add_face(doc, face)
    rail_obj = doc.addObject("Part::Feature", "Rail")
    rail_obj.Shape = rail
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [(rail_obj, "Edge1")])
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    return sheet


@pytest.mark.parametrize("kappa", [(0.01, 0.01), (0.02, -0.005), (-0.008, 0.0)])
def test_the_sheet_takes_the_curvatures_at_the_point(doc, native, kappa):
    sheet = flat_sheet(doc)
    c = varsurf.make_constraint(sheet, "Curvature", uv=(0.6, 0.45), vector=(0, 0, 1), curvature=kappa)
    doc.recompute()
    assert sheet.isValid() and c.isValid(), sheet.getStatusString()
    ku, kv = measured(sheet, (0.6, 0.45), (0, 0, 1))
    scale = max(abs(k) for k in kappa)  # a zero curvature is met to 1e-4 of the other's
    assert ku == pytest.approx(kappa[0], rel=REL, abs=REL * scale)
    assert kv == pytest.approx(kappa[1], rel=REL, abs=REL * scale)
    names = list(sheet.ConstraintNames)
    assert sheet.ConstraintResiduals[names.index(c.Label)] < REL * max(abs(k) for k in kappa)


def test_the_vector_names_the_side_it_bends_toward(doc, native):
    up, down = flat_sheet(doc), flat_sheet(doc)
    varsurf.make_constraint(up, "Curvature", uv=(0.5, 0.5), vector=(0, 0, 1), curvature=(0.01, 0.01))
    varsurf.make_constraint(down, "Curvature", uv=(0.5, 0.5), vector=(0.1, 0, -1), curvature=(0.01, 0.01))
    doc.recompute()
    assert measured(up, (0.5, 0.5), (0, 0, 1)) == pytest.approx((0.01, 0.01), rel=REL)
    assert measured(down, (0.5, 0.5), (0, 0, 1)) == pytest.approx((-0.01, -0.01), rel=REL)


def test_one_direction_leaves_the_other_to_the_energy(doc, native):
    sheet = flat_sheet(doc)
    c = varsurf.make_constraint(sheet, "Curvature", uv=(0.5, 0.5), vector=(0, 0, 1), curvature=(0.02, 0.5),
                                curvature_directions="U")
    doc.recompute()
    ku, kv = measured(sheet, (0.5, 0.5), (0, 0, 1))
    assert ku == pytest.approx(0.02, rel=REL)
    assert abs(kv) < 0.02  # CurvatureV (0.5) is not asked
    c.CurvatureDirections = "V"
    c.CurvatureV = 0.015
    doc.recompute()
    assert measured(sheet, (0.5, 0.5), (0, 0, 1))[1] == pytest.approx(0.015, rel=REL)


@pytest.mark.parametrize("scale", [0.01, 100.0])
def test_a_scaled_scene_with_scaled_curvature_scales(doc, native, scale):
    unit, scaled = flat_sheet(doc), flat_sheet(doc, scale=scale)
    varsurf.make_constraint(unit, "Curvature", uv=(0.55, 0.5), vector=(0, 0, 1), curvature=(0.01, 0.006))
    varsurf.make_constraint(scaled, "Curvature", uv=(0.55, 0.5), vector=(0, 0, 1),
                            curvature=(0.01 / scale, 0.006 / scale))
    doc.recompute()
    assert scaled.isValid(), scaled.getStatusString()
    off = max(math.dist([x * scale for x in p], q) for p, q in zip(poles_of(unit), poles_of(scaled)))
    assert off < 1e-6 * 100.0 * scale


def test_on_a_cylinder_the_command_starts_from_the_sheets_own_curvature(doc, native):
    """A Sheet on a Part Cylinder's side bounded by a sketch line: the command's constraint asks for
    what the sheet has (nothing moves); doubling the curvature around the axis bends it tighter."""
    cylinder = doc.addObject("Part::Cylinder", "Cylinder")
    cylinder.Radius, cylinder.Height = 20.0, 60.0
    rail = add_line_sketch(doc, "Rail", 0.0, (25.0, -10.0), (25.0, 10.0))
    rail.Placement = FreeCAD.Placement(V(0, 0, 30), FreeCAD.Rotation(V(0, 1, 0), 90))
    doc.recompute()
    sheet = varsurf.make_sheet((cylinder, "Face1"), [])
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    before = poles_of(sheet)
    lines = macro.constraint_command_lines("Curvature", sheet, {})
    namespace = {"App": FreeCAD}
    for line in lines:
        exec(line, namespace)
    c = namespace["_constraint"]
    assert c.isValid() and sheet.isValid(), sheet.getStatusString()
    assert max(math.dist(p, q) for p, q in zip(before, poles_of(sheet))) < 1e-3
    ku, kv = float(c.CurvatureU), float(c.CurvatureV)
    assert max(abs(ku), abs(kv)) == pytest.approx(1 / 20.0, rel=1e-3)  # around the axis: 1 / radius
    around = 0 if abs(ku) > abs(kv) else 1
    target = [ku, kv]
    target[around] *= 2.0
    c.CurvatureU, c.CurvatureV = target
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    got = measured(sheet, (0.5, 0.5), tuple(c.Vector))
    assert got[around] == pytest.approx(target[around], rel=REL)
    assert got[1 - around] == pytest.approx(target[1 - around], abs=REL * abs(target[around]))


def test_the_curvature_survives_step(doc, native, tmp_path):
    """The sheet written to STEP reads back sound, with the asked curvatures at the point."""
    sheet = flat_sheet(doc)
    varsurf.make_constraint(sheet, "Curvature", uv=(0.4, 0.55), vector=(0, 0, 1), curvature=(0.015, -0.01))
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    path = tmp_path / "curvature.step"
    varsurf.export_step(sheet, str(path))
    back = assert_reads_back(sheet.Shape, path, native)

    class Read:  # measured() reads the face from .Shape
        Shape = back

    ku, kv = measured(Read, (0.4, 0.55), (0, 0, 1))
    assert ku == pytest.approx(0.015, rel=REL) and kv == pytest.approx(-0.01, rel=REL)
