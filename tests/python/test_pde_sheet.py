# SPDX-License-Identifier: LGPL-2.1-or-later
"""Sheets with Energy = PDE (Du & Qin's generalized Bloor-Wilson equation) in FreeCAD documents:
closed-form solutions reproduced, painted coefficients, the displacement model, rigid motion,
saving, undo and bad input."""


import FreeCAD
import numpy as np
import Part
import pytest

import varsurf
from scenes import V, add_arc_sketch, add_face, add_line_sketch, curved_face, reopened

A = 2.0


def harmonic(s, t, a=A):
    """z with z_ss + a^2 z_tt = 0: its PDE energy is zero, so a sheet with its boundary reproduces
    it whatever else the energy's natural conditions ask."""
    return 10.0 * (s * s - t * t / a ** 2) + 5.0 * (s ** 3 - 3.0 * s * t * t / a ** 2) + 4.0 * s * t


def graph_face(z, interior_lift=0.0, spans=4, width=100.0, depth=80.0):
    """A bicubic B-spline face x = width s, y = depth t, z(s, t) over [0, 1]^2, exact for a cubic z
    (its poles interpolate z at the Greville points), the interior poles lifted by interior_lift."""
    n = spans + 3
    flat = [0.0] * 4 + [k / spans for k in range(1, spans)] + [1.0] * 4
    g = [sum(flat[i + 1:i + 4]) / 3.0 for i in range(n)]
    collocation = np.array([[_bspline_basis(flat, 3, i, x) for i in range(n)] for x in g])
    inverse = np.linalg.inv(collocation)
    poles_z = inverse @ np.array([[z(a, c) for c in g] for a in g]) @ inverse.T
    poles = [[V(width * g[i], depth * g[j], float(poles_z[i, j])
                + (interior_lift if 0 < i < n - 1 and 0 < j < n - 1 else 0.0)) for j in range(n)] for i in range(n)]
    mults = [4] + [1] * (spans - 1) + [4]
    knots = [k / spans for k in range(spans + 1)]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
    return surface.toShape()


def _bspline_basis(knots, degree, i, x):
    """N_i,degree(x) by the Cox-de Boor recursion (x = 1 belongs to the last function)."""
    if degree == 0:
        last = x == knots[-1] and knots[i + 1] == knots[-1] and knots[i] < knots[i + 1]
        return 1.0 if (knots[i] <= x < knots[i + 1]) or last else 0.0
    out = 0.0
    if knots[i + degree] > knots[i]:
        out += (x - knots[i]) / (knots[i + degree] - knots[i]) * _bspline_basis(knots, degree - 1, i, x)
    if knots[i + degree + 1] > knots[i + 1]:
        out += (knots[i + degree + 1] - x) / (knots[i + degree + 1] - knots[i + 1]) * _bspline_basis(
            knots, degree - 1, i + 1, x)
    return out


def farthest(shape, z, width=100.0, depth=80.0, n=21):
    """Largest |shape's z - z(x / width, y / depth)| over an n x n grid of its parameters."""
    surface = shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    worst = 0.0
    for i in range(n):
        for j in range(n):
            p = surface.value(u0 + (u1 - u0) * i / (n - 1), v0 + (v1 - v0) * j / (n - 1))
            worst = max(worst, abs(p.z - z(p.x / width, p.y / depth)))
    return worst


def test_reproduces_a_harmonic_surface_from_its_boundary(doc):
    base = add_face(doc, graph_face(harmonic, interior_lift=3.0))
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [], energy="PDE", pde_a=A)
    sheet.RestShape = "None"
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert farthest(sheet.Shape, harmonic) < 1e-6
    # Another a, or the thin plate, is another surface: the test tells them apart.
    sheet.PdeA = 1.0
    doc.recompute()
    assert farthest(sheet.Shape, harmonic) > 0.05
    sheet.Energy = "ThinPlate"
    doc.recompute()
    assert farthest(sheet.Shape, harmonic) > 0.05


def test_displacement_model_keeps_the_base_and_meets_a_point(doc):
    base = add_face(doc, curved_face())
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [], energy="PDE", pde_a=3.0)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    # Nothing asks for a change: the displacement is zero, the sheet is the base.
    face = base.Shape.Faces[0]
    assert max(sheet.Shape.Faces[0].Surface.value(u, v).distanceToPoint(face.Surface.value(u, v))
               for u in (0.1, 0.4, 0.7) for v in (0.2, 0.5, 0.9)) < 1e-7
    point = face.Surface.value(0.4, 0.6) + V(0, 0, 5.0)
    varsurf.make_constraint(sheet, "Point", uv=(0.4, 0.6), origin=point)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert sheet.Shape.distToShape(Part.Vertex(point))[0] < 2 * sheet.Tolerance.Value
    # The boundary stays the base's.
    for edge in face.Edges:
        at = edge.valueAt(edge.FirstParameter * 0.3 + edge.LastParameter * 0.7)
        assert sheet.Shape.distToShape(Part.Vertex(at))[0] < 1e-6


def _sketch_scene(doc, placement=FreeCAD.Placement()):
    """Curves alone: a mixed sketch of lines and an arc, and a higher line (the sheet's plane and
    rectangle come from their best fit)."""
    low = add_line_sketch(doc, "Low", 0.0, (0.0, 0.0), (100.0, 0.0))
    high = add_line_sketch(doc, "High", 0.0, (0.0, 80.0), (100.0, 80.0))
    arc = add_arc_sketch(doc, "Arc", 12.0, (50.0, 40.0), 25.0, 20.0, 160.0)
    for s in (low, high, arc):
        s.Placement = placement.multiply(s.Placement)
    doc.recompute()
    return [(low, "Edge1"), (high, "Edge1"), (arc, "Edge1")]


def _sample(shape, n=9):
    surface = shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    return [surface.value(u0 + (u1 - u0) * i / (n - 1), v0 + (v1 - v0) * j / (n - 1))
            for i in range(n) for j in range(n)]


def test_sheet_from_sketch_curves_meets_them_and_moves_rigidly(doc):
    curves = _sketch_scene(doc)
    sheet = varsurf.make_sheet(None, curves, energy="PDE", pde_a=1.5)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert max(sheet.MaxDeviations) <= sheet.Tolerance.Value
    thin = varsurf.make_sheet(None, curves, name="Thin")
    doc.recompute()
    assert max(thin.MaxDeviations) <= thin.Tolerance.Value
    # Through the same curves, the PDE's surface is not the thin plate's.
    assert max(thin.Shape.distToShape(Part.Vertex(p))[0] for p in _sample(sheet.Shape)) > 0.05
    # The same scene moved rigidly: the sheet moves with it.
    motion = FreeCAD.Placement(V(40.0, -25.0, 310.0), FreeCAD.Rotation(V(1, 2, 3), 37.0))
    other = FreeCAD.newDocument("Moved")
    try:
        moved_curves = _sketch_scene(other, motion)
        moved = varsurf.make_sheet(None, moved_curves, energy="PDE", pde_a=1.5)
        other.recompute()
        assert moved.isValid(), moved.getStatusString()
        expected = [motion.multVec(p) for p in _sample(sheet.Shape)]
        assert max(moved.Shape.distToShape(Part.Vertex(p))[0] for p in expected) < 1e-5
    finally:
        FreeCAD.closeDocument(other.Name)


def _pde_scene(doc):
    """The harmonic surface's boundary, its interior lifted, and a PDE sheet on it (a = 3)."""
    base = add_face(doc, graph_face(harmonic, interior_lift=3.0))
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [], energy="PDE", pde_a=3.0)
    sheet.RestShape = "None"
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    return sheet


def _poles(sheet):
    return [p for row in sheet.Shape.Faces[0].Surface.getPoles() for p in row]


def test_painted_region_saves_and_reopens(doc, tmp_path):
    sheet = _pde_scene(doc)
    plain = _poles(sheet)
    doc.openTransaction("Paint a")
    sheet.PdeRegions = [5.0, 0.5, 0.9, 0.5, 0.9]
    sheet.PdeBlend = 0.05
    doc.commitTransaction()
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    painted, name = _poles(sheet), sheet.Name
    assert max(p.distanceToPoint(q) for p, q in zip(plain, painted)) > 1e-3
    with reopened(doc, tmp_path / "pde.FCStd") as again:
        copy = again.getObject(name)
        assert copy.Energy == "PDE" and list(copy.PdeRegions) == [5.0, 0.5, 0.9, 0.5, 0.9]
        copy.touch()
        again.recompute()
        assert copy.isValid(), copy.getStatusString()
        assert max(p.distanceToPoint(q) for p, q in zip(painted, _poles(copy))) < 1e-9


def test_painted_region_undo_restores_the_shape(doc):
    sheet = _pde_scene(doc)
    plain = _poles(sheet)
    doc.openTransaction("Paint a")
    sheet.PdeRegions = [5.0, 0.5, 0.9, 0.5, 0.9]
    doc.commitTransaction()
    doc.recompute()
    assert max(p.distanceToPoint(q) for p, q in zip(plain, _poles(sheet))) > 1e-3
    doc.undo()
    doc.recompute()
    assert list(sheet.PdeRegions) == []
    assert max(p.distanceToPoint(q) for p, q in zip(plain, _poles(sheet))) < 1e-9


@pytest.mark.parametrize("prop, value, words", [
    ("PdeRegions", [5.0, 0.6, 0.2, 0.0, 1.0], "PdeRegions: region 1 spans u 0.6..0.2"),
    ("PdeRegions", [5.0, 0.1, 0.2, 0.0], "PdeRegions needs five numbers"),
    ("PdeRegions", [0.0, 0.1, 0.2, 0.0, 1.0], "PdeRegions: region 1 paints a = 0.0"),
    ("PdeBlend", 0.8, "PdeBlend must be in [0, 0.5]"),
])
def test_bad_pde_settings_leave_the_sheet_in_error_and_the_document_intact(doc, prop, value, words):
    sheet = _pde_scene(doc)
    before = _poles(sheet)
    setattr(sheet, prop, value)
    doc.recompute()
    assert not sheet.isValid()
    assert words in sheet.getStatusString(), sheet.getStatusString()
    base = doc.getObject("Surface")
    assert base.isValid() and not base.Shape.isNull()
    setattr(sheet, prop, [] if prop == "PdeRegions" else 0.0)
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert max(p.distanceToPoint(q) for p, q in zip(before, _poles(sheet))) < 1e-9
