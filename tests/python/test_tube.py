# SPDX-License-Identifier: LGPL-2.1-or-later
"""Tubes through closed sections: a bottle neck between two rings, shaped by a curve between them,
built from FreeCAD primitives the way a user would (Part circles and ellipses, a B-spline ring).
The sheet is closed around its seam, ends on its two end sections, passes through the others and
the curves, and is parametric in the sections."""

import math

import FreeCAD
import Part
import pytest

import bottle_neck
import varsurf
from step_check import assert_reads_back

V = FreeCAD.Vector


def _seam(face, samples=30):
    """The largest angle (°) between the normals on the two sides of the face's seam, and the
    largest gap (mm) between them, by OCCT's evaluation of its B-spline."""
    surface = face.Surface
    u0, u1, v0, v1 = surface.bounds()
    angle = gap = 0.0
    for k in range(1, samples):
        v = v0 + (v1 - v0) * k / samples
        gap = max(gap, (surface.value(u0, v) - surface.value(u1, v)).Length)
        angle = max(angle, math.degrees(surface.normal(u0, v).getAngle(surface.normal(u1, v))))
    return angle, gap


def _through(face, edge, samples=40):
    """The largest distance from points of `edge` to `face`."""
    return max(face.distToShape(Part.Vertex(p))[0] for p in edge.discretize(samples))


def test_a_bottle_neck_between_two_rings_shaped_by_a_wavy_ring(doc, native, tmp_path):
    """examples/bottle_neck.py: two Part circles and a wavy B-spline ring between them."""
    import freecad_env

    tube = bottle_neck.build(doc)
    bottom, top, waist = (doc.getObject(n) for n in ("Bottom", "Top", "Waist"))
    assert tube.isValid(), tube.Status
    face = tube.Shape.Faces[0]
    assert [o.Name for o in tube.Base[0].Sections] == ["Bottom", "Top"]
    assert max(tube.MaxDeviations) <= 0.01, tube.MaxDeviations
    for obj in (bottom, top, waist):
        assert _through(face, obj.Shape.Edges[0]) <= 0.01, obj.Name
    angle, gap = _seam(face)
    assert angle <= 0.01 and gap <= 1e-7, (angle, gap)
    assert face.isValid() and face.check(True) is None
    # Its two ends are the two rings: a closed bottle when capped.
    caps = [Part.Face(Part.Wire(obj.Shape.Edges[0])) for obj in (bottom, top)]
    sewn = native.sew_faces_brep([f.exportBrepToString() for f in [face] + caps], 1e-6)
    assert sewn.closed and sewn.valid
    # The waist moves the tube: the loft alone through the two rings passes it by a millimetre.
    assert _through(tube.Base[0].Shape.Faces[0], waist.Shape.Edges[0]) >= 1.0
    _fcstd, step = freecad_env.write_outputs(doc, tube, str(tmp_path), "bottle_neck")
    assert_reads_back(tube.Shape, step, native)
    # Parametric: a wider top ring recomputes the loft and the tube.
    top.Radius = 10.0
    doc.recompute()
    assert tube.isValid(), tube.Status
    assert _through(tube.Shape.Faces[0], top.Shape.Edges[0]) <= 0.01


def test_three_sections_with_an_ellipse_in_the_middle(doc):
    bottom = bottle_neck.ring(doc, "Bottom", 12.0, 0.0)
    middle = doc.addObject("Part::Ellipse", "Middle")
    middle.MajorRadius, middle.MinorRadius = 16.0, 10.0
    middle.Placement.Base = V(0, 0, 25)
    top = bottle_neck.ring(doc, "Top", 9.0, 50.0)
    # Given out of order: the tube orders its sections along itself (the first one given before
    # the last one given).
    tube = varsurf.make_tube([middle, top, bottom], doc=doc, tolerance=0.01)
    doc.recompute()
    assert tube.isValid(), tube.Status
    assert [o.Name for o in tube.Base[0].Sections] == ["Top", "Middle", "Bottom"]
    face = tube.Shape.Faces[0]
    assert _through(face, middle.Shape.Edges[0]) <= 0.01
    angle, gap = _seam(face)
    assert angle <= 0.01 and gap <= 1e-7, (angle, gap)
    assert face.check(True) is None


def test_sections_that_cannot_be_ordered_are_refused_naming_them(doc):
    """Two rings in one plane around one centre: no order along a tube. Nothing is created."""
    a = bottle_neck.ring(doc, "Outer", 20.0, 0.0)
    b = bottle_neck.ring(doc, "Inner", 10.0, 0.0)
    doc.recompute()
    before = {o.Name for o in doc.Objects}
    with pytest.raises(ValueError, match="Outer and Inner are at the same place along the tube"):
        varsurf.make_tube([a, b], doc=doc)
    line = doc.addObject("Part::Line", "Open")
    doc.recompute()
    with pytest.raises(ValueError, match="Open is not one closed curve"):
        varsurf.make_tube([a, line], doc=doc)
    assert {o.Name for o in doc.Objects} == before | {"Open"}
