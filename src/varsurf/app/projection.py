# SPDX-License-Identifier: LGPL-2.1-or-later
"""How a Sheet's curves find their place on the base face: the direction each is projected along.

A curve drawn in a sketch above a curved base means "this, seen from the sketch's side": its
orthogonal projection onto a wavy face jumps from valley to valley once the sketch is a few
waves' height above it, while its shadow along the sketch's normal stays continuous. Other
curves (edges of solids, 3D curves) are projected orthogonally, onto the nearest point.
"""

from __future__ import annotations

import math

import FreeCAD

from varsurf.app.feature import value
from varsurf.solve import errors

#: Projection property values: Automatic (planar sketches facing the base along their normal,
#: other curves orthogonally), Normal (every curve orthogonally), Direction (every curve along
#: ProjectionDirection).
MODES = ("Automatic", "Normal", "Direction")
#: A sketch counts as facing the base when its normal is within this angle of the base's normal
#: at the face's centre (either side); a sketch standing across the base (a profile drawn in a
#: vertical plane over a flat part) is projected orthogonally instead.
FACING_DEGREES = 60.0


def sketch_normal(link_obj):
    """The global normal of a sketch (or None for anything that is not one)."""
    if not link_obj.isDerivedFrom("Sketcher::SketchObject"):
        return None
    placement = link_obj.getGlobalPlacement()
    normal = placement.Rotation.multVec(FreeCAD.Vector(0, 0, 1))
    return (normal.x, normal.y, normal.z)


def base_normal(face):
    """The face's normal at the middle of its parameter range (orientation included), or None
    where it has none (a degenerate face: the solve refuses it with its own message)."""
    u0, u1, v0, v1 = face.ParameterRange
    try:
        n = face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    except Exception:  # Part raises a bare Part.OCCError for "normal not defined"
        return None
    return (n.x, n.y, n.z)


def _facing(normal, reference):
    dot = abs(sum(a * b for a, b in zip(normal, reference)))
    return dot >= math.cos(math.radians(FACING_DEGREES))


def directions(obj, face, links):
    """One projection direction per curve of a Sheet (None: orthogonal projection).

    links: the (link object, sub-element) of each curve, in the solve's order.
    """
    mode = str(getattr(obj, "Projection", "Normal"))
    if mode == "Normal" or face is None:
        return [None] * len(links)
    if mode == "Direction":
        d = value(obj, "ProjectionDirection")
        if not all(math.isfinite(c) for c in (d.x, d.y, d.z)) or d.Length == 0.0:
            raise errors.SheetError("Projection is Direction but ProjectionDirection is zero: give the direction "
                                    "the curves are projected along (e.g. 0, 0, 1 for a plan view)")
        return [(d.x, d.y, d.z)] * len(links)
    reference = base_normal(face)
    closed = face.Surface.isUClosed() or face.Surface.isVClosed()
    found = []
    for link_obj, sub in links:
        normal = sketch_normal(link_obj)
        if normal is not None and closed:
            # Around a closed face (a tube) the normal at the middle of its parameters points
            # wherever the seam puts it: judge each curve by the normal where it lies.
            reference = _normal_near(face, link_obj, sub)
        facing = normal is not None and reference is not None and _facing(normal, reference)
        found.append(normal if facing else None)
    return found


def _normal_near(face, link_obj, sub):
    """The face's normal at the point nearest the middle of a curve, or None."""
    import Part

    try:
        edge = Part.getShape(link_obj, sub, needSubElement=True)
        middle = edge.valueAt(0.5 * (edge.FirstParameter + edge.LastParameter))
        n = face.normalAt(*face.Surface.parameter(middle))
    except Exception:  # a broken link or no normal: the solve reports it with its own message
        return None
    return (n.x, n.y, n.z)
