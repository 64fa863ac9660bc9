#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a corner blend. A Part box has the three edges at one corner filleted; where
the fillets meet, OpenCASCADE puts a spherical patch. That three-sided corner is replaced by a
sheet G1 to all three fillets: one closed solid, parametric in the box and the fillet radius.

    /usr/bin/python3 examples/corner_blend.py [OUT_DIR]        (default: out/corner_blend)

G2 to the three fillets is refused, naming the corners: each fillet (a cylinder) is flat along
its axis, which at a corner of the patch is the direction along the next fillet's arc, curved
by 1/radius. No surface can take both curvatures there (the classic vertex-blend conflict).

Writes corner_blend.FCStd and corner_blend.step into OUT_DIR and prints how the sheet joins the
fillets (largest gap and angle along each edge, 200 points each).
"""

import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402

import varsurf  # noqa: E402

V = FreeCAD.Vector
LENGTH, WIDTH, HEIGHT, RADIUS = 60.0, 40.0, 30.0, 6.0


def corner_patch(shape):
    """The face where the three fillets meet (OpenCASCADE makes it a piece of a sphere)."""
    return next(i for i, f in enumerate(shape.Faces) if f.Surface.TypeId == "Part::GeomSphere")


def build(doc, radius=RADIUS):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = LENGTH, WIDTH, HEIGHT
    doc.recompute()
    corner = V(LENGTH, WIDTH, HEIGHT)
    at_corner = [k + 1 for k, e in enumerate(box.Shape.Edges)
                 if any((v.Point - corner).Length < 1e-9 for v in e.Vertexes)]
    fillet = doc.addObject("Part::Fillet", "Fillet")
    fillet.Base = box
    fillet.Edges = [(k, radius, radius) for k in at_corner]
    doc.recompute()
    blend = varsurf.make_fill_hole(fillet, f"Face{corner_patch(fillet.Shape) + 1}", continuity="G1",
                                   tolerance=0.001, name="CornerBlend")
    doc.recompute()
    return blend


def main(out_dir="out/corner_blend"):
    doc = FreeCAD.newDocument("CornerBlend")
    blend = build(doc)
    print(f"status : {blend.Status}")
    if not blend.isValid() or blend.Shape.isNull():
        print(blend.getStatusString())
        return 1
    for name, gap, angle in zip(blend.JoinNames, blend.JoinGaps, blend.JoinAngles):
        print(f"{name}: gap {gap:.2g} mm, angle {angle:.2g} deg")
    fcstd, step = freecad_env.write_outputs(doc, blend, out_dir, "corner_blend")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
