# SPDX-License-Identifier: LGPL-2.1-or-later
"""Small documents for the tests: a gently curved bicubic base face and sketches above it."""

import contextlib
import math

import FreeCAD
import Part
import Sketcher

V = FreeCAD.Vector

WIDTH = 100.0  # mm along x (u)
DEPTH = 80.0  # mm along y (v)


def curved_face(width=WIDTH, depth=DEPTH, height=6.0, n=6):
    """A bicubic B-spline face with n x n poles over width x depth mm, a gentle dome."""
    poles = []
    for i in range(n):
        row = []
        for j in range(n):
            x = width * i / (n - 1)
            y = depth * j / (n - 1)
            z = height * math.sin(math.pi * i / (n - 1)) * math.sin(math.pi * j / (n - 1))
            z += 1.5 * (x / width) ** 2  # a slight tilt-like asymmetry, not a plane
            row.append(V(x, y, z))
        poles.append(row)
    spans = n - 3
    knots = [k / spans for k in range(spans + 1)]
    mults = [4] + [1] * (spans - 1) + [4]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
    return surface.toShape()


def _clamped(spans, degree=3):
    knots = [k / spans for k in range(spans + 1)]
    mults = [degree + 1] + [1] * (spans - 1) + [degree + 1]
    flat = [0.0] * (degree + 1) + knots[1:-1] + [1.0] * (degree + 1)
    greville = [sum(flat[i + 1:i + degree + 1]) / degree for i in range(len(flat) - degree - 1)]
    return knots, mults, greville


def flat_face(width=WIDTH, depth=DEPTH, z=0.0, spans=8):
    """A planar bicubic B-spline face ((spans + 3)^2 poles) at height z.

    Poles sit at the Greville abscissae, so x and y are linear in u and v: straight lines above
    the face project to straight pre-images, which the solver can meet exactly.
    """
    knots, mults, g = _clamped(spans)
    poles = [[V(width * a, depth * b, z) for b in g] for a in g]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
    return surface.toShape()


def add_face(doc, shape, name="Surface"):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shape
    return obj


def add_line_sketch(doc, name, z, start, end):
    """A sketch at height z holding one line whose end points are set by four datums.

    Constraint indices: 0, 1 = start x, y; 2, 3 = end x, y (editable with setDatum).
    """
    sketch = doc.addObject("Sketcher::SketchObject", name)
    sketch.Placement = FreeCAD.Placement(V(0, 0, z), FreeCAD.Rotation())
    sketch.addGeometry(Part.LineSegment(V(start[0], start[1], 0), V(end[0], end[1], 0)), False)
    sketch.addConstraint(Sketcher.Constraint("DistanceX", 0, 1, start[0]))
    sketch.addConstraint(Sketcher.Constraint("DistanceY", 0, 1, start[1]))
    sketch.addConstraint(Sketcher.Constraint("DistanceX", 0, 2, end[0]))
    sketch.addConstraint(Sketcher.Constraint("DistanceY", 0, 2, end[1]))
    return sketch


def add_arc_sketch(doc, name, z, center, radius, start_deg, end_deg):
    sketch = doc.addObject("Sketcher::SketchObject", name)
    sketch.Placement = FreeCAD.Placement(V(0, 0, z), FreeCAD.Rotation())
    circle = Part.Circle(V(center[0], center[1], 0), V(0, 0, 1), radius)
    arc = Part.ArcOfCircle(circle, math.radians(start_deg), math.radians(end_deg))
    sketch.addGeometry(arc, False)
    return sketch


def add_polyline_sketch(doc, name, z, points):
    sketch = doc.addObject("Sketcher::SketchObject", name)
    sketch.Placement = FreeCAD.Placement(V(0, 0, z), FreeCAD.Rotation())
    for k in range(len(points) - 1):
        a, b = points[k], points[k + 1]
        sketch.addGeometry(Part.LineSegment(V(a[0], a[1], 0), V(b[0], b[1], 0)), False)
        if k > 0:
            sketch.addConstraint(Sketcher.Constraint("Coincident", k - 1, 2, k, 1))
    return sketch


def poles_of(obj):
    """Poles of the (single) face of obj's shape as a flat list of (x, y, z)."""
    surface = obj.Shape.Faces[0].Surface
    return [(p.x, p.y, p.z) for row in surface.getPoles() for p in row]


class Sel:
    """Stands in for a Gui.Selection.getSelectionEx() item headless."""

    def __init__(self, obj, *subs):
        self.Object = obj
        self.SubElementNames = tuple(subs)
        self.HasSubObjects = bool(subs)


def railed_sheet(doc):
    """A Sheet over a flat 100 x 80 mm base at z = 0 (x = 100 u, y = 80 v) with its boundary
    kept, through a low rail 5 mm up."""
    import varsurf

    surface = add_face(doc, flat_face())
    rail = add_line_sketch(doc, "Rail", 5.0, (20.0, 15.0), (40.0, 20.0))
    doc.recompute()
    s = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")])
    doc.recompute()
    assert s.isValid(), s.getStatusString()
    return s


def residual_of(sheet, constraint):
    """The residual the Sheet reports for one of its constraints."""
    names = list(sheet.ConstraintNames)
    assert constraint.Label in names, names
    return sheet.ConstraintResiduals[names.index(constraint.Label)]


def add_vertex(doc, name, point):
    obj = doc.addObject("Part::Vertex", name)
    obj.X, obj.Y, obj.Z = point
    return obj


def add_shape(doc, name, shape):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = shape
    return obj


@contextlib.contextmanager
def reopened(doc, path):
    """Save ``doc`` to ``path``, close it and open the file again; yields the reopened document
    and closes it afterwards."""
    doc.saveAs(str(path))
    FreeCAD.closeDocument(doc.Name)
    again = FreeCAD.openDocument(str(path))
    try:
        yield again
    finally:
        FreeCAD.closeDocument(again.Name)


def recompute_all(doc):
    """Recompute every object, as after an edit upstream of everything."""
    for o in doc.Objects:
        o.touch()
    doc.recompute()
