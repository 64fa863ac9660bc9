# SPDX-License-Identifier: LGPL-2.1-or-later
"""The variational sheet as a computation, without a document.

``solve_sheet_on_face`` takes a Part face (the base surface and its boundary), Part edges (the
curves the sheet must pass through) and the sheet's settings, builds the native ``SheetProblem``
and returns the solved face together with what a user wants to know about it: how far each curve
is from the result (measured independently of the solver), the size of the B-spline, the solve
time and the constraint rank. It runs in stages: the base (its spline space and trim), the
curves' pre-images, the constraints, the solve with its refinement, and the measurement.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from types import SimpleNamespace
from typing import List, Optional, Sequence

import numpy

from varsurf.solve import constraints as constraint_specs
from varsurf.solve import boundary, continuity, energy, local_refinement, plane_fit, preimages, seams, shapes
from varsurf.solve.errors import BOUNDING_REMEDY, CANCELLED, SheetError, advised
from varsurf.solve.native import build, int_of, native
from varsurf.solve.outcome import SheetOutcome
from varsurf.solve.settings import DEVIATION_SAMPLES, FIT_TO_TOLERANCE, MAX_DEGREE, SheetSettings


def _close(a, b, tol=1e-9):
    return len(a) == len(b) and all(abs(x - y) <= tol * (1.0 + abs(x)) for x, y in zip(a, b))


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


def _spans(space) -> int:
    """Fewest polynomial spans of the space over its two directions."""
    return min(len(set(space.knots_u)) - 1, len(set(space.knots_v)) - 1)


@dataclass
class _Sheet:
    """What the stages find out about one sheet before it is solved."""

    settings: SheetSettings
    names: List[str]
    base: object = None  # native BSplineSurface of the base face
    trim: object = None  # native BaseTrim: the face's wires and orientation
    curves: list = None  # native CurveConstraints: the named curves, then a kept trim's edges
    targets: list = None  # the named curves' 3D curves
    placed: list = None  # placed constraint specs
    energy: object = None  # native ThinPlateWeights
    rest: object = None  # None, "base", or the native surface of an installed rest shape
    corners: list = None  # continuity.Corner: where two G1 joins ask for two tangent planes
    kept: object = None  # native Region the trim to a loop keeps (the energy acts there), or None
    seams: seams.Seams = seams.Seams()  # the directions the base closes in: one seam, not two sides


def _base(nat, face, settings):
    """Stage 1: the base face's surface and trim (SheetError if the face cannot carry a sheet)."""
    if getattr(face, "ShapeType", None) != "Face":
        raise SheetError("the base must be a face: link a face (FaceN) as Base")
    brep = face.exportBrepToString()
    try:
        base = nat.surface_from_face_brep(brep)
        trim = nat.BaseTrim(brep)  # the face's wires and orientation
        # To 1 %, which is all a collapsed face needs: Part's exact Area took 8 ms on a 16-span
        # B-spline square, more than the rest of this stage.
        area = nat.mass_properties(brep, 1e-2)[0]
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(advised(f"the base face cannot be used: {error}", "pick another face as Base")) from error
    extent = face.BoundBox.DiagonalLength
    if not (math.isfinite(extent) and extent > 0.0) or area < 1e-6 * extent ** 2:
        raise SheetError(f"the base face is degenerate: {area:.3g} mm² over a {extent:.3g} mm extent "
                         "(collapsed to a line or a point); pick a face that has an area")
    if settings.tolerance >= extent:
        raise SheetError(f"Tolerance {settings.tolerance:.3g} mm is not smaller than the model ({extent:.3g} mm "
                         "across): every curve would count as met; give a tolerance well below the model's size")
    return base, trim


def _constraints(nat, sheet, constraints):
    """Stage 3: the constraints placed on the base, refused where the trim does not keep them;
    a kept boundary's edges join the curves (after the named ones: outcome.problem.curves starts
    in curve_names order)."""
    # The solve elevates the base to the Degree setting; below 3 the curvature jumps at every knot.
    degree = max(sheet.settings.degree, min(sheet.base.space.degree_u, sheet.base.space.degree_v))
    g2 = [c.name for c in constraints if c.kind == "G2"]
    if g2 and degree < 3:
        raise SheetError(f"{', '.join(g2)}: G2 needs a sheet of degree 3 or more (this one has degree {degree}: its "
                         "curvature jumps at every knot line): raise the Sheet's Degree to 3, or join with G1")
    try:
        placed = constraint_specs.place(list(constraints), sheet.base, nat)
    except constraint_specs.ConstraintError as error:
        raise SheetError(str(error)) from error
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(advised(f"a constraint's location cannot be placed on the base face: {error}",
                                 "move its Location over the base face")) from error
    preimages.refuse_outside_trim(sheet.trim, [(n, c.preimage) for n, c in zip(sheet.names, sheet.curves)],
                                  placed, sheet.settings.tolerance)
    if sheet.settings.fix_boundary:
        sheet.curves = sheet.curves + preimages.kept_boundary(nat, sheet.trim)
    return placed


def _rest(nat, rest):
    if rest is None or (isinstance(rest, str) and rest == "base"):
        return rest
    try:
        return nat.surface_from_face_brep(rest.exportBrepToString())
    except (nat.InvalidInput, nat.GeometryError, AttributeError) as error:
        raise SheetError(advised(f"the installed rest shape cannot be used: {error}",
                                 "install the rest shape again, or set RestShape to Base")) from error


def _options(nat, settings, keep_going):
    """The native SolveOptions (the limits are set per solve, see _Budget)."""
    options = build(nat.SolveOptions)
    options.rank_tolerance = float(settings.rank_tolerance)
    options.fit_tolerance = FIT_TO_TOLERANCE * float(settings.tolerance)
    mode = settings.solve_mode
    options.mode = getattr(nat.SolveMode, "penalty" if mode == "PenaltyQR" else mode.lower())
    options.penalty_qr = mode == "PenaltyQR"
    if keep_going is not None:  # asked between iterative steps and refinement levels
        options.keep_going = keep_going
    options.memory_limit = settings.memory_bytes()
    return options


class _Budget:
    """Runs native solves on what is left of the sheet's time limit; their refusals as
    SheetErrors."""

    def __init__(self, nat, options, seconds):
        self.nat, self.options, self.seconds = nat, options, seconds
        self.deadline = time.monotonic() + seconds

    def run(self, solve, *args):
        nat = self.nat
        self.options.time_limit = self.deadline - time.monotonic()
        if self.options.time_limit <= 0.0:
            raise SheetError(f"the solve took longer than its time limit of {self.seconds:.3g} s; "
                             "raise the limit in the preferences, or use fewer spans or a looser tolerance")
        try:
            return solve(*args)
        except (nat.InvalidInput, nat.ResourceLimit) as error:
            raise SheetError(advised(str(error), "check the Sheet's Degree, spans, energy and constraints")) from error
        except nat.Cancelled as error:
            raise SheetError(CANCELLED) from error


def _problem(nat, sheet, spans):
    """The base refined to `spans` per direction, its space and the native problem on it."""
    settings = sheet.settings
    refined = nat.refine_surface(sheet.base, spans, spans, settings.degree)
    space = refined.space
    terms = constraint_specs.native_terms(sheet.placed, space, nat)
    closed = sheet.seams
    fixed = list(nat.boundary_pole_indices(space, closed.closed_u, closed.closed_v)) if settings.fix_boundary else []
    fixed = sorted(set(fixed) | set(terms.frozen_poles))
    problem = build(nat.SheetProblem, space=space, initial_poles=refined.poles, energy=sheet.energy, points=[],
                    curves=sheet.curves, fixed_poles=fixed, closed_u=closed.closed_u, closed_v=closed.closed_v)
    terms.apply(problem)
    pde = energy.pde_coefficient(nat, settings, space)
    if pde is not None:
        problem.pde = pde
    if sheet.kept is not None:
        problem.kept_region = sheet.kept
    # The core inflates along Su x Sv; a Reversed base face's outward normal is the opposite.
    problem.pressure = float(settings.pressure) * sheet.trim.normal_sign
    if sheet.rest == "base":
        problem.rest_poles = refined.poles
    elif sheet.rest is not None:
        problem.rest_poles = _rest_poles_in(sheet.rest, space, nat, spans, settings.degree)
    return space, problem


#: How far beyond the box of its base and curves a solved sheet's poles may reach, in sizes of
#: that box. A fair sheet's control net stays close to its inputs (a pillow's pressure moves its
#: poles well under one size); a curve rising steeply right beside a kept boundary is met exactly by
#: poles hundreds of sizes away (measured: a 10 mm rise 0.001 mm from the boundary of a 100 mm face,
#: poles 1.2e5 mm out, "OK" at 1e-12 mm), a surface nobody can use.
RUNAWAY_SIZES = 20.0


def _runaway(sheet, poles):
    """(how far the farthest pole reaches beyond the box of the base's poles and the curves' poles
    (mm), that box's diagonal, the pole's index), or None when every pole stays within
    RUNAWAY_SIZES diagonals of the box."""
    inputs = [numpy.asarray(sheet.base.poles, dtype=float)]
    inputs += [numpy.asarray(c.poles, dtype=float)[:, :3] for c in sheet.targets]
    points = numpy.vstack(inputs)
    low, high = points.min(axis=0), points.max(axis=0)
    size = max(float(numpy.linalg.norm(high - low)), sheet.settings.tolerance)
    poles = numpy.asarray(poles, dtype=float)
    beyond = numpy.maximum(low - poles, 0.0) + numpy.maximum(poles - high, 0.0)
    reach = numpy.linalg.norm(beyond, axis=1)
    worst = int(numpy.argmax(reach))
    if not numpy.isfinite(reach).all() or reach[worst] > RUNAWAY_SIZES * size:
        return float(reach[worst]), size, worst
    return None


def _refuse_runaway(sheet, space, spans, runaway, edges):
    """SheetError saying how far the sheet ran away, where, and the curve nearest that place."""
    reach, size, worst = runaway
    i, j = divmod(worst, int_of(space.nv))
    directions = ((space.knots_u, space.degree_u, i), (space.knots_v, space.degree_v, j))
    greville = [sum(k[a + 1:a + d + 1]) / d for k, d, a in directions]
    where = [float(x) for x in sheet.base.evaluate(greville[0], greville[1])]  # the base under that pole
    nearest = ""
    if edges:
        part = shapes.part()
        vertex = part.Vertex(shapes.vector(*where))
        distances = [(e.distToShape(vertex)[0], n) for e, n in zip(edges, sheet.names)]
        nearest = f" nearest to {min(distances)[1]}"
    raise SheetError(
        f"the sheet runs away: its poles reach {reach:.3g} mm beyond its base and curves (which span "
        f"{size:.3g} mm) near ({where[0]:.4g}, {where[1]:.4g}, {where[2]:.4g}){nearest}, even with {spans} spans "
        "per direction; a curve that rises steeply right beside a kept boundary asks for this: move it away "
        "from the boundary, turn FixBoundary off, or give the sheet more spans (MaxSpans)"
    )


def _deviations(nat, surface, targets, tolerance, stop_above=math.inf):
    """Each target's largest distance from the sheet. Points Newton finds within the tolerance skip
    the search over the whole sheet unless they could be the largest (the same figure, measured 12
    times faster on 64-span curves a sheet meets; on a sheet folded over itself it may overstate,
    never understate). A finite stop_above ends the measure at the first curve proven farther than it
    (the curves after it: infinity), for a round that is redone with more spans if any curve is."""
    return [float(d) for d in nat.max_deviations(surface, list(targets), DEVIATION_SAMPLES, accept=tolerance,
                                                 stop_above=stop_above)]


def _solve(nat, sheet, budget, keep_going, edges=()):
    """Stage 4: solve, doubling the spans (Uniform) while the curves are not met, or refining
    locally (Local). Returns (space, result, problem, local report or None, deviations or None)."""
    settings = sheet.settings
    tolerance = settings.tolerance
    spans = max(int(settings.min_spans), _spans(sheet.base.space))
    while True:
        if keep_going is not None and not keep_going():
            raise SheetError(CANCELLED)
        space, problem = _problem(nat, sheet, spans)
        if settings.refinement == "Local":
            hierarchy = local_refinement.hierarchy_options(nat, space, settings)
            solved = budget.run(nat.solve_hierarchical, problem, hierarchy, budget.options)
            local = solved.report
            runaway = _runaway(sheet, solved.poles)
            if runaway:
                _refuse_runaway(sheet, solved.space, spans * 2 ** local.depth, runaway, edges)
            if local.depth > 0:  # joint solves start from the outcome's problem: the finest level's
                problem = _problem(nat, sheet, spans * 2 ** local.depth)[1]
            result = SimpleNamespace(poles=solved.poles, report=solved.report.solve)
            return solved.space, result, problem, local, None  # what is left is measured and reported
        # A round that doubles the spans when it falls short may stop as soon as it must.
        budget.options.give_up_early = 2 * spans <= settings.max_spans
        try:
            result = budget.run(nat.solve_sheet, problem, budget.options)
        finally:
            budget.options.give_up_early = False  # the options live on in drags and joint solves
        if not result.report.converged and result.report.curvature_iterations == 0:
            # G2 iterations that stop short are reported (the joins' measured jumps), not refused.
            raise SheetError(
                f"the nonlinear terms (pressure, repellers, shape attractors) did not settle in "
                f"{result.report.iterations} steps (the last moved poles {result.report.last_step:.3g} mm); "
                "a pressure needs tension to hold it: give the sheet a Stretch, or lower the pressure"
            )
        conflict = float(result.report.conflict)
        deviations = None
        # A sheet that runs away is not met whatever its deviations say (measuring them on it can
        # take minutes): more spans may hold the curves calmly.
        runaway = _runaway(sheet, result.poles)
        if conflict <= tolerance and not runaway:
            # The fit is judged per curve by its RMS; a curve can still stray further somewhere.
            # A round that more spans would follow only needs to know whether some curve is off.
            last_round = 2 * spans > settings.max_spans
            deviations = _deviations(nat, build(nat.BSplineSurface, space=space, poles=result.poles), sheet.targets,
                                     tolerance, math.inf if last_round else tolerance)
            if max(deviations, default=0.0) <= tolerance:
                break
        if 2 * spans > settings.max_spans:
            break
        spans *= 2
    if conflict > tolerance:  # the more telling reason when both hold
        _refuse_conflict(nat, sheet, build(nat.BSplineSurface, space=space, poles=result.poles), conflict, spans)
    if runaway:
        _refuse_runaway(sheet, space, spans, runaway, edges)
    return space, result, problem, None, deviations


def _refuse_conflict(nat, sheet, surface, conflict, spans):
    """SheetError naming the curves and constraints that contradict each other."""
    tolerance = sheet.settings.tolerance
    deviations = _deviations(nat, surface, sheet.targets, tolerance)
    worst = [f"{n} ({d:.3g} mm)" for n, d in zip(sheet.names, deviations) if d > tolerance]
    for p in sheet.placed:  # point-like constraints contradict too (two targets at one place)
        unit = constraint_specs.KINDS[p.spec.kind][1]
        off = float(constraint_specs.residual(p, surface, sheet.base))
        if unit == "mm" and off > tolerance:
            worst.append(f"{p.spec.name} ({off:.3g} mm)")
    raise SheetError(
        f"the curves and constraints cannot all be met: they contradict each other by {conflict:.3g} mm "
        f"(RMS) even with {spans} spans per direction. Off by more than the tolerance: "
        f"{', '.join(worst) or 'none individually'}. Curves that cross must meet in space; "
        "curves close to a kept boundary must reach it smoothly (or turn FixBoundary off); "
        "points must not ask one place of the sheet to be in two."
        + "".join(f" {c.message()}." for c in sheet.corners)
    )


def _outcome(nat, sheet, solved, options, started):
    """Stage 5: the result face (bounded and oriented like the base), measured."""
    space, result, problem, local, deviations = solved
    surface = build(nat.BSplineSurface, space=space, poles=result.poles)
    try:
        shape = shapes.single_face(shapes.shape_from_binary(sheet.trim.face_binary(surface)))
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(advised(f"the sheet cannot be bounded like its base face: {error}",
                                 BOUNDING_REMEDY)) from error
    if deviations is None:
        deviations = _deviations(nat, surface, sheet.targets, sheet.settings.tolerance)
    placed = sheet.placed
    report = result.report
    options.keep_going = None  # the outcome's options serve later solves (joint, drag)
    options.time_limit = sheet.settings.time_seconds()  # each later solve gets the whole limit again
    return SheetOutcome(
        shape=shape,
        surface=surface,
        curve_names=list(sheet.names),
        max_deviations=deviations,
        pole_count_u=int_of(space.nu),
        pole_count_v=int_of(space.nv),
        degree_u=int(space.degree_u),
        degree_v=int(space.degree_v),
        # Local: the whole hierarchical solve (every refinement round), as a recompute feels it.
        solve_seconds=float(local.total_seconds if local is not None else report.total_seconds),
        total_seconds=time.perf_counter() - started,
        constraint_rank=int(report.constraint_rank),
        unknowns=int(report.unknowns),
        constraint_names=[p.spec.name for p in placed],
        constraint_residuals=[float(constraint_specs.residual(p, surface, sheet.base)) for p in placed],
        constraint_units=[constraint_specs.KINDS[p.spec.kind][1] for p in placed],
        iterations=int(report.iterations),
        # G2 steps that stop short are measured and reported, not a failed nonlinear solve.
        converged=bool(report.converged) or int(report.curvature_iterations) > 0,
        curvature_iterations=int(report.curvature_iterations),
        curvature_jump=float(report.curvature_jump),
        report=report,
        solve_mode=local_refinement.mode_used(report, local),
        lcurve_residuals=[float(x) for x in report.lcurve.residual],
        lcurve_norms=[float(x) for x in report.lcurve.solution_norm],
        lcurve_corner=int(report.lcurve.corner),
        refinement_depth=int(local.depth) if local is not None else 0,
        degrees_of_freedom=int(local.dofs) if local is not None else int(space.size()),
        refinement_met=bool(local.met) if local is not None else True,
        refined_spans=[(b.level, b.u0, b.u1, b.v0, b.v1) for b in local.refined] if local is not None else [],
        problem=problem,
        options=options,
        trim=sheet.trim,
        joins=_joins(shape, placed),
        corners=sheet.corners,
    )


def _joins(shape, placed):
    """The continuity of the result along each G0 (to its edge), G1 and G2 (to its reference face)."""
    joins = constraint_specs.JOIN_KINDS
    return [continuity.measure(p.spec.name, shape, p.spec.edge, p.spec.reference if p.spec.kind in joins else None)
            for p in placed if p.spec.kind == "G0" or p.spec.kind in joins]


def _names_and_projections(edges, names, projections):
    if names is None:
        names = [f"Edge{i + 1}" for i in range(len(edges))]
    names = [str(n) for n in names]
    if len(names) != len(edges):
        raise SheetError(f"{len(edges)} edges but {len(names)} names")
    projections = [None] * len(edges) if projections is None else list(projections)
    if len(projections) != len(edges):
        raise SheetError(f"{len(edges)} edges but {len(projections)} projection directions")
    return names, projections


def solve_sheet_on_face(
    face,
    edges: Sequence,
    settings: Optional[SheetSettings] = None,
    *,
    names: Optional[Sequence[str]] = None,
    projections: Optional[Sequence] = None,
    constraints: Sequence = (),
    rest=None,
    keep_going=None,
    **changes,
) -> SheetOutcome:
    """Solve the variational sheet over ``face`` that passes through ``edges``.

    face: a Part.Face (any surface type; non-B-spline surfaces are converted to NURBS, and the
        surface is cut to the face's parameter bounds). Its poles are the start shape and, with
        ``fix_boundary``, its boundary poles are held so the sheet keeps the base face's boundary.
    edges: Part.Edge objects the sheet must contain; each is projected onto the base face to find
        its pre-image, so each must lie over the face.
    settings: a SheetSettings (energy, tolerance, degree, spans, solve mode, refinement, limits;
        defaults: a thin plate at 0.01 mm); keyword ``changes`` replace some of its fields
        (``stretch=1.0, tolerance=0.001``). Curves that contradict each other by more than the
        tolerance have the spans doubled up to ``max_spans``; a conflict that survives refinement
        (curves crossing at different heights, a curve the fixed boundary cannot reach) is an
        error naming the curves.
    names: one label per edge for messages and reports ("Sketch001:Edge2").
    projections: one entry per edge: None projects the edge orthogonally onto the base face (to
        its closest points), an (x, y, z) direction projects it along that direction (a sketch
        seen along its normal). Omitted: every edge orthogonally.
    constraints: ConstraintSpec objects (varsurf.solve.constraints): point, tangent, normal,
        point-in-plane and point-on-line constraints, attractors, directors, frozen regions.
    rest: None (pure fairness), "base" (the base face is the rest shape: the energy acts on the
        displacement from it, so edits keep its detail), or a Part face whose B-spline has the
        sheet's own spline space (an installed rest shape).
    keep_going: a callable asked between steps; False cancels the solve.

    Raises SheetError (a ValueError) naming the curve or parameter at fault, and lets the
    extension's SolveFailure / GeometryError through for numerical or kernel failures.
    """
    settings = (settings or SheetSettings()).changed(**changes)
    return _solve_on(face, list(edges), settings, True, dict(names=names, projections=projections,
                                                             constraints=constraints, rest=rest,
                                                             keep_going=keep_going))


def _solve_on(face, edges, settings, has_base, inputs):
    """The stages, and the trim to a loop of the curves when ``settings.trim`` asks for one."""
    names, projections = _names_and_projections(edges, inputs.get("names"), inputs.get("projections"))
    settings.check()
    loop = boundary.loop_for(edges, names, settings, has_base)
    outcome = _stages(face, edges, settings, names, projections, inputs.get("constraints", ()),
                      inputs.get("rest"), inputs.get("keep_going"), loop)
    if loop:
        outcome.shape = boundary.trimmed_to_loop("the sheet", outcome.shape, edges, loop, settings.tolerance)
        outcome.boundary_curves = [names[i] for i in loop]
    return outcome


def _kept_region(nat, sheet, loop):
    """The region a trim to the curves ``loop`` keeps: the energy acts there only, so the overhang
    of the rectangle the sheet is solved on does not pull on the kept shape."""
    u0, u1, v0, v1 = sheet.base.space.domain()
    polygon = [[min(max(u, u0), u1), min(max(v, v0), v1)]
               for u, v in boundary.kept_polygon([sheet.curves[i].preimage for i in loop])]
    return nat.Region(loop=polygon)


def _stages(face, edges, settings, names, projections, constraints, rest, keep_going, loop=None):
    """Base, pre-images, constraints, energy, solve with refinement, and the measured outcome
    (with the energy on the region the trim to ``loop`` keeps)."""
    nat = native()
    started = time.perf_counter()
    sheet = _Sheet(settings=settings, names=names)
    sheet.base, sheet.trim = _base(nat, face, settings)
    sheet.seams = seams.of_base(nat, sheet.base)
    sheet.curves, sheet.targets, pieces = preimages.curve_constraints(nat, sheet.base, edges, names, projections,
                                                                      settings, closed=sheet.seams.any)
    if loop:
        sheet.kept = _kept_region(nat, sheet, loop)
    sheet.curves = sheet.curves + pieces  # after the named curves, as a kept boundary's edges
    sheet.placed = _constraints(nat, sheet, constraints)
    sheet.corners = continuity.incompatible_corners(
        [(p.spec.name, p.spec.edge, p.spec.reference) for p in sheet.placed
         if p.spec.kind in constraint_specs.JOIN_KINDS],
        settings.tolerance)
    g2_corners = continuity.curvature_corners(
        [(p.spec.name, p.spec.edge, p.spec.reference) for p in sheet.placed if p.spec.kind == "G2"],
        settings.tolerance)
    if g2_corners:  # refused before the solve: its Newton steps would fold the sheet there
        raise SheetError("G2 cannot hold where two G2 joins meet with different curvatures: "
                         + "; ".join(c.message() for c in g2_corners))
    sheet.rest = _rest(nat, rest)
    if settings.energy == "PDE":  # the problem's pde replaces the thin plate (_problem)
        sheet.energy = nat.ThinPlateWeights()
    else:
        sheet.energy = energy.energy_weights(nat, settings.stretch, settings.bend, settings.stretch_tensor,
                                             settings.bend_tensor, energy.parameter_lengths(sheet.base))
    # Pre-images and constraint (u, v) stay valid on every refinement: knot insertion keeps the
    # parametrization.
    options = _options(nat, settings, keep_going)
    solved = _solve(nat, sheet, _Budget(nat, options, settings.time_seconds()), keep_going, edges)
    return _outcome(nat, sheet, solved, options, started)


def solve_sheet_from_curves(edges: Sequence, settings: Optional[SheetSettings] = None, **options) -> SheetOutcome:
    """``solve_sheet_on_face`` on the best-fit plane of the curves (``plane_face_for_curves``),
    with a free boundary: the sheet is shaped by the curves and its energy alone. With
    ``trim`` Automatic (the default) or Loop and a closed loop among the curves, the result is
    bounded by that loop (``boundary_curves`` names its curves)."""
    settings = (settings or SheetSettings()).changed(
        fix_boundary=False, **{k: options.pop(k) for k in list(options) if k in _SETTING_NAMES})
    degree = settings.degree
    if not (isinstance(degree, int) and 2 <= degree <= MAX_DEGREE):
        raise SheetError(f"Degree must be an integer in 2..{MAX_DEGREE} (got {degree})")
    unknown = set(options) - _INPUT_NAMES
    if unknown:
        raise TypeError(f"solve_sheet_from_curves() got unexpected keyword arguments: {', '.join(sorted(unknown))}")
    edges = list(edges)
    face = plane_fit.plane_face_for_curves(edges, spans=int(settings.min_spans), degree=degree)
    return _solve_on(face, edges, settings, False, options)


_SETTING_NAMES = frozenset(f.name for f in SheetSettings.__dataclass_fields__.values())
_INPUT_NAMES = frozenset(("names", "projections", "constraints", "rest", "keep_going"))
