# SPDX-License-Identifier: LGPL-2.1-or-later
"""Part shapes from and to what the extension returns: BREP (text or binary) and native curves.

This is the only module of the solve tier that uses FreeCAD's Part, and only when a shape is
made: the tier imports (and its math runs) without FreeCAD, shapes cross into the extension as
BREP text, so FreeCAD and the extension need only share OpenCASCADE, not any C++ types.
"""

from __future__ import annotations

import os
import tempfile

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


def _scratch_dir():
    """Where binary BREP passes through: memory (/dev/shm) where the system has it."""
    shm = "/dev/shm"
    return shm if os.path.isdir(shm) and os.access(shm, os.W_OK) else tempfile.gettempdir()


def shape_from_binary(data: bytes):
    """A Part shape from the extension's binary BREP (its ``face_binary``). FreeCAD 0.20 reads
    binary BREP only from a file (``importBinary(filename)``), so the bytes pass through a file
    in memory: for a 64 x 64 pole face that took 0.8 ms against 13 ms for BREP text written by
    the extension and read by importBrepFromString (measured), on every move of a drag."""
    handle, path = tempfile.mkstemp(prefix="varsurf-", suffix=".brep.bin", dir=_scratch_dir())
    try:
        with os.fdopen(handle, "wb") as out:
            out.write(data)
        shape = part().Shape()
        shape.importBinary(path)
    finally:
        os.unlink(path)
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
