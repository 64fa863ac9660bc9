#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: Welch & Witkin's Figure 2 motion. The rounded box (rounded_box.py), with its
top front edge made a variational SpaceCurve: moving the handle in its middle reshapes the curve,
and the two sheets joined along it (top and front) follow in one joint solve; the box stays a
valid closed solid.

    /usr/bin/python3 examples/moving_curve.py [LIFT_MM] [OUT_DIR]   (defaults: 8, out/moving_curve)
"""

import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402

import rounded_box  # noqa: E402
import varsurf  # noqa: E402

V = FreeCAD.Vector
#: The edge made variational: from corner (-1, -1, 1) to (1, -1, 1), on the top and front faces.
EDGE = ((-1, -1, 1), (1, -1, 1))


def build(doc):
    """The rounded box with EDGE variational; returns (solid, space curve)."""
    solid = rounded_box.build(doc, variational=EDGE)
    curve = next(o for o in doc.Objects if o.Name.startswith("SpaceCurve"))
    return solid, curve


def lift(doc, curve, amount):
    """Move the middle handle up by ``amount`` mm and recompute."""
    varsurf.move_handle(curve, 1, curve.Handles[1] + V(0, 0, amount))
    doc.recompute()


def main(amount="8", out_dir="out/moving_curve"):
    doc = FreeCAD.newDocument("MovingCurve")
    solid, curve = build(doc)
    volume = solid.Shape.Volume
    print(f"before : {solid.Status}, volume {volume:.0f} mm^3")
    lift(doc, curve, float(amount))
    print(f"after  : {solid.Status}, volume {solid.Shape.Volume:.0f} mm^3 ({solid.JointSolve})")
    if not solid.isValid() or not solid.Closed:
        print(solid.getStatusString())
        return 1
    fcstd, step = freecad_env.write_outputs(doc, solid, out_dir, "moving_curve")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
