# SPDX-License-Identifier: LGPL-2.1-or-later
"""Sheets on torus faces: a full torus (doubly periodic) and a partial one are taken as base faces
like any other, and with the base as rest shape and no curves the sheet is the torus itself,
measured against the torus's own equation and area."""

import math

import numpy as np
import pytest

R, r = 30.0, 8.0  # major and minor radius (mm)


def _torus_feature(doc, name, **angles):
    # Part's Torus starts the tube's angle at 180 degrees: its seams are not where a conversion of
    # the whole surface opens it.
    torus = doc.addObject("Part::Torus", name)
    torus.Radius1, torus.Radius2 = R, r
    for key, value in angles.items():
        setattr(torus, key, value)
    doc.recompute()
    return torus


def _off_torus(point):
    """Distance of a point from the torus about the z axis (its implicit equation)."""
    return abs(math.hypot(math.hypot(point.x, point.y) - R, point.z) - r)


def _area(surface, samples=8):
    """Area of a B-spline surface by Gauss-Legendre quadrature on each knot span (independent of
    OCCT's surface-property integration, which is coarse on rational B-splines)."""
    x, w = np.polynomial.legendre.leggauss(samples)
    total = 0.0
    us, vs = surface.getUKnots(), surface.getVKnots()
    for ua, ub in zip(us, us[1:]):
        for va, vb in zip(vs, vs[1:]):
            for xi, wi in zip(x, w):
                u = 0.5 * (ua + ub) + 0.5 * (ub - ua) * xi
                for yj, wj in zip(x, w):
                    v = 0.5 * (va + vb) + 0.5 * (vb - va) * yj
                    du, dv = surface.getDN(u, v, 1, 0), surface.getDN(u, v, 0, 1)
                    total += wi * wj * 0.25 * (ub - ua) * (vb - va) * du.cross(dv).Length
    return total


def _check_reproduces(sheet, base_face, area, angle_range):
    import Part

    assert sheet.isValid() and sheet.Status.startswith("OK"), sheet.Status
    face = sheet.Shape.Faces[0]
    size = base_face.BoundBox.DiagonalLength
    u0, u1, v0, v1 = face.ParameterRange
    grid = [face.valueAt(u0 + (u1 - u0) * i / 30, v0 + (v1 - v0) * j / 30) for i in range(31) for j in range(31)]
    # Every point of the sheet lies on the torus, inside the base face's angular range.
    assert max(_off_torus(p) for p in grid) <= 1e-9 * size
    lo, hi = angle_range
    for p in grid:
        angle = math.degrees(math.atan2(p.y, p.x))
        angle = angle + 360.0 if angle < -1e-7 else angle
        assert lo - 1e-7 <= angle <= hi + 1e-7, angle
    # ... and the sheet covers the face: points of the base face (its own parametrization) are on
    # the sheet, measured by OCCT's distToShape.
    a0, a1, b0, b1 = base_face.ParameterRange
    for i in range(9):
        for j in range(9):
            p = base_face.valueAt(a0 + (a1 - a0) * (i + 0.5) / 9, b0 + (b1 - b0) * (j + 0.5) / 9)
            assert face.distToShape(Part.Vertex(p))[0] <= 1e-9 * size
    assert _area(face.Surface) == pytest.approx(area, rel=1e-9)
    # The sheet's boundary is the face's (for a full torus: its two seams, wherever they lie).
    rim = Part.Compound(face.Edges)
    for edge in base_face.Edges:
        for p in edge.discretize(12):
            assert rim.distToShape(Part.Vertex(p))[0] <= 1e-9 * size


def test_a_full_torus_face_is_a_base(doc, native):
    import varsurf

    torus = _torus_feature(doc, "Torus")
    sheet = varsurf.make_sheet((torus, "Face1"), [], name="OnTorus")
    doc.recompute()
    _check_reproduces(sheet, torus.Shape.Faces[0], 4 * math.pi ** 2 * R * r, (0.0, 360.0))


def test_a_partial_torus_face_is_a_base(doc, native):
    import varsurf

    # The outer half of the tube (v in -90..90 degrees), swept over 200 degrees.
    torus = _torus_feature(doc, "HalfTorus", Angle1=-90.0, Angle2=90.0, Angle3=200.0)
    sheet = varsurf.make_sheet((torus, "Face1"), [], name="OnHalfTorus")
    doc.recompute()
    sweep = math.radians(200.0)
    area = sweep * r * (R * math.pi + 2 * r)  # integral of (R + r cos v) r dv du
    _check_reproduces(sheet, torus.Shape.Faces[0], area, (0.0, 200.0))
