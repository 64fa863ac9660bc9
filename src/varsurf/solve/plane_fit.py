# SPDX-License-Identifier: LGPL-2.1-or-later
"""The start of a sheet made from curves alone: the best-fit plane of the curves."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from varsurf.solve import shapes
from varsurf.solve.errors import SheetError
from varsurf.solve.settings import DEFAULT_MIN_SPANS, SHEET_MIN_DEGREE

#: Points per curve for the best-fit plane of a sheet made from curves alone, and the margin
#: (fraction of the curves' extent) by which its rectangle overhangs them.
PLANE_FIT_SAMPLES = 64
PLANE_MARGIN = 0.1


def _canonical(axis):
    """The axis pointing to +z, else (lying in the xy plane) to +y, else +x. An SVD's signs are
    its library's choice (OpenBLAS picked the opposite u direction for the hinge pair's sheets on
    another processor): fixed here, the same curves give the same sheet, parametrized and facing
    the same way, on every machine."""
    for component in (2, 1, 0):
        if abs(axis[component]) > 1e-9:
            return axis if axis[component] > 0 else -axis
    return axis


def plane_face_for_curves(edges: Sequence, spans: int = DEFAULT_MIN_SPANS, margin: float = PLANE_MARGIN,
                          degree: int = SHEET_MIN_DEGREE):
    """A planar B-spline face for a sheet made from curves alone (Michalik & Bruderlin's
    interpolation mode): the least-squares plane of points sampled on the curves, as a rectangle
    covering their projection with ``margin`` overhang, of ``degree`` with ``spans`` uniform
    spans per direction (simple interior knots: the sheet is C^(degree - 1)).

    Raises SheetError without curves, or when the curves do not span a plane (all on one line).
    """
    points = []
    for edge in edges:
        points.extend((p.x, p.y, p.z) for p in edge.discretize(PLANE_FIT_SAMPLES))
    if not points:
        raise SheetError("a sheet without a base face needs at least one curve: link a base face, or curves")
    pts = np.asarray(points, dtype=float)
    if not np.all(np.isfinite(pts)):
        raise SheetError("the curves have non-finite points: redraw them, or remove them from the Curves")
    center = pts.mean(axis=0)
    # Principal axes: the two largest spread directions span the plane, the smallest is its normal.
    _, sing, axes = np.linalg.svd(pts - center, full_matrices=False)
    extent = float(np.ptp(pts, axis=0).max())
    if extent <= 0.0 or sing[1] <= 1e-9 * max(sing[0], 1e-300):
        raise SheetError(
            "the curves lie on one line: they do not define a surface without a base face; link a base face, "
            "or add a curve off that line"
        )
    e1, e2 = _canonical(axes[0]), _canonical(axes[1])
    s, t = (pts - center) @ e1, (pts - center) @ e2
    grow = margin * max(np.ptp(s), np.ptp(t))
    s0, s1 = s.min() - grow, s.max() + grow
    t0, t1 = t.min() - grow, t.max() + grow
    p = int(degree)
    knots = [k / spans for k in range(spans + 1)]
    mults = [p + 1] + [1] * (spans - 1) + [p + 1]
    flat = [0.0] * (p + 1) + knots[1:-1] + [1.0] * (p + 1)
    # Poles at the Greville abscissae make the parametrization linear: the face is the plane.
    greville = [sum(flat[i + 1:i + p + 1]) / p for i in range(len(flat) - p - 1)]
    poles = [
        [shapes.vector(*(center + (s0 + a * (s1 - s0)) * e1 + (t0 + b * (t1 - t0)) * e2)) for b in greville]
        for a in greville
    ]
    surface = shapes.part().BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, p, p)
    return surface.toShape()
