# SPDX-License-Identifier: LGPL-2.1-or-later
"""Constraints and energy operators of a sheet as plain data, and their residuals.

A ``ConstraintSpec`` says what a Constraint document object asks of a sheet; ``native_terms``
turns specs into the solver's terms for one spline space, and ``residual`` measures on the solved
surface how well each was met. No document and no GUI here.

Positions on the sheet are given either by a 3D ``location`` (projected onto the base surface to
find its (u, v)) or by normalized parameters ``uv`` in [0, 1]^2; regions are normalized
rectangles (u0, u1, v0, v1), or the area a closed loop of edges encloses (its projection onto the
base).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

from varsurf.solve import continuity, shapes
from varsurf.solve.errors import advised
from varsurf.solve.native import native

#: Kind -> (what it does, unit of its residual).
KINDS: Dict[str, Tuple[str, str]] = {
    "Point": ("the sheet passes through the location (or Origin) at its (u, v)", "mm"),
    "TangentU": ("the derivative along u at (u, v) is Vector", "mm"),
    "TangentV": ("the derivative along v at (u, v) is Vector", "mm"),
    "Normal": ("the normal at (u, v) is parallel to Vector", "deg"),
    "PointInPlane": ("the point at (u, v) lies in the plane (Origin, normal Vector)", "mm"),
    "PointOnLine": ("the point at (u, v) lies on the line (Origin, direction Vector)", "mm"),
    "Curvature": ("the sheet's normal curvatures at (u, v) along u and v are CurvatureU and CurvatureV (1/mm; "
                  "positive: it bends toward the side Vector points to; CurvatureDirections says which are "
                  "asked; not linear: iterated; residual: the largest difference)", "1/mm"),
    "PointAttractor": ("the region is pulled toward Origin with strength Weight", "mm"),
    "PlaneAttractor": ("the region is pulled onto the plane (Origin, normal Vector)", "mm"),
    "LineAttractor": ("the region is pulled onto the line (Origin, direction Vector)", "mm"),
    "Director": ("the region's normals are pushed toward Vector", "deg"),
    "Repeller": ("the region is pushed away from Origin with strength Weight (residual: closest distance)", "mm"),
    "FrozenRegion": ("the sheet over the region keeps the base shape", "mm"),
    "SurfaceAttractor": ("the region is pulled onto Reference (a face) with strength Weight (residual: RMS distance)",
                         "mm"),
    "CurveAttractor": ("the region is pulled onto Curve (an edge) with strength Weight (residual: RMS distance)", "mm"),
    "Ribbon": ("along Curve, the sheet's normal follows Reference (a face's normal, or the strip toward a second "
               "edge; without Reference the base's own normal), turned by Angle", "deg"),
    "G0": ("the sheet contains Curve: position continuity with the face it bounds (residual: max distance)", "mm"),
    "G1": ("the sheet contains Curve and joins Reference there tangent-continuously", "deg"),
    "CurveMap": ("the source curve Curve (on the sheet: its projection onto the base) is mapped onto the "
                 "destination curve Reference (an edge), point for point at the same normalized parameter "
                 "(residual: max distance)", "mm"),
    "RegionMap": ("the sheet over the region (RegionU0..V1) is mapped onto Reference (a face, the destination "
                  "patch), point for point: the region's normalized (u, v) onto the face's parameter rectangle "
                  "(residual: max distance)", "mm"),
    "G2": ("the sheet contains Curve and joins Reference there curvature-continuously (not linear: iterated; "
           "residual: the largest relative jump of the normal curvature across Curve)", "%"),
}
POINT_KINDS = ("Point", "TangentU", "TangentV", "Normal", "PointInPlane", "PointOnLine", "Curvature")
#: Which normal curvatures a Curvature constraint asks for.
CURVATURE_DIRECTIONS = ("U and V", "U", "V")
CURVE_KINDS = ("Ribbon", "G1", "G2")
#: Curve kinds that join a Reference face (the sheet contains the curve).
JOIN_KINDS = ("G1", "G2")
REGION_KINDS = ("PointAttractor", "PlaneAttractor", "LineAttractor", "Director", "Repeller",
                "FrozenRegion", "SurfaceAttractor", "CurveAttractor")
#: Region kinds pulled onto another shape (closest points, iterated).
SHAPE_KINDS = ("SurfaceAttractor", "CurveAttractor")
#: Kinds whose Weight is a condition's importance: 0 would hold nothing (a region kind's weight is
#: its strength, which may be 0).
HELD_KINDS = POINT_KINDS + CURVE_KINDS + ("G0", "CurveMap", "RegionMap")
#: Most points a region's residual is measured on.
REGION_SAMPLES = 400


#: What to do when a curve constraint's curve cannot be placed on the base face.
CURVE_REMEDY = "move its Curve over the base face, or pick the edge again"


class ConstraintError(ValueError):
    """A constraint's own data is unusable; the message starts with its name."""


@dataclass
class ConstraintSpec:
    kind: str
    name: str = "Constraint"
    location: Optional[Tuple[float, float, float]] = None
    uv: Optional[Tuple[float, float]] = None
    vector: Tuple[float, float, float] = (0.0, 0.0, 1.0)
    origin: Optional[Tuple[float, float, float]] = None
    region: Tuple[float, float, float, float] = (0.0, 1.0, 0.0, 1.0)
    weight: float = 1.0
    edge: object = None  # Part.Edge: Ribbon/G1 curve, CurveAttractor target
    reference: object = None  # Part.Face (G1, Ribbon, SurfaceAttractor) or Part.Edge (Ribbon)
    angle: float = 0.0  # degrees, Ribbon
    region_loop: object = None  # Part shape whose edges form one closed loop: the region
    curvature: Tuple[float, float] = (0.0, 0.0)  # 1/mm along u and v, Curvature
    curvature_directions: str = "U and V"  # which of the two, Curvature

    def validate(self):
        fail = lambda why: ConstraintError(f"{self.name}: {why}")  # noqa: E731
        if self.kind not in KINDS:
            raise fail(f"unknown kind {self.kind!r}: give one of {', '.join(KINDS)}")
        if not (math.isfinite(self.weight) and self.weight >= 0.0):
            raise fail(f"weight/strength must be finite and >= 0 (got {self.weight}): set its Weight to 0 or more")
        if self.kind in HELD_KINDS and self.weight == 0.0:
            raise fail("a constraint's weight must be > 0: set its Weight above 0, or disable it")
        if self.kind in POINT_KINDS:
            if self.location is None and self.uv is None:
                raise fail("needs a location (a vertex) or (u, v): link a vertex as its Location")
            if self.uv is not None and not all(0.0 <= t <= 1.0 for t in self.uv):
                raise fail(f"(u, v) must lie in [0, 1] x [0, 1] (got {self.uv}): give a place on the sheet")
        if (self.kind in REGION_KINDS and self.region_loop is None) or self.kind == "RegionMap":
            u0, u1, v0, v1 = self.region
            if not (0.0 <= u0 < u1 <= 1.0 and 0.0 <= v0 < v1 <= 1.0):
                loop = "" if self.kind == "RegionMap" else ", or link a RegionLoop"
                raise fail(f"the region must satisfy 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1 (got {self.region}): set "
                           f"its Region inside the sheet{loop}")
        if self.kind == "SurfaceAttractor":
            if not _is_shape(self.reference, "Face"):
                raise fail("needs a Reference face to pull the region onto: link a face (FaceN) as its Reference")
            return
        if self.kind == "G0":
            if not _is_shape(self.edge, "Edge"):
                raise fail("needs a Curve (an edge) for the sheet to contain: link an edge (EdgeN) as its Curve")
            return
        if self.kind == "RegionMap":
            if not _is_shape(self.reference, "Face"):
                raise fail("needs a Reference face (the destination patch): link a face (FaceN) as its Reference")
            return
        if self.kind == "CurveMap":
            if not (_is_shape(self.edge, "Edge") and self.reference is not None):
                raise fail("needs a Curve (the source, an edge on the sheet) and a Reference (the destination "
                           "edge): link both edges")
            if not _is_shape(self.reference, "Edge"):
                raise fail(f"the destination (Reference) must be an edge (got a {self.reference.ShapeType.lower()}): "
                           "link the destination edge (EdgeN) as its Reference")
            return
        if self.kind == "CurveAttractor":
            if not _is_shape(self.edge, "Edge"):
                raise fail("needs a Curve (an edge) to pull the region onto: link an edge (EdgeN) as its Curve")
            return
        if self.kind in CURVE_KINDS:
            if not _is_shape(self.edge, "Edge"):
                raise fail("needs a Curve (an edge) along which to set the sheet's normal: link an edge (EdgeN) as its "
                           "Curve")
            if self.kind in JOIN_KINDS and not _is_shape(self.reference, "Face"):
                raise fail("needs a Curve (an edge) and a Reference (the face to join): link the neighbouring face "
                           "(FaceN) as its Reference")
            if self.reference is not None and not (_is_shape(self.reference, "Face")
                                                   or _is_shape(self.reference, "Edge")):
                raise fail("Reference must be a face or a second edge: link one (FaceN or EdgeN) as its Reference")
            if not math.isfinite(self.angle):
                raise fail(f"Angle must be finite (got {self.angle}): set its Angle in degrees")
            return
        if self.kind == "Curvature":
            if not all(math.isfinite(k) for k in self.curvature):
                raise fail(f"CurvatureU and CurvatureV must be finite (got {tuple(self.curvature)}): set them in 1/mm "
                           "(1 / the radius of curvature)")
            if self.curvature_directions not in CURVATURE_DIRECTIONS:
                raise fail(f"CurvatureDirections must be one of {', '.join(CURVATURE_DIRECTIONS)} "
                           f"(got {self.curvature_directions!r})")
        needs_vector = self.kind not in ("Point", "PointAttractor", "Repeller", "FrozenRegion")
        vec = self.vector
        if needs_vector and not (all(math.isfinite(c) for c in vec) and math.hypot(*vec) > 0.0):
            raise fail(f"Vector must be a finite non-zero direction (got {tuple(vec)}): set its Vector")
        if self.kind in ("PointInPlane", "PointOnLine", "PointAttractor", "PlaneAttractor", "LineAttractor",
                         "Repeller"):
            if self.origin is None and self.location is None:
                raise fail("needs an Origin (or a location): set UseOrigin and its Origin, or link a vertex as its "
                           "Location")
        if self.kind == "Point" and self.location is None and self.origin is None:
            raise fail("needs a Location vertex to pass through (was it deleted?): link a vertex as its Location, "
                       "or set UseOrigin and its Origin")


def _is_shape(shape, kind: str) -> bool:
    return shape is not None and not shape.isNull() and shape.ShapeType == kind


@dataclass
class PlacedSpec:
    """A spec with its (u, v) in the sheet's own parameters and its region in them."""

    spec: ConstraintSpec
    u: float = 0.0
    v: float = 0.0
    region: Tuple[float, float, float, float] = (0.0, 1.0, 0.0, 1.0)
    start_distance: float = 0.0  # location to base surface, when a location was given
    ribbon: object = None  # native RibbonConstraint of a curve kind
    curve: object = None  # native CurveConstraint of a G1 or G2
    curvature: object = None  # native CurvatureConstraint of a G2
    loop: object = None  # the region's closed loop in the sheet's (u, v), or None
    target: object = None  # native ClosestPointTarget of a shape attractor
    region_map: object = None  # RegionMap: its RegionMapLines (built per space solved)
    side: float = 1.0  # Curvature: +1 where the sheet's normal w_u x w_v points to Vector's side, else -1

    @property
    def origin(self):
        s = self.spec
        return s.origin if s.origin is not None else s.location


def place(specs: Sequence[ConstraintSpec], base, nat) -> List[PlacedSpec]:
    """Validate specs and find their (u, v) on the base surface (a native BSplineSurface)."""
    space = base.space
    uf, ul = space.knots_u[0], space.knots_u[-1]
    vf, vl = space.knots_v[0], space.knots_v[-1]
    placed = []
    for spec in specs:
        spec.validate()
        p = PlacedSpec(spec)
        if spec.kind in POINT_KINDS:
            if spec.location is not None:
                hit = nat.project_point(base, list(spec.location))
                p.u, p.v, p.start_distance = hit.u, hit.v, hit.distance
            else:
                p.u, p.v = uf + spec.uv[0] * (ul - uf), vf + spec.uv[1] * (vl - vf)
        if spec.kind == "Curvature":
            p.side = _side(spec, base, p.u, p.v)
        if spec.kind in CURVE_KINDS:
            _place_curve(p, base, nat)
        if spec.kind in ("G0", "CurveMap"):
            _place_incidence(p, base, nat)
        if spec.kind == "RegionMap":
            p.region_map = RegionMapLines(spec, base, nat)
            p.region_map.lines(space)  # a destination that cannot be taken is said here
        if spec.kind in SHAPE_KINDS:
            target = spec.reference if spec.kind == "SurfaceAttractor" else spec.edge
            try:
                p.target = nat.ClosestPointTarget(target.exportBrepToString())
            except (nat.InvalidInput, nat.GeometryError) as error:
                raise ConstraintError(f"{spec.name}: {error}") from error
        if spec.region_loop is not None:
            p.loop = _place_loop(spec, base, nat)
        u0, u1, v0, v1 = spec.region
        p.region = (uf + u0 * (ul - uf), uf + u1 * (ul - uf), vf + v0 * (vl - vf), vf + v1 * (vl - vf))
        placed.append(p)
    return placed


def _side(spec: ConstraintSpec, base, u: float, v: float) -> float:
    """+1 if the base's normal w_u x w_v at (u, v) points to the side of ``spec.vector``, -1 if away;
    ConstraintError if Vector lies in the tangent plane there (no side is named)."""
    d = base.derivatives(u, v, 1)
    normal = _unit(_cross(list(d[1]), list(d[2])))
    along = _dot(normal, _unit(spec.vector))
    if abs(along) < 1e-3:
        raise ConstraintError(f"{spec.name}: Vector lies in the sheet's tangent plane at the point, so it names no "
                              "side to bend toward: point it to one side of the sheet (e.g. along its normal)")
    return 1.0 if along > 0.0 else -1.0


#: How far (mm) a ribbon's curve may pass from its reference face.
RIBBON_DISTANCE = 1e-3


#: Points per closed region loop (its pre-image is a polygon through their projections).
LOOP_POINTS = 240


def _place_loop(spec: ConstraintSpec, base, nat):
    """The pre-image on the base of a region's closed loop of edges, as (u, v) points."""
    Part = shapes.part()
    fail = lambda why: ConstraintError(f"{spec.name}: {why}")  # noqa: E731
    edges = list(spec.region_loop.Edges)
    if not edges:
        raise fail("the region loop has no edges: link the closed edges around the region as its RegionLoop")
    try:
        wires = [Part.Wire(group) for group in Part.sortEdges(edges)]
    except Exception as error:  # OCC refuses edges that do not chain
        raise fail(f"the region loop's edges do not form a wire ({error}): link edges that join end to end") from error
    if len(wires) != 1 or not wires[0].isClosed():
        raise fail("the region loop must be one closed chain of edges: link edges that close around the region")
    # Per edge, so that corners are kept; each edge is walked in the loop's direction.
    wire = wires[0]
    total = max(wire.Length, 1e-300)
    pieces = [e.discretize(Number=max(2, int(round(LOOP_POINTS * e.Length / total)) + 1))
              for e in wire.OrderedEdges]
    if len(pieces) > 1:
        ends = (pieces[1][0], pieces[1][-1])
        if min(pieces[0][0].distanceToPoint(q) for q in ends) < min(pieces[0][-1].distanceToPoint(q) for q in ends):
            pieces[0].reverse()
    points = list(pieces[0])
    for along in pieces[1:]:
        if along[0].distanceToPoint(points[-1]) > along[-1].distanceToPoint(points[-1]):
            along.reverse()
        points.extend(along[1:])
    points = points[:-1]  # the loop's end is its start
    loop = []
    for q in points:
        hit = nat.project_point(base, [q.x, q.y, q.z])
        loop.append((hit.u, hit.v))
    try:  # a loop that crosses itself once projected, or encloses nothing, is refused here
        nat.region_quadrature(base.space, nat.Region(loop=[list(q) for q in loop]))
    except nat.InvalidInput as error:
        raise fail(f"{error} (projected onto the base): draw the region's loop so that it encloses an area of "
                   "the face without crossing itself") from error
    return loop


def _place_incidence(p: PlacedSpec, base, nat):
    """A G0 join or a curve map: the curve's pre-image on the base and an incidence constraint
    (onto the curve itself, or onto the destination curve at the same normalized parameter)."""
    s = p.spec
    try:
        curve = nat.curve_from_edge_brep(s.edge.exportBrepToString())
        pre = nat.project_curve(base, curve)
        target = curve
        if s.kind == "CurveMap":
            target = mapped_destination(curve, nat.curve_from_edge_brep(s.reference.exportBrepToString()), nat)
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise ConstraintError(advised(f"{s.name}: {error}", CURVE_REMEDY)) from error
    p.curve = nat.CurveConstraint(preimage=pre.curve, target=target, weight=s.weight)


class RegionMapLines:
    """A region map's incidence conditions: lines along u across the region at the Gauss points of
    each knot span in v of the space being solved (as many as a polynomial of its degree needs,
    so a destination the space holds is met exactly), each onto the destination face's iso-curve
    at the mapped v, taken exactly (a B-spline segment of the face's surface); and the region's
    four sides. The lines depend on the space: a sheet placed on its base face is solved on finer
    spans, and lines at the base's Gauss points alone left the surface 0.25 mm off its destination
    between them (measured on a 3-span base refined to 16 spans)."""

    def __init__(self, spec: ConstraintSpec, base, nat):
        space = base.space
        uf, ul = space.knots_u[0], space.knots_u[-1]
        vf, vl = space.knots_v[0], space.knots_v[-1]
        u0, u1, v0, v1 = spec.region
        self.ua, self.ub = uf + u0 * (ul - uf), uf + u1 * (ul - uf)
        self.va, self.vb = vf + v0 * (vl - vf), vf + v1 * (vl - vf)
        self.spec, self.nat = spec, nat
        try:
            face = spec.reference.toNurbs().Faces[0]
            self.surface = face.Surface
            self.a0, self.a1, self.b0, self.b1 = face.ParameterRange
        except Exception as error:  # OCCT's conversion (Part.OCCError: Part is not imported here)
            raise ConstraintError(f"{spec.name}: the destination face cannot be converted to a B-spline ({error}): "
                                  "link another face as its Reference") from error
        self._sides = None
        self._cache = {}

    def _incidence(self, iso, first, last, pre_start, pre_end, weight):
        """The line pre_start -> pre_end of (u, v) onto the iso-curve's segment [first, last]."""
        nat = self.nat
        iso.segment(first, last)
        try:
            target = nat.curve_from_edge_brep(iso.toShape().exportBrepToString())
        except (nat.InvalidInput, nat.GeometryError) as error:
            raise ConstraintError(f"{self.spec.name}: {error}") from error
        line = nat.BSplineCurve(degree=1, knots=[0.0, 0.0, 1.0, 1.0], poles=[list(pre_start), list(pre_end)])
        return nat.CurveConstraint(preimage=line, target=nat.curve_on_range(target, 0.0, 1.0), weight=weight)

    def _across(self, v, weight):
        """The line along u at the sheet's v onto the destination's iso-curve at the mapped v."""
        b = self.b0 + (v - self.va) / (self.vb - self.va) * (self.b1 - self.b0)
        return self._incidence(self.surface.vIso(b), self.a0, self.a1, (self.ua, v), (self.ub, v), weight)

    def lines(self, space) -> list:
        """The native CurveConstraints for a sheet solved on `space`."""
        import numpy

        key = (tuple(space.knots_v), int(space.degree_v))
        if key in self._cache:
            return self._cache[key]
        va, vb, weight = self.va, self.vb, self.spec.weight
        breaks = sorted({va, vb} | {float(k) for k in space.knots_v if va < k < vb})
        nodes, rule = numpy.polynomial.legendre.leggauss(space.degree_v + 1)
        out = []
        for lo, hi in zip(breaks, breaks[1:]):
            for x, w in zip(nodes, rule):
                out.append(self._across(0.5 * (lo + hi) + 0.5 * (hi - lo) * float(x),
                                        weight * 0.5 * (hi - lo) * float(w) / (vb - va)))
        # The region's four sides too: the Gauss lines leave its border (and corners) to the energy.
        # Each weighs like a Gauss line of a region four spans deep, whatever the spans solved:
        # shares of the lines' count let finer spans loosen the corners (at 1e-4 mm, 16 spans:
        # 1.75 -> 2.5 x Tolerance there).
        side = weight / (4 * (space.degree_v + 1))
        a0, a1, b0, b1, ua, ub = self.a0, self.a1, self.b0, self.b1, self.ua, self.ub
        surface = self.surface
        out += [self._incidence(surface.vIso(b0), a0, a1, (ua, va), (ub, va), side),
                self._incidence(surface.vIso(b1), a0, a1, (ua, vb), (ub, vb), side),
                self._incidence(surface.uIso(a0), b0, b1, (ua, va), (ua, vb), side),
                self._incidence(surface.uIso(a1), b0, b1, (ub, va), (ub, vb), side)]
        self._cache = {key: out}  # one space at a time: the refinement moves on to finer ones
        return out

    def check_lines(self, space) -> list:
        """Lines where the map is measured: the solved ones and, between them, the span ends and
        the midpoints of neighbouring Gauss lines (where a surface that meets its lines can still
        stray)."""
        solved = self.lines(space)
        vs = sorted(float(c.preimage.evaluate(0.0)[1]) for c in solved[:-4])
        between = [0.5 * (a + b) for a, b in zip(vs, vs[1:])]
        return solved + [self._across(v, 1.0) for v in between]


def mapped_destination(source, destination, nat):
    """The destination curve on the source's parameter range, exactly (its knots mapped affinely),
    turned so that it starts at the end nearer the source's start: the point of the destination
    at the source's normalized parameter."""
    t0, t1 = source.first(), source.last()
    turned = nat.oriented_curve(destination, source.evaluate(t0), source.evaluate(t1))
    return nat.curve_on_range(turned, t0, t1)


def _place_curve(p: PlacedSpec, base, nat):
    """The ribbon of a curve kind: the curve's pre-image on the base and the normals it follows:
    a reference face's, the strip toward a second edge, or (no reference) the base's own."""
    s = p.spec
    try:
        curve = nat.curve_from_edge_brep(s.edge.exportBrepToString())
        pre = nat.project_curve(base, curve)
        if s.reference is None:
            normals = nat.normal_field_brep(nat.face_brep(base), curve, angle_deg=float(s.angle),
                                            max_distance=math.inf)
        elif s.reference.ShapeType == "Edge":
            second = nat.curve_from_edge_brep(s.reference.exportBrepToString())
            normals = nat.normal_field_between(curve, second, angle_deg=float(s.angle))
        else:
            normals = nat.normal_field_brep(s.reference.exportBrepToString(), curve,
                                            angle_deg=float(s.angle), max_distance=RIBBON_DISTANCE)
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise ConstraintError(advised(f"{s.name}: {error}", CURVE_REMEDY)) from error
    p.ribbon = nat.RibbonConstraint(preimage=pre.curve, normals=normals, weight=s.weight)
    if s.kind in JOIN_KINDS:
        p.curve = nat.CurveConstraint(preimage=pre.curve, target=curve, weight=1.0)
    if s.kind == "G2":
        normals, shape = curvature_fields(curve, s.reference, nat)
        p.curvature = nat.CurvatureConstraint(preimage=pre.curve, normals=normals, shape=shape, weight=s.weight)


#: Points along a G2 curve where the neighbour's normal and curvature are taken (the fields
#: between them are linear: the neighbour's curvature varies slowly along an edge).
CURVATURE_SAMPLES = 201


def curvature_fields(curve, face, nat, seeded: bool = True):
    """The neighbour ``face``'s unit normal and second fundamental form along ``curve`` (a native
    3D BSplineCurve on its boundary), as piecewise-linear native fields over the curve's range.
    With ``seeded`` the feet on the face are found from each other's (continuity.parameters_along:
    OCCT's global projection of all 201 points took 0.3 s of a five-sided G2 fill)."""
    t0, t1 = curve.first(), curve.last()
    ts = [t0 + (t1 - t0) * i / (CURVATURE_SAMPLES - 1) for i in range(CURVATURE_SAMPLES)]
    surface = face.Surface
    box = face.BoundBox
    Vector = type(box.Center)
    points = [Vector(*[float(x) for x in curve.evaluate(t)]) for t in ts]
    reach = continuity.SEEDED_REACH * box.DiagonalLength if seeded else 0.0
    normals, shapes_ = [], []
    for u, v in continuity.parameters_along(surface, points, reach):
        n, k = continuity.shape_operator(surface, u, v)
        normals.append([n.x, n.y, n.z])
        shapes_.append(list(k))
    knots = [t0] + ts + [t1]
    return (nat.BSplineCurve(degree=1, knots=knots, poles=normals),
            nat.BSplineCurve(degree=1, knots=knots, poles=shapes_))


@dataclass
class NativeTerms:
    points: list = field(default_factory=list)
    tangents: list = field(default_factory=list)
    normals: list = field(default_factory=list)
    plane_points: list = field(default_factory=list)
    line_points: list = field(default_factory=list)
    attractors: list = field(default_factory=list)
    directors: list = field(default_factory=list)
    repellers: list = field(default_factory=list)
    ribbons: list = field(default_factory=list)
    shape_attractors: list = field(default_factory=list)
    curves: list = field(default_factory=list)
    curvatures: list = field(default_factory=list)
    point_curvatures: list = field(default_factory=list)
    frozen_poles: list = field(default_factory=list)

    def apply(self, problem):
        for name in ("points", "tangents", "normals", "plane_points", "line_points", "attractors", "directors",
                     "repellers", "ribbons", "curves", "shape_attractors", "curvatures",
                     "point_curvatures"):
            setattr(problem, name, list(getattr(problem, name)) + getattr(self, name))


def native_terms(placed: Sequence[PlacedSpec], space, nat) -> NativeTerms:
    """The solver's terms for the specs on one spline space (frozen poles depend on the space)."""
    out = NativeTerms()
    for p in placed:
        s, kind = p.spec, p.spec.kind
        vec = list(s.vector)
        region = _native_region(p, nat)
        if kind == "Point":
            out.points.append(nat.PointConstraint(u=p.u, v=p.v, target=list(p.origin), weight=s.weight))
        elif kind in ("TangentU", "TangentV"):
            out.tangents.append(nat.TangentConstraint(u=p.u, v=p.v, direction=0 if kind == "TangentU" else 1,
                                                      target=vec, weight=s.weight))
        elif kind == "Normal":
            out.normals.append(nat.NormalConstraint(u=p.u, v=p.v, normal=vec, weight=s.weight))
        elif kind == "PointInPlane":
            out.plane_points.append(nat.PlanePointConstraint(u=p.u, v=p.v, origin=list(p.origin), normal=vec,
                                                             weight=s.weight))
        elif kind == "PointOnLine":
            out.line_points.append(nat.LinePointConstraint(u=p.u, v=p.v, origin=list(p.origin), direction=vec,
                                                           weight=s.weight))
        elif kind in ("PointAttractor", "PlaneAttractor", "LineAttractor"):
            attractor_kind = {"PointAttractor": nat.AttractorKind.point, "PlaneAttractor": nat.AttractorKind.plane,
                              "LineAttractor": nat.AttractorKind.line}[kind]
            out.attractors.append(nat.Attractor(kind=attractor_kind, region=region, origin=list(p.origin),
                                                direction=vec, strength=s.weight))
        elif kind == "Curvature":
            ku, kv = (p.side * k for k in s.curvature)
            out.point_curvatures.append(nat.PointCurvatureConstraint(
                u=p.u, v=p.v, kappa_u=ku, kappa_v=kv, along_u=s.curvature_directions != "V",
                along_v=s.curvature_directions != "U", weight=s.weight))
        elif kind == "Director":
            out.directors.append(nat.Director(region=region, direction=vec, strength=s.weight))
        elif kind in CURVE_KINDS:
            out.ribbons.append(p.ribbon)
            if p.curve is not None:
                out.curves.append(p.curve)
            if p.curvature is not None:
                out.curvatures.append(p.curvature)
        elif kind in ("G0", "CurveMap"):
            out.curves.append(p.curve)
        elif kind == "RegionMap":
            out.curves.extend(p.region_map.lines(space))
        elif kind in SHAPE_KINDS:
            out.shape_attractors.append(nat.ShapeAttractor(region=region, target=p.target, strength=s.weight))
        elif kind == "Repeller":
            out.repellers.append(nat.Repeller(region=region, origin=list(p.origin), strength=s.weight))
        elif kind == "FrozenRegion":
            out.frozen_poles.extend(int(k) for k in nat.poles_in_region(space, region))
    return out


def _native_region(p: PlacedSpec, nat):
    if p.loop is not None:
        return nat.Region(loop=[list(q) for q in p.loop])
    return nat.Region(u0=p.region[0], u1=p.region[1], v0=p.region[2], v1=p.region[3])


def _region_samples(p: PlacedSpec, surface):
    """(u, v, weight) on which a region kind's residual is measured: the region's quadrature
    points (at most REGION_SAMPLES of them, evenly picked) with their weights normalized."""
    nat = native()
    points = nat.region_quadrature(surface.space, _native_region(p, nat))
    points = points[:: max(1, len(points) // REGION_SAMPLES)]
    total = sum(q.weight for q in points)
    return [(q.u, q.v, q.weight / total) for q in points]


def _unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _sub(a, b):
    return [x - y for x, y in zip(a, b)]


def _norm(a):
    return math.sqrt(_dot(a, a))


def _angle_deg(normal, direction):
    """Unsigned angle between a surface normal and a direction (a normal has no preferred side)."""
    c = abs(_dot(_unit(normal), _unit(direction)))
    return math.degrees(math.acos(min(1.0, c)))


def residual(p: PlacedSpec, surface, base) -> float:
    """How far the solved ``surface`` is from what the spec asks, in KINDS' unit."""
    s, kind = p.spec, p.spec.kind
    if kind == "G0":
        return native().max_deviation(surface, p.curve.target)
    if kind == "CurveMap":  # through the pre-image: the same parameter, not the nearest point
        return native().incidence_error(surface.space, surface.poles, p.curve, 200)
    if kind == "RegionMap":
        return max(native().incidence_error(surface.space, surface.poles, c, 50)
                   for c in p.region_map.check_lines(surface.space))
    if kind == "G2":
        return 100.0 * native().curvature_jump(surface.space, surface.poles, p.curvature,
                                               1.0 / max(p.spec.reference.BoundBox.DiagonalLength, 1e-300))
    if kind in CURVE_KINDS:
        return math.degrees(native().ribbon_angle_error(surface.space, surface.poles, p.ribbon))
    if kind == "Curvature":
        ku, kv = (p.side * float(k) for k in native().normal_curvatures(surface.space, surface.poles, p.u, p.v))
        asked = [(ku, s.curvature[0])] if s.curvature_directions == "U" else \
            [(kv, s.curvature[1])] if s.curvature_directions == "V" else [(ku, s.curvature[0]), (kv, s.curvature[1])]
        return max(abs(k - target) for k, target in asked)
    if kind in POINT_KINDS:
        d = surface.derivatives(p.u, p.v, 1)
        w, wu, wv = list(d[0]), list(d[1]), list(d[2])
        if kind == "Point":
            return _norm(_sub(w, p.origin))
        if kind == "TangentU":
            return _norm(_sub(wu, s.vector))
        if kind == "TangentV":
            return _norm(_sub(wv, s.vector))
        if kind == "Normal":
            return _angle_deg(_cross(wu, wv), s.vector)
        if kind == "PointInPlane":
            return abs(_dot(_unit(s.vector), _sub(w, p.origin)))
        if kind == "PointOnLine":
            return _norm(_cross(_sub(w, p.origin), _unit(s.vector)))
    # Region kinds: RMS over the region (max for a frozen region, min for a repeller).
    values, weights = [], []
    for u, v, weight in _region_samples(p, surface):
        weights.append(weight)
        d = surface.derivatives(u, v, 1)
        w = list(d[0])
        if kind in ("PointAttractor", "Repeller"):
            values.append(_norm(_sub(w, p.origin)))
        elif kind == "PlaneAttractor":
            values.append(abs(_dot(_unit(s.vector), _sub(w, p.origin))))
        elif kind == "LineAttractor":
            values.append(_norm(_cross(_sub(w, p.origin), _unit(s.vector))))
        elif kind == "Director":
            values.append(_angle_deg(_cross(list(d[1]), list(d[2])), s.vector))
        elif kind == "FrozenRegion":
            values.append(_norm(_sub(w, list(base.evaluate(u, v)))))
        elif kind in SHAPE_KINDS:
            values.append(_norm(_sub(w, list(p.target.closest(w)))))
    if kind == "FrozenRegion":
        return max(values)
    if kind == "Repeller":  # how close the region comes: the smallest distance
        return min(values)
    return math.sqrt(sum(w * x * x for w, x in zip(weights, values)))
