#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: a crowned lid. A Part box's flat top is replaced by a sheet that rises 8 mm
along two sketched arcs, ending on the top's four edges (G0 to the walls): one closed solid,
parametric in the box and the sketches.

    /usr/bin/python3 examples/crowned_lid.py [OUT_DIR]        (default: out/crowned_lid)

Writes crowned_lid.FCStd and crowned_lid.step into OUT_DIR and prints the solid's volume.
"""

import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Part  # noqa: E402
import Sketcher  # noqa: E402,F401  (registers Sketcher::SketchObject)

import varsurf  # noqa: E402

V = FreeCAD.Vector
LENGTH, WIDTH, HEIGHT, RISE = 100.0, 60.0, 40.0, 8.0


def add_arc_sketch(doc, name, x):
    """A sketch in the plane x = const (its x axis along the box's width, its y axis up) holding
    one arc from the top's front edge to its back edge, RISE above the top in the middle."""
    sketch = doc.addObject("Sketcher::SketchObject", name)
    # Sketch x -> world y, sketch y -> world z (a turn of 120 degrees about (1, 1, 1)).
    sketch.Placement = FreeCAD.Placement(V(x, 0, 0), FreeCAD.Rotation(V(1, 1, 1), 120))
    arc = Part.Arc(V(0, HEIGHT, 0), V(WIDTH / 2, HEIGHT + RISE, 0), V(WIDTH, HEIGHT, 0))
    sketch.addGeometry(Part.ArcOfCircle(arc.toShape().Curve, arc.FirstParameter, arc.LastParameter), False)
    return sketch


def build(doc):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = LENGTH, WIDTH, HEIGHT
    sketches = [add_arc_sketch(doc, f"Arc{k + 1}", x) for k, x in enumerate((0.3 * LENGTH, 0.7 * LENGTH))]
    doc.recompute()
    top = next(i for i, f in enumerate(box.Shape.Faces) if abs(f.CenterOfMass.z - HEIGHT) < 1e-9)
    lid = varsurf.make_fill_hole(box, f"Face{top + 1}", curves=[(s, "Edge1") for s in sketches],
                                 continuity="G0", name="CrownedLid")
    doc.recompute()
    return lid


def main(out_dir="out/crowned_lid"):
    doc = FreeCAD.newDocument("CrownedLid")
    lid = build(doc)
    print(f"status : {lid.Status}")
    if not lid.isValid() or lid.Shape.isNull():
        print(lid.getStatusString())
        return 1
    print(f"volume : {lid.Shape.Volume:.1f} mm^3 (the box alone: {LENGTH * WIDTH * HEIGHT:.1f})")
    fcstd, step = freecad_env.write_outputs(doc, lid, out_dir, "crowned_lid")
    print(f"written: {fcstd}, {step}")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
