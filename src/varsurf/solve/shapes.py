# SPDX-License-Identifier: LGPL-2.1-or-later
"""Part shapes from and to what the extension returns: BREP text and native curves.

This is the only module of the solve tier that uses FreeCAD's Part, and only when a shape is
made: the tier imports (and its math runs) without FreeCAD, shapes cross into the extension as
BREP text, so FreeCAD and the extension need only share OpenCASCADE, not any C++ types.
"""

from __future__ import annotations

from varsurf.solve.errors import SheetError
from varsurf.solve.native import native


def part():
    import Part  # here, not at the top: the solve tier imports without FreeCAD

    return Part


def vector(x, y, z):
    import FreeCAD  # as part(): only when a shape is made

    return FreeCAD.Vector(float(x), float(y), float(z))


def shape_from_brep(text: str):
    shape = part().Shape()
    shape.importBrepFromString(text)
    return shape


def single_face(shape, purpose="the extension's result"):
    """The one face of ``shape``, or SheetError (a ValueError) saying what needed it."""
    faces = getattr(shape, "Faces", None) or []
    if len(faces) != 1:
        raise SheetError(f"{purpose} needs one face (got {len(faces)}): give it a single face")
    return faces[0]


def part_curve(native_curve):
    """A Part.BSplineCurve with the native curve's knots and poles (non-rational)."""
    knots, mults = native().split_knots(list(native_curve.knots))
    poles = [vector(*row) for row in native_curve.poles]
    curve = part().BSplineCurve()
    curve.buildFromPolesMultsKnots(poles, mults, knots, False, int(native_curve.degree))
    return curve
