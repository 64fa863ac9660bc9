#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a pillow. Two sheets joined along one closed, non-planar 3D curve and pushed
apart by pressure close into a smooth solid.

    /usr/bin/python3 examples/pillow.py [OUT_DIR]        (default: out/pillow)

Writes pillow.FCStd and pillow.step into OUT_DIR and prints the solid's volume and status.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector


def add_rim(doc):
    """The rim: a closed B-spline through an ellipse 80 x 50 mm with a 4 mm wave in z."""
    rim_points = [V(40 * math.cos(t), 25 * math.sin(t), 4 * math.sin(2 * t))
                  for t in (2 * math.pi * k / 64 for k in range(64))]
    curve = Part.BSplineCurve()
    curve.interpolate(rim_points, PeriodicFlag=True)
    rim = doc.addObject("Part::Feature", "Rim")
    rim.Shape = curve.toShape()
    return rim


def build(doc):
    """The rim, two flat bases and the Solid."""
    rim = add_rim(doc)
    sheets = []
    for name, pressure in (("Top", 0.1), ("Bottom", -0.1)):
        base = doc.addObject("Part::Feature", name + "Base")
        base.Shape = Part.makePlane(120, 90, V(-60, -45, 0))
        base.Visibility = False
        doc.recompute()
        sheet = varsurf.make_sheet((base, "Face1"), [(rim, "Edge1")], name=name)
        sheet.Stretch = 1.0  # membrane tension: what holds a pressure
        sheet.Tolerance = 0.001  # the seam is as tight as the sheets meet the rim
        sheet.Pressure = pressure
        # The sheet ends on the rim: its energy and pressure act inside the rim only, so the part of
        # the base beyond it cannot pull the rim into a valley (a knife-edge seam).
        sheet.Trim = "Loop"
        sheets.append(sheet)
    solid = varsurf.make_solid(sheets, name="Pillow")
    doc.recompute()
    return solid


def main(out_dir="out/pillow"):
    doc = FreeCAD.newDocument("Pillow")
    solid = build(doc)
    print(f"status : {solid.Status}")
    if not solid.isValid() or solid.Shape.isNull():
        print(solid.getStatusString())
        return 1
    print(f"volume : {solid.Shape.Volume:.1f} mm^3, area {solid.Shape.Area:.1f} mm^2")
    fcstd, step = freecad_env.write_outputs(doc, solid, out_dir, "pillow")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
