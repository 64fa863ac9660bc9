"""The variational sheet as a computation, without a document.

``solve_sheet_on_face`` takes a Part face (the base surface and its boundary) and Part edges (the
curves the sheet must pass through), builds the native ``SheetProblem`` and returns the solved face
together with what a user wants to know about it: how far each curve is from the result (measured
independently of the solver), the size of the B-spline, the solve time and the constraint rank.

Shapes cross into the native extension as BREP strings, so FreeCAD and the extension need only
share OpenCASCADE, not any C++ types.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import List, Optional, Sequence

from varsurf import constraints as constraint_specs

#: Thin plate by default: no stretching term, unit bending. Stretch (alpha) pulls the sheet toward
#: the smallest area (a membrane), bend (beta) toward the smallest curvature.
DEFAULT_STRETCH = 0.0
DEFAULT_BEND = 1.0
#: Largest distance (mm) at which a curve counts as met. The solver fits each group of curves
#: only until its RMS residual is a quarter of this (the discrepancy principle: max deviations
#: run 1-3x the RMS) and leaves the remaining directions to the energy, so the sheet stays fair
#: instead of chasing data its space can hold only with wild poles.
DEFAULT_TOLERANCE = 0.01
#: A new sheet's tolerance when none is set: this fraction of the model's size, rounded down to
#: 1, 2 or 5 times a power of ten (0.01 mm for a 100 mm part, 0.1 mm for a 1 m one).
RELATIVE_TOLERANCE = 1e-4
FIT_TO_TOLERANCE = 0.25
#: The base face's knot vectors are refined (knot insertion: the base shape is unchanged) to at
#: least this many spans per direction; curves off the iso lines need that freedom.
DEFAULT_MIN_SPANS = 16
#: Bases of lower degree (planes and ruled faces convert to degree 1) are elevated to at least
#: cubic by default so the sheet can bend smoothly; a Sheet may ask for a higher degree.
SHEET_MIN_DEGREE = 3
#: Highest degree a Sheet may ask for (OCCT allows 25; beyond 9 the basis is ill-conditioned).
MAX_DEGREE = 9
#: When the curves cannot be held within the tolerance even with wild poles (the solver's
#: "conflict"), the spans are doubled up to this count before giving up.
DEFAULT_MAX_SPANS = 64
#: Solve modes a Sheet offers (see _native.SolveMode): Automatic picks by size and says which.
SOLVE_MODES = ("Automatic", "Exact", "Penalty", "PenaltyQR", "CG", "TSVD", "MTSVD")
#: Relative singular value below which constraint rows are numerically dependent.
DEFAULT_RANK_TOLERANCE = 1e-9
#: Refinement modes: Uniform doubles the spans everywhere until the curves are met; Local refines
#: only the spans under the curves that are off (hierarchical layers, Welch & Witkin sec. 3, 4.4).
REFINEMENTS = ("Uniform", "Local")
DEFAULT_MAX_DEPTH = 5
#: The error of a solve stopped by the user (through its progress indicator).
CANCELLED = "the solve was cancelled; recompute to solve again"

# Resource limits of one sheet's solve (all its refinement rounds): past the time, or beyond the
# memory estimate, the solve stops with a message instead of hanging FreeCAD or exhausting memory.
DEFAULT_TIME_LIMIT = 600.0  # seconds


def default_memory_limit() -> float:
    """Half the machine's physical memory, in bytes (the rest is FreeCAD's and the system's)."""
    import os

    try:
        return 0.5 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return 4e9
#: Fewest points per curve at which the result's distance to the curve is measured (the
#: measurement adds its own where the curve needs them and refines the peaks between them).
DEVIATION_SAMPLES = 200

try:  # the extension is optional at import time so that the workbench still loads and explains
    from varsurf import _native
except ImportError as _error:  # pragma: no cover - exercised only without a build
    _native = None
    _NATIVE_IMPORT_ERROR: Optional[BaseException] = _error
else:
    _NATIVE_IMPORT_ERROR = None


class SheetError(ValueError):
    """A sheet cannot be built from its inputs; the message names the offending input."""


def native():
    """The compiled extension, or an ImportError that says how to build it."""
    if _native is None:
        raise ImportError(
            "The VarSurf native extension (varsurf._native) is not built: run tools/build.sh "
            f"in the VarSurf folder ({_NATIVE_IMPORT_ERROR})"
        )
    return _native


@dataclass
class SheetOutcome:
    """A solved sheet and its figures of merit."""

    shape: object  # Part.Face of the result, in the base face's coordinates
    surface: object  # _native.BSplineSurface
    curve_names: List[str] = field(default_factory=list)
    max_deviations: List[float] = field(default_factory=list)  # mm, one per curve
    pole_count_u: int = 0
    pole_count_v: int = 0
    degree_u: int = 0
    degree_v: int = 0
    solve_seconds: float = 0.0  # native solve
    total_seconds: float = 0.0  # conversion + solve + result face + measurement
    constraint_rank: int = 0
    unknowns: int = 0
    report: object = None  # _native.SolveReport
    constraint_names: List[str] = field(default_factory=list)
    constraint_residuals: List[float] = field(default_factory=list)  # in constraint_units
    constraint_units: List[str] = field(default_factory=list)  # "mm" or "deg"
    iterations: int = 0  # nonlinear steps (repellers, pressure)
    converged: bool = True
    solve_mode: str = ""  # the mode used, and why
    lcurve_residuals: List[float] = field(default_factory=list)  # TSVD/MTSVD: rho_k
    lcurve_norms: List[float] = field(default_factory=list)  # eta_k
    lcurve_corner: int = 0  # the chosen truncation k
    # Local refinement: levels above the base, degrees of freedom (poles) of the hierarchical
    # sheet, and whether every curve was met before the depth limit (Uniform: 0, the poles, True).
    refinement_depth: int = 0
    degrees_of_freedom: int = 0
    refinement_met: bool = True
    refined_spans: List[tuple] = field(default_factory=list)  # (level, u0, u1, v0, v1) each
    # The native SheetProblem of the final solve (curves in curve_names order) and its options:
    # what a joint solve of several sheets (varsurf.joint) starts from.
    problem: object = None
    options: object = None
    # The base face's trim (native BaseTrim): trim.face_brep(surface) bounds and orients any
    # surface of this sheet's space like the result (a drag's or a joint solve's).
    trim: object = None

    @property
    def max_deviation(self) -> float:
        return max(self.max_deviations, default=0.0)

    def summary(self) -> str:
        lines = [
            f"poles {self.pole_count_u} x {self.pole_count_v}, degree {self.degree_u} x {self.degree_v}",
            f"unknowns {self.unknowns}, constraint rank {self.constraint_rank}, {self.solve_mode}",
            f"solve {self.solve_seconds:.3f} s, total {self.total_seconds:.3f} s",
        ]
        for name, dev in zip(self.curve_names, self.max_deviations):
            lines.append(f"{name}: max deviation {dev:.3g} mm")
        for name, res, unit in zip(self.constraint_names, self.constraint_residuals, self.constraint_units):
            lines.append(f"{name}: residual {res:.3g} {unit}")
        return "\n".join(lines)


def tolerance_for_size(size: float) -> float:
    """RELATIVE_TOLERANCE of `size` (mm), rounded down to 1, 2 or 5 x 10^k; DEFAULT_TOLERANCE for a
    size that is not a positive finite length."""
    if not (math.isfinite(size) and size > 0.0):
        return DEFAULT_TOLERANCE
    raw = RELATIVE_TOLERANCE * size
    power = 10.0 ** math.floor(math.log10(raw))
    return max(m for m in (1.0, 2.0, 5.0) if m * power <= raw * (1 + 1e-12)) * power


def _build(cls, *args, **attrs):
    """Construct a native value type from keyword attributes."""
    try:
        return cls(**attrs)
    except TypeError:
        obj = cls()
        for key, value in attrs.items():
            setattr(obj, key, value)
        return obj


def _int(value) -> int:
    """An int from an attribute or a no-argument method (SplineSpace.nu() is a method)."""
    return int(value() if callable(value) else value)


def _part():
    import Part  # FreeCAD's Part module; imported late so this module loads without FreeCAD

    return Part


def shape_from_brep(text: str):
    Part = _part()
    shape = Part.Shape()
    shape.importBrepFromString(text)
    return shape


def _parameter_lengths(surface, samples=12):
    """Mean |S_u| and |S_v| (mm per unit parameter) of a native surface over its domain, divided
    by their geometric mean: how much longer a unit of u is than a unit of v.

    The energy integrates over the base's parameters; a cylinder's or a cone's are an angle and a
    length. Measured in those, scaling the model re-weighted the two directions (a 1 mm and a
    100 mm scene gave shapes differing by 0.9 % of their size). Weights given per unit of these
    relative lengths weigh both directions alike in any base; bases whose two parameters have one
    speed (planes in mm, square [0, 1] B-spline faces) keep their energy exactly. Only the ratio is
    taken, not the lengths themselves: the energy's overall size, which a Pressure is balanced
    against, stays what it was for such bases."""
    space = surface.space
    u0, u1 = space.knots_u[0], space.knots_u[-1]
    v0, v1 = space.knots_v[0], space.knots_v[-1]
    total_u = total_v = 0.0
    for i in range(samples):
        u = u0 + (u1 - u0) * (i + 0.5) / samples
        for j in range(samples):
            v = v0 + (v1 - v0) * (j + 0.5) / samples
            rows = surface.derivatives(u, v, 1)
            total_u += math.sqrt(sum(float(x) ** 2 for x in rows[1]))
            total_v += math.sqrt(sum(float(x) ** 2 for x in rows[2]))
    if not (math.isfinite(total_u) and math.isfinite(total_v) and total_u > 0.0 and total_v > 0.0):
        raise SheetError("the base face's parametrization is degenerate (no length along one direction)")
    mean = math.sqrt(total_u * total_v)
    return total_u / mean, total_v / mean


def _energy(nat, stretch, bend, stretch_tensor, bend_tensor, lengths=(1.0, 1.0)):
    """The native ThinPlateWeights: isotropic, or from (11, 12, 22) tensors, per unit of the
    parameters u * lengths[0], v * lengths[1] (see _parameter_lengths).

    With s = L_u u, t = L_v v: |x_s|^2 ds dt = (L_v / L_u) |x_u|^2 du dv, x_s . x_t ds dt = x_u . x_v
    du dv, |x_ss|^2 ds dt = L_v / L_u^3 |x_uu|^2 du dv, |x_st|^2 ds dt = |x_uv|^2 / (L_u L_v) du dv."""
    import numpy as np

    alpha = float(stretch) * np.eye(2)
    beta = float(bend) * np.ones((2, 2))
    for label, tensor in (("StretchTensor", stretch_tensor), ("BendTensor", bend_tensor)):
        if tensor is None or len(tensor) == 0:
            continue
        if len(tensor) != 3 or not all(math.isfinite(float(x)) for x in tensor):
            raise SheetError(f"{label} takes three finite numbers (11, 12, 22), got {list(tensor)}")
        m = np.array([[tensor[0], tensor[1]], [tensor[1], tensor[2]]], dtype=float)
        if label == "StretchTensor":
            alpha = m
        else:
            beta = m
    lu, lv = lengths
    alpha = alpha * np.array([[lv / lu, 1.0], [1.0, lu / lv]])
    beta = beta * np.array([[lv / lu ** 3, 1.0 / (lu * lv)], [1.0 / (lu * lv), lu / lv ** 3]])
    try:
        return nat.ThinPlateWeights(alpha=alpha, beta=beta)
    except nat.InvalidInput as error:
        raise SheetError(f"energy weights: {error}") from error


def _rest_poles_in(rest_surface, space, nat, spans, degree):
    """Poles of an installed rest shape in the sheet's space (refined alike), or SheetError."""
    refined = nat.refine_surface(rest_surface, spans, spans, degree)
    same = (
        refined.space.degree_u == space.degree_u
        and refined.space.degree_v == space.degree_v
        and _close(refined.space.knots_u, space.knots_u)
        and _close(refined.space.knots_v, space.knots_v)
    )
    if not same:
        raise SheetError(
            "the installed rest shape does not match the sheet's spline space any more (spans, "
            "degree or base changed): install the rest shape again, or melt it"
        )
    return refined.poles


def _close(a, b, tol=1e-9):
    return len(a) == len(b) and all(abs(x - y) <= tol * (1.0 + abs(x)) for x, y in zip(a, b))


def _canonical_direction(nat, curve):
    """``curve`` run from the lexicographically smaller of its two end poles (x, then y, then z).

    A curve and its reverse ask the same of the sheet, but the pre-image's adaptive fit samples
    and splits them differently, and its 1e-7 fit error moved the solved sheet by up to 7e-5 mm
    between the two; one direction for both makes them the same solve."""
    poles = curve.poles
    if not tuple(poles[-1]) < tuple(poles[0]):
        return curve
    a, b = curve.knots[0], curve.knots[-1]
    weights = curve.weights[::-1] if len(curve.weights) else curve.weights
    return nat.BSplineCurve(curve.degree, [a + b - k for k in reversed(curve.knots)], poles[::-1], weights)


def _spans(space) -> int:
    """Fewest polynomial spans of the space over its two directions."""
    return min(len(set(space.knots_u)) - 1, len(set(space.knots_v)) - 1)


def _refuse_outside_trim(trim, preimages, placed, tolerance):
    """SheetError naming the first curve or constraint whose pre-image leaves the base face's
    trimmed domain (over a hole, outside a disc): the sheet keeps the base face's trim, so a curve
    there would shape a part of the sheet that is not kept. Farther than `tolerance` (mm) from the
    face's boundary counts as leaving it.

    preimages: [(name, 2D pre-image)] of the curves; placed: the placed constraint specs."""
    if trim.natural:  # the projection already refuses anything beyond the parameter rectangle
        return
    nat = native()

    def refuse(name, hit):
        where = ("over a hole of the base face" if hit.place == nat.TrimPlace.over_hole
                 else "outside the base face's boundary")
        raise SheetError(f"{name} lies {where} (up to {hit.distance:.3g} mm from its edges): the sheet "
                         "keeps its base face's trim; move it onto the face, or pick a base face that "
                         "covers it")

    for name, preimage in preimages:
        hit = trim.place_curve(preimage, tolerance)
        if hit.place != nat.TrimPlace.inside:
            refuse(name, hit)
    for p in placed:
        curves = [c.preimage for c in (p.ribbon, p.curve) if c is not None]
        for preimage in curves:
            hit = trim.place_curve(preimage, tolerance)
            if hit.place != nat.TrimPlace.inside:
                refuse(p.spec.name, hit)
        if p.spec.kind in constraint_specs.POINT_KINDS:
            hit = trim.place(p.u, p.v, tolerance)
            if hit.place != nat.TrimPlace.inside:
                refuse(p.spec.name, hit)


def _single_face(shape):
    faces = shape.Faces
    if len(faces) != 1:
        raise SheetError(f"expected one face from the extension, got {len(faces)}")
    return faces[0]


#: Points per curve for the best-fit plane of a sheet made from curves alone, and the margin
#: (fraction of the curves' extent) by which its rectangle overhangs them.
PLANE_FIT_SAMPLES = 64
PLANE_MARGIN = 0.1


def plane_face_for_curves(edges: Sequence, spans: int = DEFAULT_MIN_SPANS, margin: float = PLANE_MARGIN,
                          degree: int = SHEET_MIN_DEGREE):
    """A planar B-spline face for a sheet made from curves alone (Michalik & Bruderlin's
    interpolation mode): the least-squares plane of points sampled on the curves, as a rectangle
    covering their projection with ``margin`` overhang, of ``degree`` with ``spans`` uniform
    spans per direction (simple interior knots: the sheet is C^(degree - 1)).

    Raises SheetError without curves, or when the curves do not span a plane (all on one line).
    """
    import numpy as np

    Part = _part()
    points = []
    for edge in edges:
        points.extend((p.x, p.y, p.z) for p in edge.discretize(PLANE_FIT_SAMPLES))
    if not points:
        raise SheetError("a sheet without a base face needs at least one curve")
    pts = np.asarray(points, dtype=float)
    if not np.all(np.isfinite(pts)):
        raise SheetError("the curves have non-finite points")
    center = pts.mean(axis=0)
    # Principal axes: the two largest spread directions span the plane, the smallest is its normal.
    _, sing, axes = np.linalg.svd(pts - center, full_matrices=False)
    extent = float(np.ptp(pts, axis=0).max())
    if extent <= 0.0 or sing[1] <= 1e-9 * max(sing[0], 1e-300):
        raise SheetError(
            "the curves lie on one line: they do not define a surface without a base face"
        )
    e1, e2 = axes[0], axes[1]
    s, t = (pts - center) @ e1, (pts - center) @ e2
    grow = margin * max(np.ptp(s), np.ptp(t))
    s0, s1 = s.min() - grow, s.max() + grow
    t0, t1 = t.min() - grow, t.max() + grow
    p = int(degree)
    knots = [k / spans for k in range(spans + 1)]
    mults = [p + 1] + [1] * (spans - 1) + [p + 1]
    flat = [0.0] * (p + 1) + knots[1:-1] + [1.0] * (p + 1)
    # Poles at the Greville abscissae make the parametrization linear: the face is the plane.
    greville = [sum(flat[i + 1:i + p + 1]) / p for i in range(len(flat) - p - 1)]
    V = _freecad_vector()
    poles = [
        [V(*(center + (s0 + a * (s1 - s0)) * e1 + (t0 + b * (t1 - t0)) * e2)) for b in greville]
        for a in greville
    ]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, p, p)
    return surface.toShape()


def _freecad_vector():
    import FreeCAD

    return FreeCAD.Vector


def solve_sheet_from_curves(edges: Sequence, **options) -> SheetOutcome:
    """``solve_sheet_on_face`` on the best-fit plane of the curves (``plane_face_for_curves``),
    with a free boundary: the sheet is shaped by the curves and its energy alone."""
    options["fix_boundary"] = False
    spans = int(options.get("min_spans", DEFAULT_MIN_SPANS))
    degree = options.get("degree", SHEET_MIN_DEGREE)
    if not (isinstance(degree, int) and 2 <= degree <= MAX_DEGREE):
        raise SheetError(f"Degree must be an integer in 2..{MAX_DEGREE} (got {degree})")
    face = plane_face_for_curves(list(edges), spans=spans, degree=degree)
    return solve_sheet_on_face(face, edges, **options)


def _hierarchy_options(nat, tolerance, max_depth, regions, space, automatic=True, influence_level=0):
    """Native HierarchicalOptions; regions are (level, u0, u1, v0, v1), u and v normalized."""
    options = nat.HierarchicalOptions()
    options.tolerance = float(tolerance)
    options.automatic = bool(automatic)
    if not (isinstance(influence_level, int) and 0 <= influence_level <= max_depth):
        raise SheetError(f"InfluenceLevel must be an integer in 0..MaxDepth ({max_depth}) (got {influence_level})")
    options.influence_level = influence_level
    if not (isinstance(max_depth, int) and 0 <= max_depth <= 8):
        raise SheetError(f"MaxDepth must be an integer in 0..8 (got {max_depth})")
    options.max_depth = max_depth
    boxes = []
    ua, ub = space.knots_u[0], space.knots_u[-1]
    va, vb = space.knots_v[0], space.knots_v[-1]
    for region in regions:
        level, u0, u1, v0, v1 = region
        if not all(math.isfinite(x) for x in (u0, u1, v0, v1)) or not (0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1):
            raise SheetError(f"a refine region needs 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1 (got {region})")
        boxes.append(nat.RefineBox(int(level), ua + (ub - ua) * u0, ua + (ub - ua) * u1,
                                   va + (vb - va) * v0, va + (vb - va) * v1))
    options.manual = boxes
    return options


def _mode_used(report, local) -> str:
    """The solve's mode and why; a hierarchical solve also says what its unknowns count: the x,
    y and z of its free poles in one coupled system, not its poles (DegreesOfFreedom)."""
    reason = str(report.mode_reason)
    if local is None:
        return reason
    unknowns = int(report.unknowns)
    levels = int(local.depth) + 1
    return (f"{reason}; locally refined: {int(local.dofs)} poles on {levels} level{'' if levels == 1 else 's'}, "
            f"{unknowns // 3} of them free, their x, y and z solved together ({unknowns} unknowns)")


def _projection_failure(name, direction, error):
    """The message of a curve whose pre-image cannot be found, naming the real cause."""
    if direction is not None:
        seen = tuple(round(c, 6) for c in direction)
        if "beyond the face" in error:
            return (f"{name} runs beyond the base face seen along {seen} (the Sheet's Projection): {error}; "
                    "move the curve over the face, or project it another way")
        return f"{name} cannot be projected onto the base face along {seen}: {error}"
    if "crosses the seam of the closed face" in error:  # on the face, but around it
        return f"{name} goes around the closed base face across its seam: {error}"
    if "jumps" in error:
        return (f"{name}'s orthogonal projection onto the base face jumps (the curve lies too far from a curved "
                f"base for its nearest points to follow it): {error}. Project it along a direction instead: set "
                "the Sheet's Projection to Direction (or Automatic, for a sketch facing the base)")
    return (f"{name} runs beyond the base face (it must lie over the face to be projected onto it): {error}")


def solve_sheet_on_face(
    face,
    edges: Sequence,
    stretch: float = DEFAULT_STRETCH,
    bend: float = DEFAULT_BEND,
    fix_boundary: bool = True,
    tolerance: float = DEFAULT_TOLERANCE,
    min_spans: int = DEFAULT_MIN_SPANS,
    max_spans: int = DEFAULT_MAX_SPANS,
    names: Optional[Sequence[str]] = None,
    rank_tolerance: float = DEFAULT_RANK_TOLERANCE,
    constraints: Sequence = (),
    rest=None,
    pressure: float = 0.0,
    exact_curves: Sequence[str] = (),
    stretch_tensor: Optional[Sequence[float]] = None,
    bend_tensor: Optional[Sequence[float]] = None,
    degree: int = SHEET_MIN_DEGREE,
    solve_mode: str = "Automatic",
    keep_going=None,
    refinement: str = "Uniform",
    max_depth: int = DEFAULT_MAX_DEPTH,
    refine_regions: Sequence = (),
    auto_refine: bool = True,
    influence_level: int = 0,
    time_limit: Optional[float] = None,
    memory_limit: Optional[float] = None,
    projections: Optional[Sequence] = None,
) -> SheetOutcome:
    """Solve the variational sheet over ``face`` that passes through ``edges``.

    face: a Part.Face (any surface type; non-B-spline surfaces are converted to NURBS, and the
        surface is cut to the face's parameter bounds). Its poles are the start shape and, with
        ``fix_boundary``, its boundary poles are held so the sheet keeps the base face's boundary.
    edges: Part.Edge objects the sheet must contain; each is projected onto the base face to find
        its pre-image, so each must lie over the face.
    stretch, bend: isotropic thin-plate weights (alpha, beta), both >= 0 and not both 0.
    tolerance: distance (mm) at which a curve counts as met.
    degree: the sheet's degree is at least this in u and v (the base is elevated; 2..MAX_DEGREE).
    solve_mode: one of SOLVE_MODES: Exact (Lagrange/KKT), Penalty (sparse Cholesky; PenaltyQR:
        sparse QR of the stacked system), CG, TSVD or MTSVD (the L-curve
        chooses how many constraint directions are fitted), or Automatic.
    min_spans, max_spans: the base face is refined to at least min_spans spans per direction;
        while the curves contradict each other by more than the tolerance, the spans are doubled
        up to max_spans. A conflict that survives refinement (curves crossing at different
        heights, a curve the fixed boundary cannot reach) is an error naming the curves.
    names: one label per edge for messages and reports ("Sketch001:Edge2").
    projections: one entry per edge: None projects the edge orthogonally onto the base face (to
        its closest points), an (x, y, z) direction projects it along that direction (a sketch
        seen along its normal). Omitted: every edge orthogonally.
    constraints: ConstraintSpec objects (varsurf.constraints): point, tangent, normal,
        point-in-plane and point-on-line constraints, attractors, directors, frozen regions.
    stretch_tensor, bend_tensor: anisotropic weights (a11, a12, a22) and (b11, b12, b22) of
        sum_ij alpha_ij D_i w D_j w + beta_ij (D_i D_j w)^2 (Welch & Witkin eq. 4; b12 weighs each
        of the two mixed terms), replacing stretch and bend when given.
    exact_curves: names of curves met exactly wherever the space allows (incidence in every
        direction the spline space holds), instead of within the tolerance; exact curves can
        cost fairness on coarse sheets.
    pressure: inflate (> 0, along the sheet's normal) or deflate (< 0), in the energy's units;
        solved by iterating (see SolveReport.iterations/converged).
    rest: None (pure fairness), "base" (the base face is the rest shape: the energy acts on the
        displacement from it, so edits keep its detail), or a Part face whose B-spline has the
        sheet's own spline space (an installed rest shape).

    Raises SheetError (a ValueError) naming the curve or parameter at fault, and lets the
    extension's SolveFailure / GeometryError through for numerical or kernel failures.
    """
    nat = native()
    t0 = time.perf_counter()
    edges = list(edges)
    if names is None:
        names = [f"Edge{i + 1}" for i in range(len(edges))]
    names = [str(n) for n in names]
    if len(names) != len(edges):
        raise SheetError(f"{len(edges)} edges but {len(names)} names")
    projections = [None] * len(edges) if projections is None else list(projections)
    if len(projections) != len(edges):
        raise SheetError(f"{len(edges)} edges but {len(projections)} projection directions")
    for label, value in (("Stretch", stretch), ("Bend", bend)):
        if not value >= 0.0:  # also rejects NaN
            raise SheetError(f"{label} must be >= 0 (got {value})")
    if stretch == 0.0 and bend == 0.0 and not stretch_tensor and not bend_tensor:
        raise SheetError("Stretch and Bend are both 0: the sheet would have no energy to minimize")
    if not (tolerance > 0.0 and math.isfinite(tolerance)):
        raise SheetError(f"Tolerance must be a positive length (got {tolerance})")
    if not 1 <= int(min_spans) <= int(max_spans) <= 512:
        raise SheetError(f"spans must satisfy 1 <= MinSpans <= MaxSpans <= 512 (got {min_spans}, {max_spans})")
    if not (isinstance(degree, int) and 2 <= degree <= MAX_DEGREE):
        raise SheetError(f"Degree must be an integer in 2..{MAX_DEGREE} (got {degree})")
    if solve_mode not in SOLVE_MODES:
        raise SheetError(f"SolveMode must be one of {', '.join(SOLVE_MODES)} (got {solve_mode!r})")
    if not 0.0 < rank_tolerance < 1.0:
        raise SheetError(f"rank tolerance must be in (0, 1) (got {rank_tolerance})")
    if getattr(face, "ShapeType", None) != "Face":
        raise SheetError("the base must be a face")

    try:
        base = nat.surface_from_face_brep(face.exportBrepToString())
        trim = nat.BaseTrim(face.exportBrepToString())  # the face's wires and orientation
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(f"the base face cannot be used: {error}") from error
    extent = face.BoundBox.DiagonalLength
    if not (math.isfinite(extent) and extent > 0.0) or face.Area < 1e-6 * extent ** 2:
        raise SheetError(f"the base face is degenerate: {face.Area:.3g} mm² over a {extent:.3g} mm extent "
                         "(collapsed to a line or a point); pick a face that has an area")
    if tolerance >= extent:
        raise SheetError(f"Tolerance {tolerance:.3g} mm is not smaller than the model ({extent:.3g} mm across): "
                         "every curve would count as met; give a tolerance well below the model's size")

    curve_constraints = []
    targets = []
    for edge, name, direction in zip(edges, names, projections):
        if getattr(edge, "ShapeType", None) != "Edge":
            raise SheetError(f"{name} is not an edge")
        try:
            curve = _canonical_direction(nat, nat.curve_from_edge_brep(edge.exportBrepToString()))
        except (nat.InvalidInput, nat.GeometryError) as error:
            raise SheetError(f"{name} cannot be converted to a B-spline curve: {error}") from error
        try:
            pre = nat.project_curve(base, curve, direction=direction)
        except nat.InvalidInput as error:
            raise SheetError(_projection_failure(name, direction, str(error))) from error
        except nat.GeometryError as error:
            raise SheetError(f"{name} cannot be projected onto the base face: {error}") from error
        # Where the curve's foot point is on the face's boundary, a kept boundary cannot move to it
        # (the solver sees those samples on fixed poles only): say so instead of refining in vain.
        if fix_boundary and pre.boundary_distance > tolerance:
            x, y, z = (float(c) for c in curve.evaluate(pre.boundary_t))
            raise SheetError(
                f"{name} is {pre.boundary_distance:.3g} mm from the base face where it reaches the face's "
                f"kept boundary (at ({x:.4g}, {y:.4g}, {z:.4g})): the kept boundary cannot move "
                "there; let the curve meet the boundary, or turn FixBoundary off"
            )
        curve_constraints.append(
            _build(nat.CurveConstraint, preimage=pre.curve, target=curve, weight=1.0,
                   exact=name in set(exact_curves))
        )
        targets.append(curve)

    try:
        placed = constraint_specs.place(list(constraints), base, nat)
    except constraint_specs.ConstraintError as error:
        raise SheetError(str(error)) from error
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(f"a constraint's location cannot be placed on the base face: {error}") from error
    _refuse_outside_trim(trim, [(n, c.preimage) for n, c in zip(names, curve_constraints)], placed, tolerance)
    if fix_boundary:  # a trimmed face's own edges are kept too, not only its parameter rectangle's
        try:
            held = trim.boundary()
        except (nat.InvalidInput, nat.GeometryError) as error:
            raise SheetError(f"the base face's boundary cannot be kept: {error}") from error
        # After the named curves: outcome.problem.curves starts in curve_names order.
        curve_constraints += [_build(nat.CurveConstraint, preimage=b.preimage, target=b.target, weight=1.0)
                              for b in held]

    rest_surface = None
    if rest is not None and not (isinstance(rest, str) and rest == "base"):
        try:
            rest_surface = nat.surface_from_face_brep(rest.exportBrepToString())
        except (nat.InvalidInput, nat.GeometryError, AttributeError) as error:
            raise SheetError(f"the installed rest shape cannot be used: {error}") from error

    energy = _energy(nat, stretch, bend, stretch_tensor, bend_tensor, _parameter_lengths(base))

    # Pre-images and constraint (u, v) stay valid on every refinement: knot insertion keeps the
    # parametrization.
    spans = max(int(min_spans), _spans(base.space))
    options = _build(nat.SolveOptions)
    options.rank_tolerance = float(rank_tolerance)
    options.fit_tolerance = FIT_TO_TOLERANCE * float(tolerance)
    options.mode = getattr(nat.SolveMode, "penalty" if solve_mode == "PenaltyQR" else solve_mode.lower())
    options.penalty_qr = solve_mode == "PenaltyQR"
    if keep_going is not None:  # asked between iterative steps and refinement levels
        options.keep_going = keep_going
    time_limit = DEFAULT_TIME_LIMIT if time_limit is None else float(time_limit)
    memory_limit = default_memory_limit() if memory_limit is None else float(memory_limit)
    if not (time_limit > 0.0 and memory_limit > 0.0):  # NaN too
        raise SheetError(f"the time and memory limits must be positive (got {time_limit} s, {memory_limit} bytes)")
    options.memory_limit = memory_limit
    deadline = time.monotonic() + time_limit

    def run(solve, *args):
        """A native solve on the rest of the time budget; its refusals as SheetErrors."""
        options.time_limit = deadline - time.monotonic()
        if options.time_limit <= 0.0:
            raise SheetError(f"the solve took longer than its time limit of {time_limit:.3g} s; "
                             "raise the limit in the preferences, or use fewer spans or a looser tolerance")
        try:
            return solve(*args)
        except (nat.InvalidInput, nat.ResourceLimit) as error:
            raise SheetError(str(error)) from error
        except nat.Cancelled as error:
            raise SheetError(CANCELLED) from error
    if refinement not in REFINEMENTS:
        raise SheetError(f"Refinement must be one of {', '.join(REFINEMENTS)} (got {refinement!r})")
    local = None  # the hierarchical report of a Local refinement

    def make_problem(spans):
        """The base refined to `spans` per direction, its space and the native problem on it."""
        sheet = nat.refine_surface(base, spans, spans, degree)
        space = sheet.space
        terms = constraint_specs.native_terms(placed, space, nat)
        fixed = list(nat.boundary_pole_indices(space)) if fix_boundary else []
        fixed = sorted(set(fixed) | set(terms.frozen_poles))
        problem = _build(
            nat.SheetProblem,
            space=space,
            initial_poles=sheet.poles,
            energy=energy,
            points=[],
            curves=curve_constraints,
            fixed_poles=fixed,
        )
        terms.apply(problem)
        # The core inflates along Su x Sv; a Reversed base face's outward normal is the opposite.
        problem.pressure = float(pressure) * trim.normal_sign
        if rest == "base":
            problem.rest_poles = sheet.poles
        elif rest_surface is not None:
            problem.rest_poles = _rest_poles_in(rest_surface, space, nat, spans, degree)
        return sheet, space, problem

    if not math.isfinite(pressure):
        raise SheetError(f"Pressure must be finite (got {pressure})")
    while True:
        if keep_going is not None and not keep_going():
            raise SheetError(CANCELLED)
        sheet, space, problem = make_problem(spans)
        if refinement == "Local":
            hierarchy = _hierarchy_options(nat, tolerance, max_depth, refine_regions, space, auto_refine,
                                           influence_level)
            solved = run(nat.solve_hierarchical, problem, hierarchy, options)
            local = solved.report
            if local.depth > 0:  # joint solves start from the outcome's problem: the finest level's
                problem = make_problem(spans * 2 ** local.depth)[2]
            space = solved.space
            result = SimpleNamespace(poles=solved.poles, report=solved.report.solve)
            conflict, deviations = 0.0, None  # what is left is measured below and reported
            break
        result = run(nat.solve_sheet, problem, options)
        if not result.report.converged:
            raise SheetError(
                f"the nonlinear terms (pressure, repellers, shape attractors) did not settle in "
                f"{result.report.iterations} steps (the last moved poles {result.report.last_step:.3g} mm); "
                "a pressure needs tension to hold it: give the sheet a Stretch, or lower the pressure"
            )
        conflict = float(result.report.conflict)
        deviations = None
        if conflict <= tolerance:
            # The fit is judged per curve by its RMS; a curve can still stray further somewhere.
            trial = _build(nat.BSplineSurface, space=space, poles=result.poles)
            deviations = [float(nat.max_deviation(trial, c, DEVIATION_SAMPLES)) for c in targets]
            if max(deviations, default=0.0) <= tolerance:
                break
        if 2 * spans > max_spans:
            break
        spans *= 2

    surface = _build(nat.BSplineSurface, space=space, poles=result.poles)
    if conflict > tolerance:
        deviations = [float(nat.max_deviation(surface, c, DEVIATION_SAMPLES)) for c in targets]
        worst = [f"{n} ({d:.3g} mm)" for n, d in zip(names, deviations) if d > tolerance]
        for p in placed:  # point-like constraints contradict too (two targets at one place)
            unit = constraint_specs.KINDS[p.spec.kind][1]
            off = float(constraint_specs.residual(p, surface, base))
            if unit == "mm" and off > tolerance:
                worst.append(f"{p.spec.name} ({off:.3g} mm)")
        raise SheetError(
            f"the curves and constraints cannot all be met: they contradict each other by {conflict:.3g} mm "
            f"(RMS) even with {spans} spans per direction. Off by more than the tolerance: "
            f"{', '.join(worst) or 'none individually'}. Curves that cross must meet in space; "
            "curves close to a kept boundary must reach it smoothly (or turn FixBoundary off); "
            "points must not ask one place of the sheet to be in two."
        )
    try:  # bounded and oriented like the base face
        shape = _single_face(shape_from_brep(trim.face_brep(surface)))
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(f"the sheet cannot be bounded like its base face: {error}") from error
    if deviations is None:
        deviations = [float(nat.max_deviation(surface, c, DEVIATION_SAMPLES)) for c in targets]
    residuals = [float(constraint_specs.residual(p, surface, base)) for p in placed]
    report = result.report
    options.keep_going = None  # the outcome's options serve later solves (joint, drag)
    options.time_limit = time_limit  # each later solve gets the whole limit again
    return SheetOutcome(
        shape=shape,
        surface=surface,
        curve_names=list(names),
        max_deviations=deviations,
        pole_count_u=_int(space.nu),
        pole_count_v=_int(space.nv),
        degree_u=int(space.degree_u),
        degree_v=int(space.degree_v),
        # Local: the whole hierarchical solve (every refinement round), as a recompute feels it.
        solve_seconds=float(local.total_seconds if local is not None else report.total_seconds),
        total_seconds=time.perf_counter() - t0,
        constraint_rank=int(report.constraint_rank),
        unknowns=int(report.unknowns),
        constraint_names=[p.spec.name for p in placed],
        constraint_residuals=residuals,
        constraint_units=[constraint_specs.KINDS[p.spec.kind][1] for p in placed],
        iterations=int(report.iterations),
        converged=bool(report.converged),
        report=report,
        solve_mode=_mode_used(report, local),
        lcurve_residuals=[float(x) for x in report.lcurve.residual],
        lcurve_norms=[float(x) for x in report.lcurve.solution_norm],
        lcurve_corner=int(report.lcurve.corner),
        refinement_depth=int(local.depth) if local is not None else 0,
        degrees_of_freedom=int(local.dofs) if local is not None else int(space.size()),
        refinement_met=bool(local.met) if local is not None else True,
        refined_spans=[(b.level, b.u0, b.u1, b.v0, b.v1) for b in local.refined] if local is not None else [],
        problem=problem,
        options=options,
        trim=trim,
    )
