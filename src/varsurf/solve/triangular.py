# SPDX-License-Identifier: LGPL-2.1-or-later
"""Triangular Bezier surfaces over triangulations without a document (Veltkamp & Wesselink): the
core's fairest G1 patches over a triangle mesh, each patch written exactly as three tensor-product
Bezier faces of degree n x n and all faces sewn into one shell (a solid when the mesh is closed),
and the triangulation of an N-sided loop for filling a hole. This module builds the core's inputs,
words its errors and gathers what the feature reports."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Sequence, Tuple

import numpy as np

from varsurf.solve.errors import SheetError, advised
from varsurf.solve.native import native

Point = Tuple[float, float, float]
Triangle = Tuple[int, int, int]

#: Solvers of a triangular surface, as a feature names them.
SOLVERS = ("Automatic", "Direct", "CG")

#: The largest triangulation solved: 200,000 triangles (a quintic surface of that size has about
#: 5 million unknowns; see bench/triangular.py for the cost per triangle).
MAX_TRIANGLES = 200_000


@dataclass
class Constraint:
    """A point, normal, plane or line constraint at barycentric point `at` of triangle `triangle`
    (corners in the order given)."""
    kind: str  # "point", "normal", "plane", "line"
    triangle: int
    at: Point
    target: Point = (0.0, 0.0, 0.0)
    direction: Point = (0.0, 0.0, 1.0)


#: Operator kinds, as a feature names them.
OPERATOR_KINDS = ("PointAttractor", "PlaneAttractor", "LineAttractor", "Director", "Repeller", "ShapeAttractor")


@dataclass
class Operator:
    """An external energy operator on `triangles` (empty: all): attractors pull toward `origin` (a
    point, the plane through it normal to `direction`, the line through it along `direction`), a
    Director turns the normals toward `direction`, a Repeller pushes away from `origin`, a
    ShapeAttractor pulls onto the shape `target_brep` (a BREP string). Strength 1 pulls about as hard
    as the surface resists."""
    kind: str
    triangles: Sequence[int] = ()
    origin: Point = (0.0, 0.0, 0.0)
    direction: Point = (0.0, 0.0, 1.0)
    strength: float = 1.0
    target_brep: str = ""


@dataclass
class Settings:
    degree: int = 3
    stretch: float = 0.0
    bend: float = 1.0
    g1: bool = True
    approximate_g1: bool = False
    border_angle: float = -1.0  # degrees; negative: the angle the mesh spans at each border vertex
    interpolate_vertices: bool = True
    rest_shape: bool = False  # the energy of the displacement from the mesh's own flat patches
    solver: str = "Automatic"
    angle_tolerance: float = 0.01  # degrees


@dataclass
class Outcome:
    patches: list  # native TriangularBezier, per triangle
    report: object  # native TriangularReport
    brep: str = ""
    closed: bool = False
    faces: int = 0
    seam_angle: float = 0.0  # degrees: the largest tangent-plane angle across any B-rep seam
    seams: int = 0
    export_seconds: float = 0.0
    warnings: List[str] = field(default_factory=list)
    split_triangles: int = 0  # of the source, split so that edges carry curves
    curve_fit: float = 0.0  # how far the edges carrying curves stray from them
    folded: List[int] = field(default_factory=list)  # patches that turn over inside


def _operators(nat, operators: Sequence[Operator]):
    kinds = {name: getattr(nat.TriangularOperatorKind, snake) for name, snake in zip(
        OPERATOR_KINDS, ("point_attractor", "plane_attractor", "line_attractor", "director", "repeller",
                         "shape_attractor"))}
    out = []
    for index, op in enumerate(operators):
        if op.kind not in kinds:
            raise SheetError(f"operator {index} is of kind {op.kind!r}: give one of {', '.join(kinds)}")
        target = None
        if op.kind == "ShapeAttractor":
            if not op.target_brep:
                raise SheetError(f"operator {index} (ShapeAttractor) has no target: give the shape to pull onto")
            try:
                target = nat.ClosestPointTarget(op.target_brep)
            except (nat.InvalidInput, nat.GeometryError) as error:
                raise SheetError(advised(f"operator {index}'s target cannot be read: {error}",
                                         "give a shape with faces or edges")) from error
        out.append(nat.TriangularOperator(kinds[op.kind], [int(t) for t in op.triangles],
                                          np.asarray(op.origin, float), np.asarray(op.direction, float),
                                          float(op.strength), target))
    return out


def _problem(points: Sequence[Point], triangles: Sequence[Triangle], settings: Settings,
             constraints: Sequence[Constraint], operators: Sequence[Operator] = ()):
    nat = native()
    if settings.solver not in SOLVERS:
        raise SheetError(f"Solver must be one of {', '.join(SOLVERS)}, not {settings.solver!r}")
    if len(triangles) > MAX_TRIANGLES:
        raise SheetError(f"the mesh has {len(triangles)} triangles, more than the {MAX_TRIANGLES} a triangular "
                         "surface takes: use a coarser mesh (its triangles are patches, not samples)")
    problem = nat.TriangularProblem()
    problem.vertices = np.asarray(points, float).reshape(-1, 3)
    problem.triangles = [tuple(int(c) for c in t) for t in triangles]
    problem.degree = int(settings.degree)
    problem.stretch = float(settings.stretch)
    problem.bend = float(settings.bend)
    problem.g1 = bool(settings.g1)
    problem.approximate_g1 = bool(settings.approximate_g1)
    angle = float(settings.border_angle)
    problem.border_angle = math.radians(angle) if angle > 0.0 else -1.0
    problem.interpolate_vertices = bool(settings.interpolate_vertices)
    problem.energy_of_displacement = bool(settings.rest_shape)
    problem.solver = {"Automatic": nat.TriangularSolver.automatic, "Direct": nat.TriangularSolver.direct,
                      "CG": nat.TriangularSolver.cg}[settings.solver]
    problem.angle_tolerance = float(settings.angle_tolerance)
    kinds = {"point": nat.TriangularConstraintKind.point, "normal": nat.TriangularConstraintKind.normal,
             "plane": nat.TriangularConstraintKind.plane, "line": nat.TriangularConstraintKind.line}
    native_constraints = []
    for index, c in enumerate(constraints):
        if c.kind not in kinds:
            raise SheetError(f"constraint {index} is of kind {c.kind!r}: give one of {', '.join(kinds)}")
        native_constraints.append(nat.TriangularConstraint(kinds[c.kind], int(c.triangle), np.asarray(c.at, float),
                                                           np.asarray(c.target, float),
                                                           np.asarray(c.direction, float)))
    problem.constraints = native_constraints
    problem.operators = _operators(nat, operators)
    return problem


def solve(points: Sequence[Point], triangles: Sequence[Triangle], settings: Settings = Settings(),
          constraints: Sequence[Constraint] = (), export: bool = True, tolerance: float = 0.0,
          operators: Sequence[Operator] = (), fixed_edges: Sequence[Tuple[int, int, np.ndarray]] = (),
          free_vertices: Sequence[int] = ()) -> Outcome:
    """The fairest surface over the triangulation, shaped by `operators`, and, with `export`, its
    B-rep: each patch as three n x n Bezier faces, sewn at `tolerance` (0: a ten-millionth of the
    mesh's size); `fixed_edges` are (from vertex, to vertex, degree + 1 control points) that mesh
    edges must take (curves the surface contains); `free_vertices` are not interpolated (added by
    splitting off the curves). SheetError names the triangle, edge, vertex,
    constraint or operator at fault."""
    nat = native()
    problem = _problem(points, triangles, settings, constraints, operators)
    problem.fixed_edges = [nat.FixedEdge(int(a), int(b), np.asarray(p, float)) for a, b, p in fixed_edges]
    problem.free_vertices = [int(v) for v in free_vertices]
    try:
        result = nat.solve_triangular(problem)
    except nat.InvalidInput as error:
        raise SheetError(advised(f"the triangulation cannot carry a surface: {error}",
                                 "repair the mesh")) from error
    except nat.SolveFailure as error:
        raise SheetError(advised(str(error), "add a point constraint")) from error
    report = result.report
    outcome = Outcome(list(result.patches), report)
    for (a, b), angle in list(zip(report.overruled_edges, report.overruled_angles))[:5]:
        outcome.warnings.append(f"edge ({a}, {b}) is not G1: its patches meet at {angle:.3g} degrees "
                                "(continuity overruled by interpolation or beyond the conditions)")
    if len(report.overruled_edges) > 5:
        outcome.warnings.append(f"{len(report.overruled_edges) - 5} more edges are not G1")
    # Sampling every patch costs about 0.1 ms a patch: done for a shape, not for a bare solve.
    outcome.folded = folded_patches(result.patches) if export else []
    if outcome.folded:
        listed = ", ".join(str(k) for k in outcome.folded[:8])
        outcome.warnings.append(f"patches {listed} fold (the surface turns over inside them): raise Degree, "
                                "move the curves or remesh there")
    if report.singular_vertices:
        listed = ", ".join(str(v) for v in report.singular_vertices[:8])
        outcome.warnings.append(f"vertices {listed} are nearly singular (tangents collapsed to "
                                f"{report.shortest_tangent:.2g} of an edge): raise Degree or remesh there")
    if export:
        import time
        started = time.perf_counter()
        vertices = np.asarray(points, float).reshape(-1, 3)
        size = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0))) if len(vertices) else 1.0
        tolerance = float(tolerance) or max(1e-7 * size, 1e-9)
        quads = [q for patch in result.patches for q in nat.triangle_quads(patch)]
        try:
            shell = nat.patch_shell(quads, [False] * len(quads), tolerance, 11)
        except (nat.InvalidInput, nat.GeometryError) as error:
            raise SheetError(advised(f"the patches cannot be sewn: {error}", "raise the tolerance")) from error
        if not shell.shell.valid:
            raise SheetError(f"the sewn faces are not a valid shape ({shell.shell.message}): raise the tolerance")
        outcome.brep = shell.shell.brep
        outcome.closed = bool(shell.shell.closed)
        outcome.faces = len(quads)
        outcome.seam_angle = float(shell.regular_angle)
        outcome.seams = int(shell.regular_seams)
        outcome.export_seconds = time.perf_counter() - started
    return outcome


def folded_patches(patches, samples: int = 8) -> List[int]:
    """The patches whose surface turns over inside (a fold): each sampled as samples^2 small
    triangles, one of whose normals points away from the patch's mean normal. Folds the G1 angle
    cannot see (it measures only along the edges) and that make OCCT's check find the faces
    self-intersecting."""
    n = int(samples)
    grid = [(i, j) for i in range(n + 1) for j in range(n + 1 - i)]
    index = {ij: k for k, ij in enumerate(grid)}
    small = [(index[(i, j)], index[(i + 1, j)], index[(i, j + 1)]) for i in range(n) for j in range(n - i)]
    small += [(index[(i + 1, j)], index[(i + 1, j + 1)], index[(i, j + 1)]) for i in range(n) for j in range(n - 1 - i)]
    small = np.array(small)
    out = []
    for k, patch in enumerate(patches):
        points = np.array([patch.evaluate(np.array([i / n, j / n, 1.0 - (i + j) / n])) for i, j in grid])
        normals = np.cross(points[small[:, 1]] - points[small[:, 0]], points[small[:, 2]] - points[small[:, 0]])
        mean = normals.sum(axis=0)
        if (normals @ mean < -1e-12 * np.abs(normals).sum() * np.linalg.norm(mean)).any():
            out.append(k)
    return out


def bezier_piece(curve, first: float, last: float, degree: int, derivative=None, speeds=None) -> np.ndarray:
    """The degree-`degree` Bezier control points (rows) of the polynomial through `curve(t)` at
    degree + 1 Chebyshev-Lobatto parameters of [first, last]: the piece itself when it is a
    polynomial of that degree or lower, else its interpolant (whose error falls as the piece's
    length to the power degree + 1). With `derivative` (the curve's first derivative) the ends
    take the curve's own tangents too and the inner nodes are one fewer at each end, so that two
    pieces of equal span meet with equal tangents, which G1 across the curve needs. `speeds`
    (dt/ds at the two ends, s the piece's own parameter; by default last - first) scale those
    tangents, the piece then following the curve through t(s), the cubic with those end slopes:
    pieces of two curves joined at a vertex can meet with equal tangents too."""
    n = int(degree)
    binomial = np.array([math.comb(n, k) for k in range(n + 1)], float)

    def basis(s):
        s = np.asarray(s, float)[:, None]
        return binomial * s ** np.arange(n + 1) * (1.0 - s) ** (n - np.arange(n + 1))

    span = last - first
    slope0, slope1 = (span, span) if speeds is None else (float(speeds[0]), float(speeds[1]))

    def at(s):
        return np.array([np.asarray(curve(float(u)), float) for u in hermite_parameter(s, first, last, slope0, slope1)])

    if derivative is None or n < 3:
        nodes = 0.5 - 0.5 * np.cos(np.pi * np.arange(n + 1) / n)
        return np.linalg.solve(basis(nodes), at(nodes))
    nodes = 0.5 - 0.5 * np.cos(np.pi * np.arange(n - 1) / (n - 2))
    ends = np.zeros((2, n + 1))
    ends[0, :2] = (-n, n)
    ends[1, -2:] = (-n, n)
    slopes = np.array([slope0 * np.asarray(derivative(first), float), slope1 * np.asarray(derivative(last), float)])
    return np.linalg.solve(np.vstack([basis(nodes), ends]), np.vstack([at(nodes), slopes]))


def hermite_parameter(s, first: float, last: float, slope0: float, slope1: float) -> np.ndarray:
    """t(s) on [0, 1]: the cubic from first to last with slopes slope0 and slope1 at its ends
    (the line when both are last - first)."""
    s = np.asarray(s, float)
    return (first * (2 * s**3 - 3 * s**2 + 1) + slope0 * (s**3 - 2 * s**2 + s) + last * (3 * s**2 - 2 * s**3)
            + slope1 * (s**3 - s**2))


def loop_triangulation(loop: Sequence[Point], rings: int = 2) -> Tuple[List[Point], List[Triangle]]:
    """A triangulation of the region inside a closed loop of points (an N-sided hole's border
    sampled, each point once, in order): `rings` rings shrinking towards the loop's centroid, joined
    by triangles, and a fan at the centre. The loop's points come first, in order; the region must
    be star-shaped from the centroid (every border point seen from it)."""
    corners = np.asarray(loop, float).reshape(-1, 3)
    count = len(corners)
    if count < 3:
        raise SheetError(f"a loop needs at least 3 points, not {count}: select the hole's border edges")
    if not 1 <= int(rings) <= 50:
        raise SheetError(f"Rings must be 1 to 50, not {rings}")
    centre = corners.mean(axis=0)
    points = [tuple(p) for p in corners]
    for ring in range(1, int(rings)):
        scale = 1.0 - ring / int(rings)
        points += [tuple(centre + scale * (p - centre)) for p in corners]
    points.append(tuple(centre))
    triangles: List[Triangle] = []
    for ring in range(int(rings) - 1):
        outer, inner = ring * count, (ring + 1) * count
        for k in range(count):
            a, b = outer + k, outer + (k + 1) % count
            c, d = inner + k, inner + (k + 1) % count
            triangles += [(a, b, d), (a, d, c)]
    last, middle = (int(rings) - 1) * count, len(points) - 1
    triangles += [(last + k, last + (k + 1) % count, middle) for k in range(count)]
    return points, triangles
