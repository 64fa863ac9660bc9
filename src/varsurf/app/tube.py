# SPDX-License-Identifier: LGPL-2.1-or-later
"""Tubes: a closed Sheet through closed sections (a bottle neck between two rings) and curves
between them. The sections are ordered along the tube and lofted (FreeCAD's own Part Loft, so a
changed section recomputes the start shape); the Sheet on the loft's face is closed around its
seam, keeps the two end sections as its boundary and passes through the others and the curves.

A section of several edges (a sketched rounded rectangle: lines, arcs, B-splines) would make the
loft a face per edge. Then the Sheet starts from a TubeSkin instead: one smooth periodic curve per
section, all starting along the first section's x axis and winding as it does, skinned into one
face that does not twist. The Sheet still passes through the sections' own edges. App side only."""

from __future__ import annotations

import math
from typing import Iterable

import FreeCAD
import numpy as np
import Part

from varsurf.app.feature import FeatureProxy, mark_failed
from varsurf.app.make import make_sheet
from varsurf.solve.errors import SheetError
from varsurf.solve.tube import (CORNER_DEGREES, MAX_EDGE_SPANS, SAME_KNOT, SMOOTH_SAMPLES, SMOOTH_TOLERANCE,
                                periodic_basis, periodic_fit, section_order, skin)

TYPE = "VarSurf::TubeSkin"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Sections", "App::PropertyLinkList", "TubeSkin", "The closed sections, in their order along the tube", False),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]


def _closed_wire(obj):
    """The one closed wire of a section object, or ValueError naming it."""
    if "Touched" in obj.State:
        obj.recompute()  # a section edited or added in the same script
    shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull() or not shape.Edges:
        raise ValueError(f"tube section {obj.Label} has no curve: give a closed sketch, circle or closed B-spline")
    wires = shape.Wires or [Part.Wire(Part.__sortEdges__(shape.Edges))]
    if len(wires) != 1 or not wires[0].isClosed():
        raise ValueError(f"tube section {obj.Label} is not one closed curve: give each section as a closed sketch, "
                         "circle or closed B-spline")
    return wires[0]


def _away(edge, point):
    """The unit tangent of ``edge`` at its end at ``point``, pointing into the edge."""
    first, last = edge.FirstParameter, edge.LastParameter
    if (edge.valueAt(first) - point).Length <= (edge.valueAt(last) - point).Length:
        return edge.tangentAt(first)
    return -edge.tangentAt(last)


def _corners(wire):
    """(vertex point, degrees) of every join of the wire's edges that is not smooth."""
    found = []
    edges, vertices = wire.OrderedEdges, wire.OrderedVertexes
    for k, edge in enumerate(edges):  # vertex k joins edge k - 1 to edge k
        point = vertices[k].Point
        if len(edges) == 1:  # a closed edge meets itself: its end against its start
            into_end, into_start = -edge.tangentAt(edge.LastParameter), edge.tangentAt(edge.FirstParameter)
        else:
            into_end, into_start = _away(edges[k - 1], point), _away(edge, point)
        turn = 180.0 - math.degrees(into_end.getAngle(into_start))
        if turn > CORNER_DEGREES:
            found.append((point, turn))
    return found


def _refuse_corners(wire, label):
    corners = _corners(wire)
    if corners:
        point, turn = max(corners, key=lambda c: c[1])
        raise ValueError(
            f"tube section {label} has a corner at ({point.x:.6g}, {point.y:.6g}, {point.z:.6g}) where two edges "
            f"turn by {turn:.3g}°: a closed sheet is smooth around the tube and cannot follow it; round the corner "
            "(a fillet or tangent arc in the sketch)")


def _winding(points, centre):
    """The wound area vector of a closed polygon about its centre (its direction: right hand)."""
    total = FreeCAD.Vector()
    for a, b in zip(points, points[1:] + points[:1]):
        total += (a - centre).cross(b - centre)
    return total


class _Path:
    """A closed wire as a path by arc length: edge k runs from position starts[k] to starts[k+1]."""

    def __init__(self, wire, reverse):
        self.edges = list(wire.OrderedEdges)
        vertices = [v.Point for v in wire.OrderedVertexes]
        self.forward = [(e.valueAt(e.FirstParameter) - vertices[k]).Length
                        <= (e.valueAt(e.LastParameter) - vertices[k]).Length for k, e in enumerate(self.edges)]
        self.lengths = [e.Length for e in self.edges]
        if reverse:
            self.edges.reverse()
            self.lengths.reverse()
            self.forward = [not f for f in reversed(self.forward)]
        self.starts = [0.0]
        for length in self.lengths:
            self.starts.append(self.starts[-1] + length)
        self.length = self.starts[-1]

    def point(self, k, along):
        """The point ``along`` (mm) into edge k in the path's direction."""
        edge, length = self.edges[k], self.lengths[k]
        along = min(max(along, 0.0), length)
        return edge.valueAt(edge.getParameterByLength(along if self.forward[k] else length - along))


def smooth_section(wire, toward, axis, label):
    """One periodic cubic B-spline along ``wire`` (a closed wire of smoothly joined edges) by arc
    length, as (flat knots in [0, 1), poles k x 3, largest distance from the wire): C1 knots where
    its edges join, so lines and arcs are followed as they are (within SMOOTH_TOLERANCE of the
    wire's length); it starts at the wire's point in the direction ``toward`` from its centre and
    winds right-handed about ``axis``. ValueError naming a corner where two edges meet at an
    angle."""
    _refuse_corners(wire, label)
    centre = wire.CenterOfMass
    path = _Path(wire, reverse=_winding_axis(wire).dot(axis) < 0.0)
    start = _start(path, centre, toward, axis)
    curved = [not isinstance(e.Curve, Part.Line) for e in path.edges]
    spans = [2 if c else 1 for c in curved]
    target = SMOOTH_TOLERANCE * path.length
    for _round in range(12):
        knots, params, checks, owners = _fit_data(path, spans, start)
        poles = periodic_fit(knots, 3, path.length, [p for p, _ in params], [q for _, q in params])
        basis = periodic_basis(knots, 3, path.length, [p for p, _ in checks])
        errors = np.linalg.norm(basis @ poles - np.array([q for _, q in checks]), axis=1)
        worst = [0.0] * len(spans)
        for owner, error in zip(owners, errors):
            worst[owner] = max(worst[owner], float(error))
        coarse = [k for k, e in enumerate(worst) if e > target and spans[k] < MAX_EDGE_SPANS]
        if not coarse:
            break
        for k in coarse:
            spans[k] *= 2
    return [k / path.length for k in knots], poles, max(worst)


def _start(path, centre, toward, axis):
    """The arc-length position where the path leaves its centre most nearly toward ``toward``
    (across ``axis``): where every section of a tube starts, so that the skin does not twist."""
    side = FreeCAD.Vector(toward)
    side -= axis * (side.dot(axis) / max(axis.dot(axis), 1e-300))
    if side.Length == 0.0:
        return 0.0
    side.normalize()

    def closeness(s):
        k = max(j for j in range(len(path.edges)) if path.starts[j] <= s)
        radial = path.point(k, s - path.starts[k]) - centre
        return radial.normalize().dot(side) if radial.Length > 0.0 else -2.0

    step = path.length / (32 * len(path.edges))
    where = max((step * j for j in range(32 * len(path.edges))), key=closeness)
    for _round in range(8):  # narrow down around the best, to 1e-7 of the step
        step /= 8
        where = max((where + step * j for j in range(-8, 9)), key=lambda s: closeness(s % path.length))
    where %= path.length
    # A start a hair from an edge join would leave a knot span a hair wide (a circle's start is
    # its own join): start at the join.
    for join in path.starts:
        if abs(where - join) <= SAME_KNOT * path.length:
            return join % path.length
    return where


def _fit_data(path, spans, start):
    """Flat knots (shifted so that ``start`` is 0), fit samples and check samples (each a pair
    (parameter, point)) and the edge of each check sample, for ``spans`` spans per edge."""
    period = path.length

    def shifted(s):
        return (s - start) % period

    knots = []
    params, checks, owners = [], [], []
    for k, count in enumerate(spans):
        join = shifted(path.starts[k])
        knots += [join, join]  # C1 where edges meet: a line and an arc follow each other exactly
        for j in range(1, count):
            knots.append(shifted(path.starts[k] + path.lengths[k] * j / count))
        steps = 8 * count
        for j in range(steps):
            along = path.lengths[k] * j / steps
            params.append((shifted(path.starts[k] + along), path.point(k, along)))
            middle = along + path.lengths[k] / (2 * steps)
            checks.append((shifted(path.starts[k] + middle), path.point(k, middle)))
            owners.append(k)
    if not any(abs(s - start) <= SAME_KNOT * period for s in path.starts):
        knots.append(0.0)  # the curve starts inside an edge
    knots = [k if k < period * (1 - 1e-15) else 0.0 for k in knots]
    return sorted(knots), params, checks, owners


def _winding_axis(wire):
    return _winding(wire.discretize(Number=SMOOTH_SAMPLES + 1)[:-1], wire.CenterOfMass)


def ordered_sections(sections):
    """The section objects in the tube's order, or ValueError: a section that is not one closed
    curve, one of several edges with a corner, or sections that cannot be ordered."""
    wires = [_closed_wire(obj) for obj in sections]
    for obj, wire in zip(sections, wires):
        if len(wire.Edges) > 1:
            _refuse_corners(wire, obj.Label)
    extent = max(w.BoundBox.DiagonalLength for w in wires)
    try:
        order = section_order([o.Label for o in sections], [w.CenterOfMass for w in wires], extent)
    except SheetError as error:
        raise ValueError(str(error)) from error
    return [sections[i] for i in order]


def skin_surface(wires, labels, reference=FreeCAD.Vector(1, 0, 0)):
    """(The tube's start surface through closed ``wires`` in their order, a Part.BSplineSurface
    periodic around the tube; how far its ends may be from the wires): each wire's smooth curve
    starts toward the first wire's start (``reference``, the first section's x axis, when it is
    of several edges) and winds as the first wire does, so the skin does not twist."""
    first = wires[0]
    axis = _winding_axis(first)
    if axis.Length == 0.0:
        axis = wires[-1].CenterOfMass - first.CenterOfMass
    axis.normalize()
    # Where the sections start: a single curve's own start (a circle's along its x axis), else
    # the direction of the first section's own x axis, whatever order its edges were drawn in.
    toward = first.OrderedVertexes[0].Point - first.CenterOfMass if len(first.Edges) == 1 else FreeCAD.Vector(reference)
    sections, error = [], 0.0
    for wire, label in zip(wires, labels):
        knots, poles, smoothed = smooth_section(wire, toward, axis, label)
        sections.append((knots, poles, wire.CenterOfMass))
        error = max(error, smoothed)
    try:
        u_knots, v_knots, poles, v_degree, merged = skin(sections)
    except SheetError as error:
        raise ValueError(str(error)) from error
    unique_u = sorted(set(u_knots))
    unique_v = sorted(set(v_knots))
    u_mults = [u_knots.count(k) for k in unique_u]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(
        [[FreeCAD.Vector(*p) for p in row] for row in poles], u_mults + [u_mults[0]],
        [v_knots.count(k) for k in unique_v], unique_u + [1.0], unique_v, True, False, 3, v_degree)
    return surface, error + merged


class TubeSkinFeature(FeatureProxy):
    """Proxy of a TubeSkin (Part::FeaturePython): the face a tube's Sheet starts from when a
    section is made of several edges (a Part Loft through a mix of sketches and single curves
    makes a face per edge, or fails). One face through every section, closed around the tube."""

    Type = TYPE
    TYPE = TYPE
    PROPERTIES = _PROPERTIES

    def execute(self, obj):
        try:
            sections = list(obj.Sections)
            if len(sections) < 2:
                raise ValueError(f"a tube needs two or more sections (got {len(sections)})")
            placement = getattr(sections[0], "Placement", FreeCAD.Placement())
            surface, error = skin_surface([_closed_wire(o) for o in sections], [o.Label for o in sections],
                                          placement.Rotation.multVec(FreeCAD.Vector(1, 0, 0)))
        except Exception as error:
            raise mark_failed(obj, error) from error
        obj.Shape = surface.toShape()
        obj.Status = (f"OK: {surface.NbUPoles} x {surface.NbVPoles} poles through {len(sections)} sections, "
                      f"within {error:.2g} mm of them")


def _base(ordered, doc, name):
    """The face the tube's Sheet starts from: a Part Loft of the sections when each is one edge
    (circles stay exact), else a TubeSkin (hidden either way)."""
    if all(len(_closed_wire(obj).Edges) == 1 for obj in ordered):
        loft = doc.addObject("Part::Loft", f"{name}Loft")
        loft.Sections = ordered
        loft.Solid = False
        loft.Ruled = False
        loft.Closed = False
    else:
        loft = doc.addObject("Part::FeaturePython", f"{name}Skin")
        TubeSkinFeature(loft)
        loft.Sections = ordered
        loft.recompute()
        if "Invalid" in loft.State:
            message = loft.Status.removeprefix("Error: ")
            doc.removeObject(loft.Name)
            raise ValueError(message)
    loft.Visibility = False
    return loft


def make_tube(sections: Iterable, curves: Iterable = (), doc=None, name: str = "Tube", **sheet_options):
    """A closed Sheet through ``sections`` (two or more objects, each one closed curve: a circle,
    an ellipse, a closed B-spline, or a closed sketch of smoothly joined lines, arcs and splines)
    and ``curves`` between them (as make_sheet takes them). Returns the Sheet; its Base is a Part
    Loft of the sections in their order along the tube (hidden). ``sheet_options`` go to
    make_sheet (tolerance, spans, degree, ...). ValueError, with nothing created, for sections
    that are not closed curves, have corners or cannot be ordered."""
    sections = list(sections)
    ordered = ordered_sections(sections)
    doc = doc or ordered[0].Document
    loft = _base(ordered, doc, name)
    return make_sheet((loft, "Face1"), list(ordered) + list(curves), doc=doc, name=name, **sheet_options)
