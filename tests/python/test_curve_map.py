# SPDX-License-Identifier: LGPL-2.1-or-later
"""The CurveMap constraint (Du & Qin 4.7.4): a source curve on the sheet is mapped onto a
destination curve, point for point at the same normalized parameter (the destination turned so
that its start is the end nearer the source's start). Measured on the result face: the image of the
source's pre-image follows the destination; reversed destinations, rigid motion, identity maps
and bad links."""

import math

import FreeCAD
import Part
import varsurf
from scenes import add_face, add_line_sketch, flat_face, poles_of
from step_check import assert_reads_back

V = FreeCAD.Vector


def scene(doc, placement=None, destination=None):
    """A sheet over a flat 100 x 80 mm face (boundary kept) and a source line on it, mapped onto
    an arc 8 mm above (or `destination`), all optionally moved."""
    m = placement.toMatrix() if placement is not None else FreeCAD.Matrix()
    base = add_face(doc, flat_face(100.0, 80.0).transformGeometry(m))
    source = doc.addObject("Part::Feature", "Source")
    source.Shape = Part.LineSegment(V(20, 30, 0), V(80, 45, 0)).toShape().transformGeometry(m)
    target = doc.addObject("Part::Feature", "Destination")
    shape = destination or Part.Arc(V(20, 30, 8), V(50, 45, 14), V(80, 45, 8)).toShape()
    target.Shape = shape.transformGeometry(m)
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [])
    c = varsurf.make_constraint(sheet, "CurveMap", curve=(source, "Edge1"), reference=(target, "Edge1"))
    doc.recompute()
    return sheet, c, source, target


def image_error(sheet, source, target):
    """Largest distance between the sheet's image of the source's points (their feet on the base,
    which is where the source lies) and the destination at the same normalized parameter."""
    edge, dest = source.Shape.Edges[0], target.Shape.Edges[0]
    face = sheet.Shape.Faces[0]
    surface = face.Surface
    a0, a1 = edge.ParameterRange
    b0, b1 = dest.ParameterRange
    start, end = dest.valueAt(b0), dest.valueAt(b1)
    flip = (start - edge.valueAt(a0)).Length + (end - edge.valueAt(a1)).Length > \
        (end - edge.valueAt(a0)).Length + (start - edge.valueAt(a1)).Length
    worst = 0.0
    base = sheet.Base[0].Shape.Faces[0].Surface
    for i in range(41):
        s = i / 40
        u, v = base.parameter(edge.valueAt(a0 + s * (a1 - a0)))
        t = b1 - s * (b1 - b0) if flip else b0 + s * (b1 - b0)
        worst = max(worst, (surface.value(u, v) - dest.valueAt(t)).Length)
    return worst


def test_the_source_is_mapped_onto_the_destination(doc, native):
    sheet, c, source, target = scene(doc)
    assert sheet.isValid() and c.isValid(), sheet.getStatusString()
    tolerance = float(sheet.Tolerance)
    assert image_error(sheet, source, target) < tolerance
    names = list(sheet.ConstraintNames)
    assert sheet.ConstraintResiduals[names.index(c.Label)] < tolerance
    assert sheet.Shape.BoundBox.ZMax > 13.0  # the arc's top is reached, not just its ends


def test_a_reversed_destination_maps_the_same_way(doc, native):
    forward, _c, source, target = scene(doc)
    arc = Part.Arc(V(80, 45, 8), V(50, 45, 14), V(20, 30, 8)).toShape()
    backward, _c2, _s2, _t2 = scene(doc, destination=arc)
    assert max(math.dist(p, q) for p, q in zip(poles_of(forward), poles_of(backward))) < 1e-9


def test_a_destination_equal_to_the_source_leaves_the_base(doc, native):
    sheet, c, source, target = scene(doc, destination=Part.LineSegment(V(20, 30, 0), V(80, 45, 0)).toShape())
    base = poles_of(sheet.Base[0])
    assert max(abs(p[2]) for p in poles_of(sheet)) < 1e-9
    assert len(base) > 0


def test_a_bspline_destination_from_a_sketch(doc, native):
    points = [V(20, 30, 4), V(40, 25, 12), V(60, 50, 6), V(80, 45, 10)]
    spline = Part.BSplineCurve()
    spline.interpolate(points)
    sheet, c, source, target = scene(doc, destination=spline.toShape())
    assert sheet.isValid(), sheet.getStatusString()
    assert image_error(sheet, source, target) < float(sheet.Tolerance)


def test_rigid_motion_moves_the_result_rigidly(doc, native):
    place = FreeCAD.Placement(V(-40, 120, 33), FreeCAD.Rotation(V(0.3, -1, 0.6), 71))
    plain, *_ = scene(doc)
    moved, *_ = scene(doc, place)
    a, b = plain.Shape.Faces[0].Surface, moved.Shape.Faces[0].Surface
    u0, u1, v0, v1 = a.bounds()
    worst = max((place.multVec(a.value(u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10))
                 - b.value(u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10)).Length
                for i in range(11) for j in range(11))
    assert worst < 1e-6


def test_bad_links_are_reported_on_the_constraint(doc, native, console_errors):
    sheet, c, source, target = scene(doc)
    good = poles_of(sheet)
    c.Reference = None
    doc.recompute()
    assert not c.isValid() and "needs a Curve (the source" in c.getStatusString(), c.getStatusString()
    assert "needs a Curve (the source" in console_errors()  # one line in the report view
    assert max(math.dist(p, q) for p, q in zip(good, poles_of(sheet))) < 1e-12
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    c.Reference = (box, "Face1")
    doc.recompute()
    assert not c.isValid() and "destination" in c.getStatusString(), c.getStatusString()


def test_sketch_edges_map_and_the_sheet_survives_step(doc, native, tmp_path):
    """The source a sketch's line on the base, the destination a B-spline drawn in a second sketch
    tilted 25 degrees above it (FreeCAD's own sketch geometry, not a scene made for the solver);
    the sheet written to STEP reads back sound and still maps the source."""
    base = add_face(doc, flat_face(100.0, 80.0))
    source = add_line_sketch(doc, "SourceSketch", 0.0, (20.0, 30.0), (80.0, 45.0))
    above = doc.addObject("Sketcher::SketchObject", "DestinationSketch")
    above.Placement = FreeCAD.Placement(V(0, 0, 6), FreeCAD.Rotation(V(1, 0, 0), 25))
    spline = Part.BSplineCurve()
    spline.interpolate([V(22, 28, 0), V(40, 22, 0), V(60, 40, 0), V(78, 36, 0)])
    above.addGeometry(spline, False)
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [])
    c = varsurf.make_constraint(sheet, "CurveMap", curve=(source, "Edge1"), reference=(above, "Edge1"))
    doc.recompute()
    assert sheet.isValid() and c.isValid(), sheet.getStatusString()
    assert image_error(sheet, source, above) < float(sheet.Tolerance)
    path = tmp_path / "curve_map.step"
    varsurf.export_step(sheet, str(path))
    back = assert_reads_back(sheet.Shape, path, native)
    a, b = sheet.Shape.Faces[0].Surface, back.Faces[0].Surface
    u0, u1, v0, v1 = a.bounds()
    assert max((a.value(u0 + (u1 - u0) * i / 8, v0 + (v1 - v0) * j / 8)
                - b.value(u0 + (u1 - u0) * i / 8, v0 + (v1 - v0) * j / 8)).Length
               for i in range(9) for j in range(9)) < 1e-9
