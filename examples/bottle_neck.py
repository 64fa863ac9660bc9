#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a bottle neck. A closed sheet through two rings (Part circles, 20 mm and 8 mm
across, 60 mm apart) and a wavy ring between them: the waist. The sheet is closed around its
seam (no crease, no gap there), ends on the two rings and passes through the waist; change a
ring's radius and both the loft it starts from and the sheet recompute.

    /usr/bin/python3 examples/bottle_neck.py [OUT_DIR]        (default: out/bottle_neck)

Writes bottle_neck.FCStd and bottle_neck.step into OUT_DIR and prints how far each curve is from
the sheet and how the sheet meets itself across its seam.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector


def ring(doc, name, radius, z):
    circle = doc.addObject("Part::Circle", name)
    circle.Radius = radius
    circle.Placement.Base = V(0, 0, z)
    return circle


def waist(doc, radius=15.0, z=30.0, wobble=2.0):
    """A closed B-spline around the axis, waving by `wobble` three times a turn."""
    curve = Part.BSplineCurve()
    curve.interpolate([V(radius * math.cos(a), radius * math.sin(a), z + wobble * math.sin(3 * a))
                       for a in (2 * math.pi * k / 24 for k in range(24))], PeriodicFlag=True)
    obj = doc.addObject("Part::Feature", "Waist")
    obj.Shape = curve.toShape()
    return obj


def build(doc):
    bottom, top = ring(doc, "Bottom", 20.0, 0.0), ring(doc, "Top", 8.0, 60.0)
    tube = varsurf.make_tube([bottom, top], [waist(doc)], doc=doc, tolerance=0.01, name="BottleNeck")
    doc.recompute()
    return tube


def seam(face, samples=30):
    """Largest angle (deg) and gap (mm) between the two sides of the face's seam."""
    s = face.Surface
    u0, u1, v0, v1 = s.bounds()
    vs = [v0 + (v1 - v0) * k / samples for k in range(1, samples)]
    return (max(math.degrees(s.normal(u0, v).getAngle(s.normal(u1, v))) for v in vs),
            max((s.value(u0, v) - s.value(u1, v)).Length for v in vs))


def main(out_dir="out/bottle_neck"):
    doc = FreeCAD.newDocument("BottleNeck")
    tube = build(doc)
    print(f"status : {tube.Status}")
    if not tube.isValid() or tube.Shape.isNull():
        print(tube.getStatusString())
        return 1
    for name, deviation in zip(tube.CurveNames, tube.MaxDeviations):
        print(f"{name}: {deviation:.2g} mm from the sheet")
    angle, gap = seam(tube.Shape.Faces[0])
    print(f"seam: {angle:.2g} deg, {gap:.2g} mm")
    fcstd, step = freecad_env.write_outputs(doc, tube, out_dir, "bottle_neck")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
