# SPDX-License-Identifier: LGPL-2.1-or-later
"""Variational space curves (Welch & Witkin sec. 5, Figure 2), without a document.

A variational curve starts as a given edge (its rest shape) and is reshaped by handles: points of
the curve moved to new positions. Alone, it minimizes the energy of its displacement from the rest
shape, ``integral stretch |D'|^2 + bend |D''|^2 dt``, through its handles, so it keeps its shape
where no handle pulls it. Joined to sheets in a Solid, its poles become unknowns of the joint
system (varsurf.solve.joint), so the sheets pull on it as it pulls on them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Sequence, Tuple

from varsurf.solve import shapes
from varsurf.solve.errors import SheetError
from varsurf.solve.native import build, native

#: Spans the rest curve is refined to (knot insertion, shape unchanged): the freedom handles and
#: sheets have to bend it.
DEFAULT_SPANS = 16
#: A rational base (arcs, circles) is approximated by a cubic B-spline within this distance (mm):
#: the energy of a displacement is quadratic only on a non-rational curve.
APPROXIMATION_TOLERANCE = 1e-6
#: Default energy of the displacement: pure bending.
DEFAULT_STRETCH = 0.0
DEFAULT_BEND = 1.0


@dataclass
class VariationalCurve:
    """What a joint solve needs of a variational curve."""

    start: object  # _native.BSplineCurve: the rest shape, and the knots of the unknown curve
    handles: List[Tuple[float, Tuple[float, float, float]]] = field(default_factory=list)  # (t, xyz)
    stretch: float = DEFAULT_STRETCH
    bend: float = DEFAULT_BEND
    closed: bool = False  # a ring: its two ends one point, the displacement smooth across it

    def native(self, nat):
        curve = nat.SpaceCurve()
        curve.start = self.start
        curve.variational = True
        curve.stretch = float(self.stretch)
        curve.bend = float(self.bend)
        curve.closed = bool(self.closed)
        handles = []
        for t, target in self.handles:
            h = nat.CurveHandle()
            h.t = float(t)
            h.target = [float(x) for x in target]
            handles.append(h)
        curve.handles = handles
        return curve


def rest_curve(edge, spans: int = DEFAULT_SPANS):
    """The edge as a non-rational B-spline of degree >= 3 with >= ``spans`` spans (Part curve).

    A closed edge (a circle, a closed B-spline) gives a curve whose two ends meet: solve it as a
    closed VariationalCurve. SheetError for an edge that cannot be converted.
    """
    if getattr(edge, "ShapeType", None) != "Edge":
        raise SheetError("a space curve's base must be an edge: link an edge (EdgeN) as its Base")
    if not 1 <= int(spans) <= 512:
        raise SheetError(f"Spans must be in 1..512 (got {spans}): set Spans in that range")
    first, last = edge.FirstParameter, edge.LastParameter
    try:
        curve = edge.Curve.toBSpline(first, last)
    except Exception as error:
        raise SheetError(f"the base edge cannot be converted to a B-spline: {error}; link another edge as "
                         "its Base") from error
    if curve.isRational():
        points = edge.discretize(Number=max(8 * int(spans), 64))
        curve = shapes.part().BSplineCurve()
        curve.approximate(Points=points, DegMin=3, DegMax=3, Tolerance=APPROXIMATION_TOLERANCE)
    if curve.isPeriodic():
        curve.setNotPeriodic()
    if curve.Degree < 3:
        curve.increaseDegree(3)
    a, b = curve.FirstParameter, curve.LastParameter
    for k in range(1, int(spans)):
        curve.insertKnot(a + (b - a) * k / int(spans), 1, 1e-9 * (b - a))
    return curve


def to_native(nat, curve):
    return nat.curve_from_edge_brep(curve.toShape().exportBrepToString())


def handles_at(start_part_curve, parameters: Sequence[float], positions: Sequence) -> list:
    """(t, xyz) handles from normalized parameters (0..1 along the rest curve) and positions."""
    if len(parameters) != len(positions):
        raise SheetError(f"{len(parameters)} handle parameters but {len(positions)} handle positions")
    a, b = start_part_curve.FirstParameter, start_part_curve.LastParameter
    out = []
    for i, (s, p) in enumerate(zip(parameters, positions)):
        xyz = (float(p[0]), float(p[1]), float(p[2]))
        if not (0.0 <= float(s) <= 1.0) or not all(math.isfinite(x) for x in xyz):
            raise SheetError(f"handle {i + 1}: the parameter must be in 0..1 and the position finite")
        out.append((a + (b - a) * float(s), xyz))
    return out


def solve_alone(curve: VariationalCurve):
    """The curve through its handles on its own (no sheets): a native BSplineCurve."""
    nat = native()
    problem = nat.ModelProblem()
    problem.curves = [curve.native(nat)]
    try:
        result = nat.solve_model(problem)
    except nat.InvalidInput as error:
        raise SheetError(str(error)) from error
    start = curve.start
    return build(nat.BSplineCurve, degree=start.degree, knots=list(start.knots),
                 poles=result.curve_poles[0])
