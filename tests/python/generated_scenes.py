# SPDX-License-Identifier: LGPL-2.1-or-later
"""Generated base faces and curves lying on them, for the invariant tests.

Every face is built the way a FreeCAD user gets one: Part primitives' faces (full and partial),
the faces of a filleted box, random B-spline faces (degrees 2 to 5, non-uniform knots, rational
weights) and the faces of solids written to STEP and read back. Each generator is seeded from the
face's name, so every run builds the same geometry.

Curves on a face are exact: the face's own edges and pieces of them, iso lines of its surface,
and the images of parameter lines of its exact NURBS form (rational curves of degree p + q).
"""

from __future__ import annotations

import functools
import math
import os
import shutil
import tempfile
import zlib

import numpy as np

import FreeCAD
import Part

V = FreeCAD.Vector


def rng(name: str) -> np.random.RandomState:
    """A generator seeded from a stable hash of ``name``."""
    return np.random.RandomState(zlib.crc32(name.encode()) & 0x7FFFFFFF)


def _direction(r: np.random.RandomState) -> FreeCAD.Vector:
    d = r.normal(size=3)
    return V(*(d / np.linalg.norm(d)))


def _point(r: np.random.RandomState, spread: float = 100.0) -> FreeCAD.Vector:
    return V(*r.uniform(-spread, spread, size=3))


def size_of(shape) -> float:
    """The scene's size: its bounding box diagonal (mm)."""
    return shape.BoundBox.DiagonalLength


# --------------------------------------------------------------------------------------------
# faces


def _plane(name):
    r = rng(name)
    return Part.makePlane(r.uniform(20, 150), r.uniform(20, 150), _point(r), _direction(r)).Faces[0]


def _box_face(index):
    def make(name):
        r = rng(name)
        box = Part.makeBox(60.0, 40.0, 30.0, _point(r), _direction(r))
        return box.Faces[index]

    return make


def _cylinder(angle):
    def make(name):
        r = rng(name)
        return Part.makeCylinder(r.uniform(5, 40), r.uniform(10, 80), _point(r), _direction(r), angle).Faces[0]

    return make


def _cone(apex: bool, angle):
    def make(name):
        r = rng(name)
        r1 = r.uniform(10, 40)
        r2 = 0.0 if apex else r.uniform(3, 0.8 * r1)
        return Part.makeCone(r1, r2, r.uniform(10, 60), _point(r), _direction(r), angle).Faces[0]

    return make


def _sphere(lat0, lat1, angle):
    def make(name):
        r = rng(name)
        return Part.makeSphere(r.uniform(5, 50), _point(r), _direction(r), lat0, lat1, angle).Faces[0]

    return make


def _torus(minor0, minor1, angle):
    def make(name):
        r = rng(name)
        major = r.uniform(20, 60)
        return Part.makeTorus(major, r.uniform(3, 0.4 * major), _point(r), _direction(r), minor0, minor1,
                              angle).Faces[0]

    return make


def _filleted_box(kind):
    """A 60 x 40 x 30 box with a fillet; ``kind`` picks the face."""
    box = Part.makeBox(60.0, 40.0, 30.0)
    corner = [e for e in box.Edges if any(v.Point.Length < 1e-9 for v in e.Vertexes)]
    if kind == "edge":  # one straight edge: a cylindrical fillet
        solid = box.makeFillet(5.0, [box.Edges[0]])
        return [f for f in solid.Faces if isinstance(f.Surface, Part.Cylinder)][0]
    if kind == "corner":  # three edges meeting: the spherical corner patch
        solid = box.makeFillet(5.0, corner)
        return [f for f in solid.Faces if isinstance(f.Surface, Part.Sphere)][0]
    if kind == "variable":  # radius 3 to 8 along the edge: a B-spline blend
        solid = box.makeFillet(3.0, 8.0, [box.Edges[0]])
        return [f for f in solid.Faces if isinstance(f.Surface, Part.BSplineSurface)][0]
    if kind == "flat-cut":  # the flat face whose corner the corner fillet rounds off (a trimmed plane)
        solid = box.makeFillet(5.0, corner)
        flats = [f for f in solid.Faces if isinstance(f.Surface, Part.Plane)]
        return max(flats, key=lambda f: len(f.Edges))
    raise KeyError(kind)


def _fillet(kind):
    def make(name):
        r = rng(name)
        face = _filleted_box(kind).copy()
        motion = FreeCAD.Placement(_point(r), FreeCAD.Rotation(_direction(r), r.uniform(0, 360)))
        face.transformShape(motion.toMatrix(), True)
        return face

    return make


def _knots(r: np.random.RandomState, degree: int, spans: int):
    """Non-uniform knots over a random interval (interior knots at least 0.08 apart), clamped;
    one interior knot doubled when the degree keeps the face at least C1 there."""
    while True:
        inner = np.sort(r.uniform(0.0, 1.0, size=spans - 1))
        gaps = np.diff(np.concatenate(([0.0], inner, [1.0])))
        if gaps.min() >= 0.08:
            break
    start, length = r.uniform(-3.0, 3.0), r.uniform(0.5, 20.0)
    knots = [start + length * k for k in np.concatenate(([0.0], inner, [1.0]))]
    mults = [degree + 1] + [1] * (spans - 1) + [degree + 1]
    if spans > 1 and degree >= 3:
        mults[1 + r.randint(spans - 1)] = 2
    return knots, mults


def random_bspline_surface(name: str, degree_u: int, degree_v: int) -> Part.BSplineSurface:
    """A rational B-spline patch of about 100 mm: a wavy height field over a jittered grid, placed
    and turned at random; weights in 0.5..2."""
    r = rng(name)
    spans_u, spans_v = r.randint(2, 5), r.randint(2, 5)
    knots_u, mults_u = _knots(r, degree_u, spans_u)
    knots_v, mults_v = _knots(r, degree_v, spans_v)
    nu = sum(mults_u) - degree_u - 1
    nv = sum(mults_v) - degree_v - 1
    width, depth = r.uniform(60, 120), r.uniform(60, 120)
    grid_x = np.linspace(0.0, width, nu)
    grid_y = np.linspace(0.0, depth, nv)
    jitter = 0.15 * min(width / nu, depth / nv)
    heights = r.uniform(-0.12, 0.12, size=(nu, nv)) * max(width, depth)
    rotation = FreeCAD.Rotation(_direction(r), r.uniform(0, 360))
    origin = _point(r)
    poles = []
    for i in range(nu):
        row = []
        for j in range(nv):
            x = grid_x[i] + (r.uniform(-jitter, jitter) if 0 < i < nu - 1 else 0.0)
            y = grid_y[j] + (r.uniform(-jitter, jitter) if 0 < j < nv - 1 else 0.0)
            row.append(origin + rotation.multVec(V(x, y, heights[i, j])))
        poles.append(row)
    weights = r.uniform(0.5, 2.0, size=(nu, nv)).tolist()
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults_u, mults_v, knots_u, knots_v, False, False, degree_u,
                                     degree_v, weights)
    return surface


def _bspline(degree_u, degree_v):
    def make(name):
        return Part.Face(random_bspline_surface(name, degree_u, degree_v))

    return make


def _step_round_trip(solid):
    """``solid`` written to a STEP file and read back (a Part solid as another CAD system gets it)."""
    folder = tempfile.mkdtemp(prefix="varsurf-invariants-")
    try:
        path = os.path.join(folder, "solid.step")
        solid.exportStep(path)
        shape = Part.Shape()
        shape.read(path)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return shape


@functools.lru_cache(maxsize=None)
def _step_solid(which):
    if which == "fillet":
        box = Part.makeBox(60.0, 40.0, 30.0)
        corner = [e for e in box.Edges if any(v.Point.Length < 1e-9 for v in e.Vertexes)]
        return _step_round_trip(box.makeFillet(5.0, corner))
    if which == "bspline":  # a random rational B-spline face extruded 20 mm into a solid
        surface = random_bspline_surface("step-bspline", 3, 3)
        (u0, u1, v0, v1) = surface.bounds()
        corner = surface.value(u0, v0)
        across = (surface.value(u1, v0) - corner).cross(surface.value(u0, v1) - corner)
        return _step_round_trip(Part.Face(surface).extrude(across.normalize() * 20.0))
    if which == "cylinder":
        return _step_round_trip(Part.makeCylinder(20.0, 50.0, V(10, -5, 3), V(1, 1, 2)))
    raise KeyError(which)


def _step(which, pick):
    def make(name):
        return pick(_step_solid(which).Faces)

    return make


def _surface_is_all(kind):
    return lambda faces: [f for f in faces if isinstance(f.Surface, kind)]


def _surface_is(kind):
    return lambda faces: _surface_is_all(kind)(faces)[0]


#: Base faces by name: family-variant. The family is the first word.
FACES = {
    "plane-a": _plane,
    "plane-b": _plane,
    "plane-c": _plane,
    "box-face1": _box_face(0),  # Face1..Face5 of a box include reversed faces
    "box-face4": _box_face(3),
    "box-face6": _box_face(5),
    "cylinder-full-a": _cylinder(360.0),
    "cylinder-full-b": _cylinder(360.0),
    "cylinder-partial-a": _cylinder(120.0),
    "cylinder-partial-b": _cylinder(250.0),
    "cone-full": _cone(False, 360.0),
    "cone-partial": _cone(False, 150.0),
    "cone-apex": _cone(True, 90.0),
    "sphere-full": _sphere(-90.0, 90.0, 360.0),
    "sphere-band": _sphere(-40.0, 55.0, 360.0),
    "sphere-patch": _sphere(-30.0, 50.0, 200.0),
    "torus-full": _torus(-180.0, 180.0, 360.0),
    "torus-ring": _torus(-180.0, 180.0, 140.0),
    "torus-patch": _torus(10.0, 160.0, 90.0),
    "fillet-edge": _fillet("edge"),
    "fillet-corner": _fillet("corner"),
    "fillet-variable": _fillet("variable"),
    "fillet-flatcut": _fillet("flat-cut"),
    "bspline-2x2": _bspline(2, 2),
    "bspline-3x2": _bspline(3, 2),
    "bspline-3x3": _bspline(3, 3),
    "bspline-4x3": _bspline(4, 3),
    "bspline-2x5": _bspline(2, 5),
    "bspline-4x4": _bspline(4, 4),
    "bspline-5x4": _bspline(5, 4),
    "bspline-5x5": _bspline(5, 5),
    "step-plane": _step("fillet", lambda faces: max([f for f in faces if isinstance(f.Surface, Part.Plane)],
                                                    key=lambda f: f.Area)),
    "step-fillet": _step("fillet", _surface_is(Part.Cylinder)),
    "step-corner": _step("fillet", _surface_is(Part.Sphere)),
    "step-bspline": _step("bspline", lambda faces: max(_surface_is_all(Part.BSplineSurface)(faces),
                                                       key=lambda f: f.Area)),
    "step-cylinder": _step("cylinder", _surface_is(Part.Cylinder)),
}


@functools.lru_cache(maxsize=None)
def face(name: str):
    """The generated face ``name`` (cached: callers must not modify it)."""
    return FACES[name](name)


def family(name: str) -> str:
    return name.split("-")[0]


# --------------------------------------------------------------------------------------------
# curves on a face


def boundary_edges(face):
    """The face's own edges a user can pick (degenerate edges at poles and apexes have no curve)."""
    return [e for e in face.Edges if not e.Degenerated]


def _inside(face, u, v) -> bool:
    return bool(face.isPartOfDomain(u, v))


def _uv_of(face, s, t):
    u0, u1, v0, v1 = face.ParameterRange
    return u0 + (u1 - u0) * s, v0 + (v1 - v0) * t


@functools.lru_cache(maxsize=None)
def is_rectangular(face_name: str, samples: int = 24) -> bool:
    """Whether the face covers its whole parameter rectangle (no trim inside it)."""
    f = face(face_name)
    grid = np.linspace(1e-4, 1.0 - 1e-4, samples)
    return all(_inside(f, *_uv_of(f, s, t)) for s in grid for t in grid)


def _inside_run(face, values, point_at):
    """(first, last) of the longest run of ``values`` whose points are inside the face."""
    best, start = (None, None), None
    flags = [_inside(face, *point_at(x)) for x in values] + [False]
    for k, flag in enumerate(flags):
        if flag and start is None:
            start = k
        if not flag and start is not None:
            if best[0] is None or k - 1 - start > best[1] - best[0]:
                best = (start, k - 1)
            start = None
    if best[0] is None:
        raise ValueError("no part of the iso line lies on the face")
    return values[best[0]], values[best[1]]


def iso_edge(face_name: str, direction: str, fraction: float):
    """The iso line of the face's surface at ``fraction`` of the u (direction "u": a curve along
    v) or v range, trimmed to the face (exact: the surface's own iso curve)."""
    f = face(face_name)
    u0, u1, v0, v1 = f.ParameterRange
    if direction == "u":
        u = u0 + (u1 - u0) * fraction
        curve = f.Surface.uIso(u)
        lo, hi = v0, v1
        at = lambda x: (u, x)  # noqa: E731
    else:
        v = v0 + (v1 - v0) * fraction
        curve = f.Surface.vIso(v)
        lo, hi = u0, u1
        at = lambda x: (x, v)  # noqa: E731
    if not is_rectangular(face_name):
        lo, hi = _inside_run(f, list(np.linspace(lo, hi, 201)), at)
    return Part.Edge(curve, lo, hi)


def edge_piece(edge, a: float, b: float):
    """The part of ``edge`` between fractions a and b of its parameter range (its own curve)."""
    first, last = edge.ParameterRange
    return Part.Edge(edge.Curve, first + (last - first) * a, first + (last - first) * b)


@functools.lru_cache(maxsize=None)
def _nurbs(face_name: str):
    """The face as OCCT's exact NURBS conversion (BRepBuilderAPI_NurbsConvert): the same points,
    a rational polynomial parametrization to compose curves with."""
    return face(face_name).toNurbs().Faces[0]


def _weight_surface(surface):
    """A non-rational copy of ``surface`` whose x is its weight function w(u, v)."""
    weights = surface.getWeights()
    w = surface.copy()
    for i, row in enumerate(weights):
        for j, weight in enumerate(row):
            w.setPole(i + 1, j + 1, V(weight, 0.0, 0.0), 1.0)
    return w


def _bernstein(degree: int, t: float):
    return [math.comb(degree, k) * t ** k * (1.0 - t) ** (degree - k) for k in range(degree + 1)]


def curve_on_surface(surface, uv_points):
    """The exact image of the parameter polyline ``uv_points`` on the B-spline ``surface``.

    Along a straight parameter segment that stays within one knot span, the homogeneous point
    (w S, w) is a polynomial of degree p + q; each such piece is found from p + q + 1 values
    (Chebyshev points) as a rational Bezier, and the pieces are joined into one rational
    B-spline (C0 at the joints). The result lies on the surface to rounding."""
    degree = surface.UDegree + surface.VDegree
    rational = surface.isURational() or surface.isVRational()
    weight = _weight_surface(surface) if rational else None
    u_knots, v_knots = surface.getUKnots(), surface.getVKnots()
    nodes = [0.5 - 0.5 * math.cos(math.pi * (k + 0.5) / (degree + 1)) for k in range(degree + 1)]
    matrix = np.array([_bernstein(degree, t) for t in nodes])
    pieces = []
    for (ua, va), (ub, vb) in zip(uv_points[:-1], uv_points[1:]):
        cuts = {0.0, 1.0}
        for knots, a, b in ((u_knots, ua, ub), (v_knots, va, vb)):
            if abs(b - a) > 0.0:
                cuts.update((k - a) / (b - a) for k in knots if 0.0 < (k - a) / (b - a) < 1.0)
        cuts = sorted(cuts)
        for t0, t1 in zip(cuts[:-1], cuts[1:]):
            values = []
            for t in nodes:
                s = t0 + (t1 - t0) * t
                u, v = ua + (ub - ua) * s, va + (vb - va) * s
                w = weight.value(u, v).x if rational else 1.0
                p = surface.value(u, v)
                values.append((w * p.x, w * p.y, w * p.z, w))
            pieces.append(np.linalg.solve(matrix, np.array(values)))
    poles, weights = [], []
    for k, piece in enumerate(pieces):
        for row in piece[(1 if k else 0):]:
            if not row[3] > 0.0:
                raise ValueError("the composed curve has a non-positive weight")
            poles.append(V(*(row[:3] / row[3])))
            weights.append(float(row[3]))
    knots = list(range(len(pieces) + 1))
    mults = [degree + 1] + [degree] * (len(pieces) - 1) + [degree + 1]
    curve = Part.BSplineCurve()
    curve.buildFromPolesMultsKnots(poles, mults, knots, False, degree, weights)
    return curve.toShape()


def _normalized_inside(nurbs, s, t) -> bool:
    return _inside(nurbs, *_uv_of(nurbs, s, t))


def _segment_inside(nurbs, a, b, samples: int = 41) -> bool:
    return all(_normalized_inside(nurbs, a[0] + (b[0] - a[0]) * x, a[1] + (b[1] - a[1]) * x)
               for x in np.linspace(0.0, 1.0, samples))


@functools.lru_cache(maxsize=None)
def free_curve(face_name: str):
    """A curve across the face that follows no iso line nor edge: a slanted straight line in the
    parameters of the face's exact NURBS form, mapped through its surface."""
    nurbs = _nurbs(face_name)
    r = rng(face_name + ":free")
    for _ in range(200):
        a, b = r.uniform(0.1, 0.9, size=2), r.uniform(0.1, 0.9, size=2)
        if min(abs(b - a)) > 0.25 and _segment_inside(nurbs, a, b):
            return curve_on_surface(nurbs.Surface, [_uv_of(nurbs, *a), _uv_of(nurbs, *b)])
    raise ValueError(f"no slanted line fits inside {face_name}")


@functools.lru_cache(maxsize=None)
def along_boundary_curve(face_name: str):
    """One curve that runs along part of a boundary edge, then turns into the face: a parameter
    polyline of the face's exact NURBS form (along an edge that is straight in the parameters,
    then inward), mapped through its surface."""
    nurbs = _nurbs(face_name)
    r = rng(face_name + ":along")
    u0, u1, v0, v1 = nurbs.ParameterRange
    for edge in sorted(boundary_edges(nurbs), key=lambda e: -e.Length):
        pcurve, first, last = nurbs.curveOnSurface(edge)
        a = first + (last - first) * r.uniform(0.1, 0.3)
        b = first + (last - first) * r.uniform(0.55, 0.75)
        ends = [pcurve.value(a), pcurve.value((a + b) / 2), pcurve.value(b)]
        st = [((p.x - u0) / (u1 - u0), (p.y - v0) / (v1 - v0)) for p in ends]
        direction = np.subtract(st[2], st[0])
        if np.linalg.norm(np.subtract(st[1], np.add(st[0], st[2]) / 2)) > 1e-9 * np.linalg.norm(direction):
            continue  # not straight in the parameters
        inward = np.array([-direction[1], direction[0]]) / np.linalg.norm(direction)
        for side in (1.0, -1.0):
            for reach in (0.4, 0.25, 0.15):
                turn = np.add(st[2], side * reach * inward + 0.3 * reach * direction / np.linalg.norm(direction))
                if _segment_inside(nurbs, np.add(st[2], 0.02 * side * inward), turn):
                    uv = [_uv_of(nurbs, *st[0]), _uv_of(nurbs, *st[2]), _uv_of(nurbs, *turn)]
                    return curve_on_surface(nurbs.Surface, uv)
    raise ValueError(f"no boundary edge of {face_name} is straight in the parameters with room to turn in")


#: Sets of curves lying on a face, by name.
CURVE_SETS = ("none", "boundary", "edge", "edge-piece", "u-iso", "iso-grid", "free", "along", "mixed")


def curves_on(face_name: str, kind: str):
    """The curve set ``kind`` of CURVE_SETS on the face ``face_name``, as Part edges (shared
    between calls: copy an edge before changing it)."""
    f = face(face_name)
    edges = boundary_edges(f)
    r = rng(face_name + ":" + kind)
    if kind == "none":
        return []
    if kind == "boundary":
        return edges
    if kind == "edge":
        return [max(edges, key=lambda e: e.Length)]
    if kind == "edge-piece":
        return [edge_piece(max(edges, key=lambda e: e.Length), r.uniform(0.1, 0.3), r.uniform(0.6, 0.9))]
    if kind == "u-iso":
        return [iso_edge(face_name, "u", r.uniform(0.3, 0.7))]
    if kind == "iso-grid":
        return [iso_edge(face_name, "u", x) for x in (0.3, 0.65)] + [iso_edge(face_name, "v", x) for x in (0.35, 0.7)]
    if kind == "free":
        return [free_curve(face_name)]
    if kind == "along":
        return [along_boundary_curve(face_name)]
    if kind == "mixed":
        return edges + [iso_edge(face_name, "v", 0.5), free_curve(face_name)]
    raise KeyError(kind)


def lifted_curves(face_name: str, lift: float = 0.01):
    """Curves off the face, so the sheet must move: pieces of the u and v iso lines through the
    middle of the face and a slanted curve on it, all moved by ``lift`` x the face's size along its
    normal at the middle (the iso pieces still cross there). Farther off a wavy face (3 % on
    bspline-3x3) the orthogonal projection nears the face's focal points and is ill-posed."""
    f = face(face_name)
    size = size_of(f)
    u0, u1, v0, v1 = f.ParameterRange
    normal = f.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
    shift = FreeCAD.Matrix()
    shift.move(normal * (lift * size))
    curves = [edge_piece(iso_edge(face_name, "u", 0.5), 0.25, 0.75),
              edge_piece(iso_edge(face_name, "v", 0.5), 0.2, 0.8),
              edge_piece(free_curve(face_name), 0.15, 0.85)]
    for edge in curves:
        edge.transformShape(shift, True)
    return curves


def moved(shape, matrix):
    """A copy of ``shape`` whose geometry is moved by ``matrix`` (rigid or a uniform scale)."""
    copy = shape.copy()
    copy.transformShape(matrix, True)
    return copy


def located(shape, placement):
    """A copy of ``shape`` moved by ``placement`` through its Location (the geometry untouched),
    as FreeCAD moves an object's shape by its Placement."""
    copy = shape.copy()
    copy.Placement = placement.multiply(copy.Placement)
    return copy


def random_motion(name: str, size: float) -> FreeCAD.Placement:
    """A seeded rigid motion: a turn about a random axis and a shift of up to 10 x ``size``."""
    r = rng(name + ":motion")
    return FreeCAD.Placement(V(*r.uniform(-10.0 * size, 10.0 * size, size=3)),
                             FreeCAD.Rotation(_direction(r), r.uniform(20.0, 340.0)))


# --------------------------------------------------------------------------------------------
# measurement


#: Sample grids stay this fraction of the parameter range inside it: on the boundary itself, a
#: face's trim (its edges, built to OCCT's 1e-7 mm confusion) decides whether a point is in.
INSET = 1e-6


def sample_points(face, n: int = 9):
    """(point, (u, v)) of ``face`` on an n x n grid of its parameter range (INSET from its sides),
    those inside its trim."""
    u0, u1, v0, v1 = face.ParameterRange
    points = []
    grid = np.linspace(INSET, 1.0 - INSET, n)
    for s in grid:
        for t in grid:
            u, v = u0 + (u1 - u0) * s, v0 + (v1 - v0) * t
            if _inside(face, u, v):
                points.append((face.valueAt(u, v), (u, v)))
    return points


def _on_face(face, u, v) -> bool:
    u0, u1, v0, v1 = face.ParameterRange
    return u0 <= u <= u1 and v0 <= v <= v1 and _inside(face, u, v)


def distance(point, face, uv=None, enough: float = 0.0) -> float:
    """Distance from ``point`` to ``face``: OCCT's distToShape, unless another point of the face
    is nearer. BRepExtrema's point-face search can miss the foot point on a wavy B-spline face
    (it reported 0.7 mm between two identical sheets), so the face's point at the same parameters
    ``uv`` and OCCT's point projection (GeomAPI_ProjectPointOnSurf) are candidates too. Each is
    the distance to an actual point of the face (inside its trim), so the result is never below
    the true distance. A candidate within ``enough`` ends the search (a point that close needs no
    closer look)."""
    best = math.inf
    if uv is not None and _on_face(face, *uv):
        best = (face.valueAt(*uv) - point).Length
    if best <= enough:
        return best
    best = min(best, face.distToShape(Part.Vertex(point))[0])
    if best <= enough:
        return best
    # BRepExtrema also misses feet near a sphere's pole and on a torus closed around its tube; the
    # surface's own projections, by Newton (parameter) and by its global extrema, are candidates,
    # their parameters taken a period back into the face's range where the surface is periodic.
    start = uv
    for project in (lambda: face.Surface.parameter(point),
                    lambda: face.Surface.projectPoint(point, "LowerDistanceParameters")):
        try:
            u, v = _into_range(face, *project())
        except (Part.OCCError, RuntimeError, ValueError):  # no projection found
            continue
        if _on_face(face, u, v) and (face.valueAt(u, v) - point).Length < best:
            best, start = (face.valueAt(u, v) - point).Length, (u, v)
        if best <= enough:
            return best
    # Near a degenerate edge (a sphere's pole) OCCT's projections stop short (7.5e-8 mm where a
    # point of the face lies 2e-14 away): a derivative-free descent from the best candidate.
    if start is not None and _on_face(face, *start):
        best = min(best, _pattern_search(face, point, start))
    return best


def _pattern_search(face, point, start) -> float:
    """Distance from ``point`` to the nearest face point found by compass search from ``start``
    (steps halved from 1e-3 of the parameter range to 1e-15 of it; only points inside the face)."""
    u0, u1, v0, v1 = face.ParameterRange

    def gap(u, v):
        return (face.valueAt(u, v) - point).Length if _on_face(face, u, v) else math.inf

    (u, v), here = start, gap(*start)
    du, dv = 1e-3 * (u1 - u0), 1e-3 * (v1 - v0)
    while du > 1e-15 * (u1 - u0):
        moves = [(u + a * du, v + b * dv) for a in (-1, 0, 1) for b in (-1, 0, 1) if a or b]
        nearest = min(moves, key=lambda m: gap(*m))
        if gap(*nearest) < here:
            (u, v), here = nearest, gap(*nearest)
        else:
            du, dv = 0.5 * du, 0.5 * dv
    return here


def _into_range(face, u, v):
    """(u, v) shifted by whole periods of a periodic surface toward the face's parameter range."""
    u0, u1, v0, v1 = face.ParameterRange
    surface = face.Surface
    if surface.isUPeriodic():
        period = surface.UPeriod()
        u += (period * math.floor((u1 - u) / period) if u > u1
              else period * math.ceil((u0 - u) / period) if u < u0 else 0.0)
    if surface.isVPeriodic():
        period = surface.VPeriod()
        v += (period * math.floor((v1 - v) / period) if v > v1
              else period * math.ceil((v0 - v) / period) if v < v0 else 0.0)
    return u, v


def max_distance(points, shape) -> float:
    """Largest distance from ``points`` (vectors) to ``shape`` by OCCT's distToShape."""
    return max((shape.distToShape(Part.Vertex(p))[0] for p in points), default=0.0)


def hausdorff(a, b, n: int = 9, enough: float = 0.0) -> float:
    """Both-ways sampled distance between faces a and b: from a's parameter grid to b and back
    (``distance``; points nearer than ``enough`` count as that near)."""
    return max(max((distance(p, b, uv, enough) for p, uv in sample_points(a, n)), default=0.0),
               max((distance(p, a, uv, enough) for p, uv in sample_points(b, n)), default=0.0))
