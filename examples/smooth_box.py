#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a box with a smooth band. Six sheets joined along twelve curves: a top and a
bottom rim, each a rounded square of four pieces that are tangent-continuous where they meet, and
four slanted edges (the band tapers). Hinges at 180 degrees make the four side sheets one smooth band around the
box; the rims stay sharp edges (about 90 degrees) to the top and bottom sheets.

    /usr/bin/python3 examples/smooth_box.py [OUT_DIR]        (default: out/smooth_box)

Where a smooth seam meets a rim, both side sheets contain the rim's tangent there, so the rim
must be tangent-continuous at the corner: a hinge can only hold an angle the corners allow.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector
TOP_RADIUS = 60.0  # corners of the top rim lie on this circle
BOTTOM_RADIUS = 45.0  # and of the bottom rim: the band tapers
HEIGHT = 40.0  # half the box's height
PULL = 0.3  # of a chord: how far a rim piece leaves its corner along the corner's tangent
SPANS = 32


def _corner(k, radius, z):
    angle = math.radians(45.0 + 90.0 * k)
    return V(radius * math.cos(angle), radius * math.sin(angle), z)


def _tangent(k):
    """The rim's direction at corner k (counter-clockwise, along the circle through the corners):
    the same for the pieces on both sides of the corner, so the rim turns smoothly there."""
    angle = math.radians(45.0 + 90.0 * k)
    return V(-math.sin(angle), math.cos(angle), 0)


def _arc(k, radius, z):
    """The rim piece from corner k to k + 1: a cubic leaving and reaching the corners along
    their tangents, flatter than a circle (a rounded square)."""
    a, b = _corner(k, radius, z), _corner(k + 1, radius, z)
    reach = PULL * (b - a).Length
    curve = Part.BSplineCurve()
    curve.buildFromPoles([a, a + _tangent(k) * reach, b - _tangent(k + 1) * reach, b])
    return curve.toShape()


def build(doc):
    """The twelve curves, six sheets, the Solid and four 180-degree hinges on the verticals."""
    def feature(name, shape):
        obj = doc.addObject("Part::Feature", name)
        obj.Shape = shape
        return obj

    tops = [feature(f"TopRim{k}", _arc(k, TOP_RADIUS, HEIGHT)) for k in range(4)]
    bottoms = [feature(f"BottomRim{k}", _arc(k, BOTTOM_RADIUS, -HEIGHT)) for k in range(4)]
    verticals = [feature(f"Vertical{k}", Part.makeLine(_corner(k, BOTTOM_RADIUS, -HEIGHT),
                                                       _corner(k, TOP_RADIUS, HEIGHT)))
                 for k in range(4)]
    doc.recompute()

    def sheet(name, curves):
        s = varsurf.make_sheet(None, [(c, "Edge1") for c in curves], name=name, fix_boundary=False,
                               min_spans=SPANS)
        s.Tolerance = 0.001
        return s

    sides = [sheet(f"Side{k}", [tops[k], bottoms[k], verticals[k], verticals[(k + 1) % 4]])
             for k in range(4)]
    caps = [sheet("Top", tops), sheet("Bottom", bottoms)]
    solid = varsurf.make_solid(sides + caps, name="SmoothBox")
    for k in range(4):  # vertical k is shared by side k - 1 and side k
        varsurf.make_hinge(solid, sides[k - 1], sides[k], (verticals[k], "Edge1"), angle=180.0,
                           name=f"Smooth{k}")
    doc.recompute()
    return solid


def main(out_dir="out/smooth_box"):
    doc = FreeCAD.newDocument("SmoothBox")
    solid = build(doc)
    print(f"status : {solid.Status}")
    if not solid.isValid() or solid.Shape.isNull():
        print(solid.getStatusString())
        return 1
    print(f"volume : {solid.Shape.Volume:.0f} mm^3; hinge errors (deg): "
          f"{', '.join(f'{e:.3g}' for e in solid.HingeErrors)}")
    print(f"seams  : {[round(a, 2) for a in solid.SeamAngles]}")
    print(f"solve  : {solid.JointSolve}")
    fcstd, step = freecad_env.write_outputs(doc, solid, out_dir, "smooth_box")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
