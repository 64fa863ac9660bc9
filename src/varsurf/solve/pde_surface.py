# SPDX-License-Identifier: LGPL-2.1-or-later
"""PDE surfaces from boundary conditions (Du & Qin sec. 3.1, 4.2), without a document.

A PDE surface minimizes the energy of the generalized Bloor-Wilson operator
(d2/du2 + a^2 d2/dv2)^2 P = 0 over a B-spline sheet on [0, 1]^2 whose v runs along the boundary
curves: Hermite-like data (the curves at u = 0 and u = 1 and their derivative curves: the
difference between a boundary point and its correspondence on the derivative curve is the tangent
across the boundary, per unit of u, times a magnitude), Coons-like data (also the curves at v = 0
and v = 1) and Gordon-like networks (isoparametric curves inside). The spans double until every
curve lies on the result within the tolerance.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field
from typing import Dict, List, Sequence, Tuple

from varsurf.solve import constraints as constraint_specs
from varsurf.solve.errors import CANCELLED, SheetError, advised
from varsurf.solve.native import build, native

#: Roles of the curves, in the core's names: boundary curves at u = 0, 1, their derivative curves,
#: the Coons sides at v = 0, 1.
ROLES = ("u0", "u1", "d0", "d1", "v0", "v1")


@dataclass(frozen=True)
class PdeSurfaceSettings:
    a: float = 1.0
    regions: Sequence[Tuple[float, float, float, float, float]] = ()  # (a, u0, u1, v0, v1), 0..1
    # a painted inside closed (u, v) polygons, over the rectangles: (a, ((u, v), ...)), 0..1.
    loops: Sequence[Tuple[float, Sequence[Tuple[float, float]]]] = ()
    blend: float = 0.0
    magnitude0: float = 1.0
    magnitude1: float = 1.0
    degree: int = 3
    min_spans: int = 8
    max_spans: int = 64
    tolerance: float = 0.01
    time_limit: float = 600.0
    # Mass and damping painted for the dynamic drag: (mass, damping, u0, u1, v0, v1), 0..1.
    materials: Sequence[Tuple[float, float, float, float, float, float]] = ()


@dataclass
class PdeSurfaceOutcome:
    surface: object  # native BSplineSurface
    names: List[str]  # every curve, in the order of deviations
    deviations: List[float]  # mm from each curve to the surface
    fit_error: float  # mm: the held boundary rows against their curves
    spans: int
    seconds: float
    kind: str  # Hermite, Coons, Gordon or Boundary
    report: object = None
    curves: list = field(default_factory=list)
    problem: object = None  # the last round's native SheetProblem, constraints applied (a drag updates it)
    options: object = None  # native SolveOptions for such an update (no time limit)
    trim: object = None  # a PdeSurface covers its parameter rectangle (a Sheet's outcome may be trimmed)

    def surface_of(self, poles):
        """The native surface of solved poles on the last round's space, as the recompute makes
        it (a drag's moved poles)."""
        return _surface_of(self.problem, poles)


def _surface_of(problem, poles):
    """The native surface of solved poles: a closed surface's seam (its two pole columns, tied to
    rounding by the solve) made one."""
    if problem.closed_v:
        poles = _closed_seam(poles, problem.space)
    return build(native().BSplineSurface, space=problem.space, poles=poles)


def kind_of(curves: Dict[str, object], u_curves: Sequence, v_curves: Sequence) -> str:
    """The conditions given: Hermite (derivative curves), Coons (sides), Gordon (a network), joined
    by '+'; Boundary for the two boundary curves alone."""
    kinds = []
    if curves.get("d0") is not None or curves.get("d1") is not None:
        kinds.append("Hermite")
    if curves.get("v0") is not None or curves.get("v1") is not None:
        kinds.append("Coons")
    if u_curves or v_curves:
        kinds.append("Gordon")
    return "+".join(kinds) or "Boundary"


def _named(message: str, labels: Dict[str, str]) -> str:
    """The core's roles (u0, d1, u-curve 2, ...) replaced by the curves' labels."""
    for role in sorted(labels, key=len, reverse=True):
        message = re.sub(rf"(?<![\w-]){re.escape(role)}(?![\w])", lambda _m, r=role: labels[r], message)
    return message


def _loop_paint(nat, a, points):
    return nat.PaintedCoefficient(nat.Region(loop=[(float(u), float(v)) for u, v in points]), float(a))


def boundary(nat, settings: PdeSurfaceSettings, curves: Dict[str, object],
             u_curves: Sequence[Tuple[float, object]] = (), v_curves: Sequence[Tuple[float, object]] = ()):
    """The native PdeBoundary: curves by role (native BSplineCurves, None where not given)."""
    b = nat.PdeBoundary()
    for role in ROLES:
        if curves.get(role) is not None:
            setattr(b, role, curves[role])
    b.magnitude0, b.magnitude1 = float(settings.magnitude0), float(settings.magnitude1)
    b.u_curves = [nat.IsoCurve(float(at), c) for at, c in u_curves]
    b.v_curves = [nat.IsoCurve(float(at), c) for at, c in v_curves]
    unit = nat.SplineSpace.uniform(1, 1, 1, 1)
    painted = [nat.PaintedCoefficient(nat.Region(u0, u1, v0, v1), float(a)) for a, u0, u1, v0, v1 in settings.regions]
    painted += [_loop_paint(nat, a, points) for a, points in settings.loops]
    b.a = nat.PdeCoefficient(a=float(settings.a), painted=painted, blend=float(settings.blend))
    b.a.validate(unit)
    return b


def _closed_seam(poles, space):
    """The poles with the first and last column of every row (v = 0 and v = 1) replaced by their
    mean: the solve ties them to rounding, OpenCASCADE sees a closed surface (one seam edge) only
    when they are equal."""
    import numpy as np

    nv = len(space.knots_v) - space.degree_v - 1
    grid = np.array(poles, dtype=float).reshape(-1, nv, 3)
    mean = 0.5 * (grid[:, 0, :] + grid[:, -1, :])
    grid[:, 0, :] = grid[:, -1, :] = mean
    return grid.reshape(-1, 3)


def _place(nat, specs, problem, result):
    """Constraint specs (Du & Qin's sculpting tools: points, normals, frozen regions, operators...)
    placed on the surface the boundary conditions alone give."""
    try:
        return constraint_specs.place(list(specs), nat.BSplineSurface(problem.space, result.poles), nat)
    except constraint_specs.ConstraintError as error:
        raise SheetError(str(error)) from error
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(advised(f"a constraint cannot be placed on the surface: {error}",
                                 "move its Location over the surface")) from error


def solve(settings: PdeSurfaceSettings, curves: Dict[str, object], labels: Dict[str, str],
          u_curves: Sequence[Tuple[float, object]] = (), v_curves: Sequence[Tuple[float, object]] = (),
          keep_going=None, constraints: Sequence = ()) -> PdeSurfaceOutcome:
    """The PDE surface through the curves (native BSplineCurves by role; labels name them and the
    Gordon curves, "u-curve 1", ... in messages), sculpted by the constraint specs (placed on the
    surface the boundary conditions alone give, then held with them). SheetError says what is wrong
    and what to do."""
    nat = native()
    started = time.monotonic()
    if curves.get("u0") is None or curves.get("u1") is None:
        raise SheetError("a PDE surface needs its two boundary curves (at u = 0 and u = 1): select them")
    try:
        b = boundary(nat, settings, curves, u_curves, v_curves)
    except nat.InvalidInput as error:
        raise SheetError(advised(f"PDE coefficient: {error}",
                                 "check PdeA, PdeRegions, PdeLoops and PdeBlend")) from error
    measured = [(labels.get(r, r), curves[r]) for r in ("u0", "u1", "v0", "v1") if curves.get(r) is not None]
    measured += [(labels.get(f"u-curve {k + 1}", f"u-curve {k + 1}"), c) for k, (_, c) in enumerate(u_curves)]
    measured += [(labels.get(f"v-curve {k + 1}", f"v-curve {k + 1}"), c) for k, (_, c) in enumerate(v_curves)]
    spans = max(1, int(settings.min_spans))
    placed = None
    while True:
        options = build(nat.PdeSurfaceOptions, degree=int(settings.degree), spans_u=spans, spans_v=spans,
                        tolerance=float(settings.tolerance))
        solve_options = build(nat.SolveOptions, fit_tolerance=0.25 * float(settings.tolerance))
        solve_options.time_limit = max(1e-3, float(settings.time_limit) - (time.monotonic() - started))
        if keep_going is not None:
            solve_options.keep_going = keep_going
        try:
            problem, fit_error = nat.pde_surface_problem(b, options)
            if constraints:
                # The boundary conditions' own surface: where the constraints are placed, and what
                # a frozen region keeps.
                free = nat.solve_sheet(problem, solve_options)
                if placed is None:
                    placed = _place(nat, constraints, problem, free)
                problem.initial_poles = free.poles
            if placed:
                terms = constraint_specs.native_terms(placed, problem.space, nat)
                terms.apply(problem)
                problem.fixed_poles = sorted(set(problem.fixed_poles) | set(terms.frozen_poles))
            result = nat.solve_sheet(problem, solve_options)
        except nat.InvalidInput as error:
            raise SheetError(advised(_named(str(error), labels), "check the curves and their roles (boundary, "
                                     "derivative, side or network curve)")) from error
        except nat.ResourceLimit as error:
            raise SheetError(advised(str(error), "use fewer spans or a looser tolerance")) from error
        except nat.Cancelled as error:
            raise SheetError(CANCELLED) from error
        surface = _surface_of(problem, result.poles)
        deviations = [float(d) for d in nat.max_deviations(surface, [c for _, c in measured], 200)]
        worst = max(deviations + [fit_error])
        if worst <= settings.tolerance or 2 * spans > settings.max_spans:
            break
        spans *= 2
    return PdeSurfaceOutcome(surface=surface, names=[n for n, _ in measured], deviations=deviations,
                             fit_error=float(fit_error), spans=spans, seconds=time.monotonic() - started,
                             kind=kind_of(curves, u_curves, v_curves), report=result.report, problem=problem,
                             options=build(nat.SolveOptions, fit_tolerance=0.25 * float(settings.tolerance)))


def check(settings: PdeSurfaceSettings) -> None:
    """SheetError naming the first setting out of range."""
    if not (settings.a > 0.0 and settings.a < float("inf")):
        raise SheetError(f"PdeA must be a number above 0 (got {settings.a}): set it above 0 (1: the same length "
                         "scale along u and v)")
    for label, m in (("Magnitude0", settings.magnitude0), ("Magnitude1", settings.magnitude1)):
        if not (abs(m) < float("inf")):
            raise SheetError(f"{label} must be finite (got {m}): set it to a number (1: the derivative curve's "
                             "own length)")
    if not 1 <= int(settings.min_spans) <= int(settings.max_spans) <= 512:
        raise SheetError(f"spans must satisfy 1 <= MinSpans <= MaxSpans <= 512 (got {settings.min_spans}, "
                         f"{settings.max_spans}): set MinSpans no larger than MaxSpans")
    if not (settings.tolerance > 0.0 and settings.tolerance < float("inf")):
        raise SheetError(f"Tolerance must be a positive length (got {settings.tolerance}): set it above 0 mm")
    for k, region in enumerate(settings.regions):
        a, u0, u1, v0, v1 = (float(x) for x in region)
        if not (0.0 < a < float("inf")):
            raise SheetError(f"PdeRegions: region {k + 1} paints a = {a}; give it a number above 0")
        if not (0.0 <= u0 < u1 <= 1.0 and 0.0 <= v0 < v1 <= 1.0):
            raise SheetError(f"PdeRegions: region {k + 1} spans u {u0}..{u1}, v {v0}..{v1}; give 0 <= u0 < u1 <= 1 "
                             "and 0 <= v0 < v1 <= 1")
    if not (0.0 <= settings.blend <= 0.5):
        raise SheetError(f"PdeBlend must be in [0, 0.5] (got {settings.blend}): 0 for a sharp border")
    nat = native() if settings.loops else None
    for k, (a, points) in enumerate(settings.loops):
        if not (0.0 < float(a) < float("inf")):
            raise SheetError(f"PdeLoops: loop {k + 1} paints a = {a}; give it a number above 0")
        if not all(0.0 <= float(x) <= 1.0 for point in points for x in point):
            raise SheetError(f"PdeLoops: loop {k + 1} leaves the domain; give u and v from 0 to 1")
        try:  # the core's check: at least three points enclosing an area, not crossing itself
            nat.PdeCoefficient(painted=[_loop_paint(nat, a, points)]).validate(nat.SplineSpace.uniform(1, 1, 1, 1))
        except nat.InvalidInput as error:
            raise SheetError(f"PdeLoops: loop {k + 1}: {str(error).split(': ', 1)[-1]}; draw it again") from error
    for k, region in enumerate(settings.materials):
        mass, damping, u0, u1, v0, v1 = (float(x) for x in region)
        if not (0.0 < mass < float("inf")):
            raise SheetError(f"MaterialRegions: region {k + 1} paints mass {mass}; give it a number above 0 (1: the "
                             "surface's own)")
        if not (0.0 <= damping < float("inf")):
            raise SheetError(f"MaterialRegions: region {k + 1} paints damping {damping}; give it a number from 0 "
                             "(none) up (1: critical)")
        if not (0.0 <= u0 < u1 <= 1.0 and 0.0 <= v0 < v1 <= 1.0):
            raise SheetError(f"MaterialRegions: region {k + 1} spans u {u0}..{u1}, v {v0}..{v1}; give "
                             "0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1")


def material_fields(nat, settings: PdeSurfaceSettings, mass: float, damping: float, mass_scale: float,
                    damping_scale: float):
    """The core's mass and damping densities: `mass` and the damping ratio `damping` where nothing
    is painted, each region's (mass, damping) inside it (blended by PdeBlend). The damping density
    is damping_scale * ratio * sqrt(mass): a ratio is the local motion's, so a region painted
    (m, z) everywhere is the surface with Mass m and Damping z. Densities are the relative numbers
    times mass_scale and damping_scale (the caller's, from the surface's stiffness)."""
    def field(base, values):
        painted = [nat.PaintedCoefficient(nat.Region(u0, u1, v0, v1), float(x))
                   for x, (_, _, u0, u1, v0, v1) in zip(values, settings.materials)]
        return nat.PdeCoefficient(a=float(base), painted=painted, blend=float(settings.blend))

    regions = settings.materials
    return (field(mass_scale * mass, [mass_scale * m for m, *_ in regions]),
            field(damping_scale * damping * math.sqrt(mass),
                  [damping_scale * z * math.sqrt(m) for m, z, *_ in regions]))


def labels_for(names: Dict[str, str], u_names: Sequence[str] = (), v_names: Sequence[str] = ()) -> Dict[str, str]:
    """Role -> label for messages: the roles' labels and the Gordon curves' ("u-curve 1", ...)."""
    out = dict(names)
    out.update({f"u-curve {k + 1}": n for k, n in enumerate(u_names)})
    out.update({f"v-curve {k + 1}": n for k, n in enumerate(v_names)})
    return out
