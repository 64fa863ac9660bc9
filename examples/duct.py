#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a duct from a rectangular port to a round one. A closed sheet through a
sketched rounded rectangle (4 lines and 4 tangent arcs, 60 x 30 mm, 6 mm corners) and a Part
circle 12 mm in radius 50 mm above it, bulged by a sketched arc on one side. The sheet is closed
around the duct, ends on the sketch's lines and arcs and on the circle, and follows the arc; edit
the sketch (a corner radius) and it recomputes.

    /usr/bin/python3 examples/duct.py [OUT_DIR]        (default: out/duct)

Writes duct.FCStd and duct.step into OUT_DIR and prints how far each curve is from the sheet.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402
import Sketcher  # noqa: E402  (registers Sketcher::SketchObject)

import varsurf  # noqa: E402

V = FreeCAD.Vector


def rounded_rectangle(doc, name, width, height, radius, placement=None):
    """A sketch of a width x height rectangle with corners rounded to radius, centred on its
    origin: lines and arcs joined end to end and tangent, constrained as a user draws them."""
    sketch = doc.addObject("Sketcher::SketchObject", name)
    sketch.Placement = placement or FreeCAD.Placement()
    a, b, r = width / 2, height / 2, radius
    geometry = []
    corners = [(a - r, -b + r, -90), (a - r, b - r, 0), (-a + r, b - r, 90), (-a + r, -b + r, 180)]
    sides = [((-a + r, -b), (a - r, -b)), ((a, -b + r), (a, b - r)), ((a - r, b), (-a + r, b)),
             ((-a, b - r), (-a, -b + r))]
    for (p, q), (cx, cy, start) in zip(sides, corners):
        geometry.append(Part.LineSegment(V(p[0], p[1], 0), V(q[0], q[1], 0)))
        geometry.append(Part.ArcOfCircle(Part.Circle(V(cx, cy, 0), V(0, 0, 1), r), math.radians(start),
                                         math.radians(start + 90)))
    sketch.addGeometry(geometry, False)
    # Each line runs into the next arc's start, each arc into the next line's start, tangent;
    # the sides straight, the corners equal, the size and the centre given: fully constrained,
    # so editing a radius keeps the rest.
    for k in range(0, 8, 2):
        sketch.addConstraint(Sketcher.Constraint("Tangent", k, 2, k + 1, 1))
        sketch.addConstraint(Sketcher.Constraint("Tangent", k + 1, 2, (k + 2) % 8, 1))
    for k in (0, 4):
        sketch.addConstraint(Sketcher.Constraint("Horizontal", k))
    for k in (2, 6):
        sketch.addConstraint(Sketcher.Constraint("Vertical", k))
    sketch.addConstraint(Sketcher.Constraint("Radius", 1, r))
    for k in (3, 5, 7):
        sketch.addConstraint(Sketcher.Constraint("Equal", 1, k))
    sketch.addConstraint(Sketcher.Constraint("DistanceX", 6, 1, 2, 1, width))
    sketch.addConstraint(Sketcher.Constraint("DistanceY", 0, 1, 4, 1, height))
    sketch.addConstraint(Sketcher.Constraint("Symmetric", 0, 1, 4, 1, -1, 1))
    return sketch


def bulge(doc, name="Bulge"):
    """A sketched arc in the plane x = 0 from the rectangle's long side up to the circle,
    bowed 4 mm outward."""
    sketch = doc.addObject("Sketcher::SketchObject", name)
    # Sketch x -> world y, sketch y -> world z.
    sketch.Placement = FreeCAD.Placement(V(0, 0, 0), FreeCAD.Rotation(V(1, 1, 1), 120))
    arc = Part.Arc(V(15.0, 0, 0), V(17.5, 25.0, 0), V(12.0, 50.0, 0))
    sketch.addGeometry(Part.ArcOfCircle(arc.toShape().Curve, arc.FirstParameter, arc.LastParameter), False)
    return sketch


def build(doc):
    port = rounded_rectangle(doc, "Port", 60.0, 30.0, 6.0)
    round_port = doc.addObject("Part::Circle", "Round")
    round_port.Radius = 12.0
    round_port.Placement.Base = V(0, 0, 50)
    duct = varsurf.make_tube([port, round_port], [bulge(doc)], doc=doc, tolerance=0.01, name="Duct")
    doc.recompute()
    return duct


def main(out_dir="out/duct"):
    doc = FreeCAD.newDocument("Duct")
    duct = build(doc)
    print(f"status : {duct.Status}")
    if not duct.isValid() or duct.Shape.isNull():
        print(duct.getStatusString())
        return 1
    for name, deviation in zip(duct.CurveNames, duct.MaxDeviations):
        print(f"{name}: {deviation:.2g} mm from the sheet")
    fcstd, step = freecad_env.write_outputs(doc, duct, out_dir, "duct")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
