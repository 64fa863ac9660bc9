#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a hinge pair. Two sheets meet along a wavy curve and a Hinge holds the angle
between them all along it; the Solid reports the angle reached along the seam.

    /usr/bin/python3 examples/hinge_pair.py [ANGLE_DEG] [OUT_DIR]   (defaults: 120, out/hinge_pair)

Each sheet is bounded by the shared curve, a far edge 60 mm away and 20 mm up, and two side
curves that leave the seam at the hinge's angle (where curves meet, the sheet's tangent plane is
theirs: a hinge can only hold an angle the corners allow).
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector
LENGTH = 100.0  # along the seam (y)
WIDTH = 60.0  # from the seam to each far edge
RISE = 20.0  # height of the far edges
WAVE = 8.0  # the seam rises by this much in its middle, level at its ends
#: Spans per direction: turning a sheet's tangent plane along a trimmed seam takes a band about a
#: span wide; with 16 the band is too coarse and the sheet ripples beside the seam (looked at).
SPANS = 32


def _seam():
    """Level at both ends (its first and last two poles are level), WAVE up in the middle."""
    heights = [0.0, 0.0, 0.5, 1.0, 0.5, 0.0, 0.0]
    poles = [V(0, LENGTH * k / (len(heights) - 1), WAVE * h) for k, h in enumerate(heights)]
    curve = Part.BSplineCurve()
    curve.buildFromPoles(poles, False, 3)
    return curve.toShape()


def _side(y, sign, angle):
    """From the seam's end to the far edge, leaving the seam so that the two sides open by the
    hinge's angle."""
    lift = math.radians(90.0 - angle / 2.0)  # from the horizontal
    start = V(0, y, 0)
    end = V(sign * WIDTH, y, RISE)
    reach = WIDTH / 3.0
    poles = [start, start + V(sign * math.cos(lift), 0, math.sin(lift)) * reach,
             end - V(sign * reach, 0, 0), end]
    curve = Part.BSplineCurve()
    curve.buildFromPoles(poles)
    return curve.toShape()


def build(doc, angle=120.0):
    """The four curves per sheet, the two sheets, their Solid and the Hinge."""
    seam = doc.addObject("Part::Feature", "Seam")
    seam.Shape = _seam()
    sheets = []
    for name, sign in (("Left", -1), ("Right", 1)):
        edges = doc.addObject("Part::Feature", name + "Edges")
        far = Part.makeLine(V(sign * WIDTH, 0, RISE), V(sign * WIDTH, LENGTH, RISE))
        edges.Shape = Part.Compound([_side(0.0, sign, angle), far, _side(LENGTH, sign, angle)])
        doc.recompute()
        sheet = varsurf.make_sheet(None, [(seam, "Edge1"), (edges, ("Edge1", "Edge2", "Edge3"))],
                                   name=name, fix_boundary=False)
        sheet.Tolerance = 0.001
        sheet.MinSpans = SPANS
        sheets.append(sheet)
    solid = varsurf.make_solid(sheets, name="HingePair")
    varsurf.make_hinge(solid, sheets[0], sheets[1], (seam, "Edge1"), angle=angle)
    doc.recompute()
    return solid


def main(angle="120", out_dir="out/hinge_pair"):
    doc = FreeCAD.newDocument("HingePair")
    solid = build(doc, float(angle))
    print(f"status : {solid.Status}")
    if not solid.isValid() or solid.Shape.isNull():
        print(solid.getStatusString())
        return 1
    lo, hi = solid.HingeAngles[0], solid.HingeAngles[1]
    print(f"hinge  : target {float(angle):.2f} deg, reached {lo:.4f} .. {hi:.4f} deg along the seam "
          f"(largest error {solid.HingeErrors[0]:.2g} deg)")
    print(f"solve  : {solid.JointSolve}")
    fcstd, step = freecad_env.write_outputs(doc, solid, out_dir, "hinge_pair")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
