# SPDX-License-Identifier: LGPL-2.1-or-later
"""Constraints that couple x, y and z (normal, point in plane or on line, curvature, with the
curves of the sheet): the scene moved rigidly should give the moved result, to rounding.

Known defect, recorded here by strict expected failures: a coupled solve splits each curve into
x, y and z rows, three clusters the discrepancy principle truncates one by one, so a turned scene
keeps other directions (measured: up to 0.16 mm on this 100 mm sheet at a 0.01 mm tolerance).
Deciding the three together fixes these cases but changes the pillow example's seam so that
OCCT's 1 mm outward offset of it gains C0 faces; the fix waits for that to be understood."""

import random

import FreeCAD
import Part
import pytest

import varsurf
from scenes import add_face, flat_face

V = FreeCAD.Vector

#: kind -> make_constraint arguments in the unmoved scene (vectors and origins are moved along).
KINDS = {
    "Normal": dict(uv=(0.4, 0.6), vector=(0.3, -0.2, 1.0)),
    "PointInPlane": dict(uv=(0.6, 0.4), vector=(0.2, 0.1, 1.0), origin=(0.0, 0.0, 7.0)),
    "PointOnLine": dict(uv=(0.55, 0.5), vector=(0.0, 0.3, 1.0), origin=(55.0, 40.0, 0.0)),
    "Curvature": dict(uv=(0.4, 0.6), vector=(0.0, 0.0, 1.0), curvature=(0.012, 0.004)),
    "TangentU": dict(uv=(0.5, 0.5), vector=(100.0, 0.0, 20.0)),  # separable: the reference case
}


def motion(seed):
    rng = random.Random(seed)
    axis = V(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
    return FreeCAD.Placement(V(rng.uniform(-200, 200), rng.uniform(-200, 200), rng.uniform(-200, 200)),
                             FreeCAD.Rotation(axis, rng.uniform(5, 175)))


def sheet_in(doc, placement, kind):
    """A sheet over a flat 100 x 80 mm face through a rail 5 mm up and a second lower one, with one
    constraint of `kind`, all moved by `placement`."""
    m = placement.toMatrix()
    base = add_face(doc, flat_face(100.0, 80.0).transformGeometry(m))
    rails = []
    for name, a, b in (("RailA", V(20, 15, 5), V(40, 20, 5)), ("RailB", V(70, 55, 3), V(85, 30, 2))):
        obj = doc.addObject("Part::Feature", name)
        obj.Shape = Part.LineSegment(a, b).toShape().transformGeometry(m)
        rails.append((obj, "Edge1"))
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), rails)
    args = dict(KINDS[kind])
    rotate = placement.Rotation.multVec
    args["vector"] = tuple(rotate(V(*args["vector"])))
    if "origin" in args:
        args["origin"] = tuple(placement.multVec(V(*args["origin"])))
    varsurf.make_constraint(sheet, kind, **args)
    return sheet


#: (kind, seed) cases the per-coordinate truncation gets wrong today (see the module's note).
KNOWN = {(kind, seed) for kind in ("Normal", "PointOnLine", "Curvature") for seed in (1, 2, 3)}


@pytest.mark.parametrize("kind, seed", [
    pytest.param(kind, seed, marks=pytest.mark.xfail(strict=True, reason="coupled solves truncate x, y, z apart"))
    if (kind, seed) in KNOWN else (kind, seed) for kind in KINDS for seed in (1, 2, 3)])
def test_a_rigid_motion_moves_the_result_rigidly(doc, native, kind, seed):
    place = motion(seed)
    plain, moved = sheet_in(doc, FreeCAD.Placement(), kind), sheet_in(doc, place, kind)
    doc.recompute()
    assert plain.isValid() and moved.isValid(), (plain.getStatusString(), moved.getStatusString())
    a, b = plain.Shape.Faces[0].Surface, moved.Shape.Faces[0].Surface
    u0, u1, v0, v1 = a.bounds()
    worst = max((place.multVec(a.value(u0 + (u1 - u0) * i / 12, v0 + (v1 - v0) * j / 12))
                 - b.value(u0 + (u1 - u0) * i / 12, v0 + (v1 - v0) * j / 12)).Length
                for i in range(13) for j in range(13))
    assert worst < 1e-6, (kind, seed, worst)
