# SPDX-License-Identifier: LGPL-2.1-or-later
"""Trimming sheets to pre-image loops and sewing them into a solid, through the Python binding
and FreeCAD's Part module: a pillow of two domes along the unit circle (volume pi)."""

import math

import numpy as np
import Part
import pytest

HALF = 1.2  # the domes span [-1.2, 1.2]^2


def dome(nat, sign):
    """z = sign (1 - x^2 - y^2) on one bicubic span (exact: Bernstein interpolation)."""
    space = nat.SplineSpace.uniform(3, 3, 1, 1)
    g = np.array([0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0])  # Greville abscissae of the single span
    bern = np.array([[math.comb(3, i) * t**i * (1 - t) ** (3 - i) for i in range(4)] for t in g])
    x = 2 * HALF * g - HALF
    values = np.array([[sign * (1 - a * a - b * b) for b in x] for a in x])
    z = np.linalg.solve(bern, np.linalg.solve(bern, values).T).T  # B z B^T = values
    poles = [[x[i], x[j], z[i, j]] for i in range(4) for j in range(4)]
    return nat.BSplineSurface(space=space, poles=poles)


def circle_loop(nat, pieces):
    """The unit circle's pre-image: centre (0.5, 0.5), radius 1 / 2.4, as rational arcs."""
    import FreeCAD

    loop = []
    for k in range(pieces):
        arc = Part.Geom2d.Circle2d(FreeCAD.Base.Vector2d(0.5, 0.5), 0.5 / HALF)
        b = arc.toBSpline(2 * math.pi * k / pieces, 2 * math.pi * (k + 1) / pieces)
        knots = [t for t, m in zip(b.getKnots(), b.getMultiplicities()) for _ in range(m)]
        poles = [[p.x, p.y] for p in b.getPoles()]
        loop.append(nat.BSplineCurve(degree=b.Degree, knots=knots, poles=poles, weights=b.getWeights()))
    return loop


def test_pillow_of_two_domes_is_a_closed_solid(native):
    nat = native
    top = nat.trimmed_face_brep(dome(nat, 1.0), circle_loop(nat, 2))
    bottom = nat.trimmed_face_brep(dome(nat, -1.0), circle_loop(nat, 3))
    result = nat.sew_faces_brep([top, bottom], 1e-6)
    assert result.closed and result.valid, result.message
    assert result.faces == 2 and result.free_edges == 0
    shape = Part.Shape()
    shape.importBrepFromString(result.brep)
    assert shape.ShapeType == "Solid" and shape.isValid()
    assert shape.Volume == pytest.approx(math.pi, rel=1e-6)
    assert shape.check(True) is None  # raises on any problem


def test_open_loops_are_refused(native):
    nat = native
    loop = circle_loop(nat, 3)[:2]
    with pytest.raises(nat.InvalidInput, match="does not close"):
        nat.trimmed_face_brep(dome(nat, 1.0), loop)
