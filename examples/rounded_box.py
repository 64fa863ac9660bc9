#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a rounded box. Six sheets, one per face of a 100 mm cube, each passing through
the four edges of its face; the twelve edges bow outward, so the sheets bulge to meet them, and
the Solid joins the six sheets along the twelve shared curves into a closed solid.

    /usr/bin/python3 examples/rounded_box.py [OUT_DIR]        (default: out/rounded_box)
"""

import itertools
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector
HALF = 50.0  # the cube spans [-50, 50]^3
BOW = 6.0  # how far each edge's middle is pushed out, away from the cube's axis through it


def _edge_curve(a, b):
    """A cubic edge from corner a to b whose middle is pushed BOW mm out, away from the axis."""
    mid = (a + b) * 0.5
    axis = b - a
    axis.normalize()
    out = mid - axis * mid.dot(axis)  # from the cube's axis parallel to the edge, to the edge
    out.normalize()
    c = Part.BSplineCurve()
    c.interpolate([a, mid + out * BOW, b])
    return c.toShape()


def build(doc, variational=None):
    """The box; ``variational`` = (corner, corner) makes that edge a SpaceCurve the sheets share
    (moving_curve.py moves it)."""
    corners = {k: V(*(HALF * s for s in k)) for k in itertools.product((-1, 1), repeat=3)}
    edges = {}
    for k, v in corners.items():
        for axis in range(3):
            if k[axis] < 0:
                other = list(k)
                other[axis] = 1
                other = tuple(other)
                obj = doc.addObject("Part::Feature", "Edge")
                obj.Shape = _edge_curve(v, corners[other])
                edges[frozenset((k, other))] = (obj, "Edge1")
    if variational is not None:
        key = frozenset(variational)
        doc.recompute()
        edges[key] = (varsurf.make_space_curve(edges[key]), "Edge1")
        doc.recompute()
    sheets = []
    for axis in range(3):
        for side in (-1, 1):
            on_face = [key for key in edges if all(c[axis] == side for c in key)]
            # a flat base over the face, a little larger than it
            normal = V(*(side if i == axis else 0 for i in range(3)))
            centre = normal * HALF
            size = 2 * HALF + 30
            plane = Part.makePlane(size, size, V(0, 0, 0), normal)
            plane.translate(centre - plane.CenterOfMass)
            base = doc.addObject("Part::Feature", "Base")
            base.Shape = plane
            base.Visibility = False
            doc.recompute()
            sheet = varsurf.make_sheet((base, "Face1"), [edges[key] for key in on_face],
                                       name="Side")
            sheet.Tolerance = 0.001
            sheet.FixBoundary = False
            sheets.append(sheet)
    solid = varsurf.make_solid(sheets, name="RoundedBox")
    doc.recompute()
    return solid


def main(out_dir="out/rounded_box"):
    doc = FreeCAD.newDocument("RoundedBox")
    solid = build(doc)
    print(f"status : {solid.Status}")
    if not solid.isValid() or solid.Shape.isNull():
        print(solid.getStatusString())
        return 1
    print(f"volume : {solid.Shape.Volume:.0f} mm^3 (the plain cube: {8 * HALF ** 3:.0f})")
    fcstd, step = freecad_env.write_outputs(doc, solid, out_dir, "rounded_box")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
