# SPDX-License-Identifier: LGPL-2.1-or-later
"""Sheets, their shared curves and hinges solved as one system (Welch & Witkin sec. 5), without
a document.

Each sheet brings the problem of its own solve (``SheetOutcome.problem``: space, energy, its own
constraints, each curve's pre-image on it). Curves shared by several sheets, variational curves
and hinge curves become joins of the joint system; a variational curve's poles are unknowns of it;
a hinge holds the angle between two sheets across a join (see _native.solve_model).
"""

from __future__ import annotations

import copy
import math
import re
from dataclasses import dataclass
from typing import Dict, List, Sequence

from varsurf.solve.errors import BOUNDING_REMEDY, CANCELLED, SheetError, advised
from varsurf.solve.native import build, native
from varsurf.solve.shapes import part_curve, shape_from_brep, single_face
from varsurf.solve.space_curve import VariationalCurve

#: A hinge farther than this (degrees) from its angle anywhere is a failure, not a result.
HINGE_FAILURE = 1.0
#: The hinges' iteration stops when no aimed bisector turns by more (radians, 0.006 degrees): an
#: order below the angle a hinge must hold (0.05 degrees). Tighter, a penalty solve's own
#: tolerance shows as noise in the turns: a pair tilted 15 degrees still turned by 7e-5 rad after
#: 40 iterations.
HINGE_SETTLED = 1e-4
#: At most this many hinge iterations (a pair leaning 15 degrees settles in 39; each is one
#: factorization, and a long one can be cancelled from the progress indicator).
HINGE_ITERATIONS = 80


@dataclass
class JointSheet:
    label: str
    outcome: object  # SheetOutcome of the sheet's own solve
    keys: List[str]  # one key per curve, in outcome.curve_names order (equal keys: the same curve)


@dataclass
class HingeSpec:
    name: str
    key: str  # the curve
    sheet_a: str  # labels
    sheet_b: str
    angle: float  # degrees, (0, 180]; 180: tangent-continuous


@dataclass
class JointOutcome:
    faces: List[object]  # Part.Face per sheet, in input order
    curve_edges: Dict[str, object]  # key -> Part.Edge of each variational curve as solved
    join_gaps: List[float]  # per join: largest sheet-to-curve distance (mm)
    hinge_angles: List[tuple]  # per hinge: (min, max, max error) in degrees
    summary: str = ""  # what was solved, the iterations and the time


def _loop_sides(nat, preimages: Dict[str, object], gap: float) -> Dict[str, int]:
    """+1 / -1 per key: the side of its pre-image the sheet's loop encloses; {} if no loop."""
    keys = list(preimages)
    try:
        loop = nat.chain_loop([preimages[k] for k in keys], gap)
    except nat.InvalidInput:
        return {}
    return {keys[step.curve]: int(step.inside) for step in loop.steps}


def _domain_side(space, preimage) -> int:
    """+1 / -1: the side of a pre-image along the domain's edge (a closed sheet's end: a ring at
    the end of a tube) on which the domain lies; 0 for a curve with the domain on both sides."""
    t0, t1 = preimage.knots[0], preimage.knots[-1]
    u0, u1, v0, v1 = space.knots_u[0], space.knots_u[-1], space.knots_v[0], space.knots_v[-1]
    su, sv = u1 - u0, v1 - v0
    votes = 0
    for k in (1, 2, 3):  # three places along it, so an end touching a corner does not decide
        t = t0 + (t1 - t0) * k / 4.0
        a, b = preimage.evaluate(t - 1e-4 * (t1 - t0)), preimage.evaluate(t + 1e-4 * (t1 - t0))
        du, dv = (b[0] - a[0]) / su, (b[1] - a[1]) / sv  # in domain sizes: both directions alike
        norm = math.hypot(du, dv)
        if norm == 0.0:
            continue
        mid = preimage.evaluate(t)
        step = 1e-3 / norm  # a thousandth of the domain to the left (+) and to the right (-)
        inside = [u0 < mid[0] - sign * dv * step * su < u1 and v0 < mid[1] + sign * du * step * sv < v1
                  for sign in (1, -1)]
        if inside[0] != inside[1]:
            votes += 1 if inside[0] else -1
    return (votes > 0) - (votes < 0)


def solve_joint(sheets: Sequence[JointSheet], variational: Dict[str, VariationalCurve],
                hinges: Sequence[HingeSpec], keep_going=None) -> JointOutcome:
    nat = native()
    if not sheets:
        raise SheetError("no sheets to solve")
    labels = [s.label for s in sheets]
    counts: Dict[str, int] = {}
    for s in sheets:
        if s.outcome is None or s.outcome.problem is None:
            raise SheetError(f"{s.label} has no solve to join: recompute it first")
        if len(s.keys) != len(s.outcome.curve_names):
            raise SheetError(f"{s.label}: {len(s.keys)} curve keys for {len(s.outcome.curve_names)} curves")
        for k in set(s.keys):
            counts[k] = counts.get(k, 0) + 1
    for key in variational:
        if key not in counts:
            raise SheetError(f"the variational curve {key} is not a curve of any of the sheets")
    joined = {k for k, n in counts.items() if n >= 2} | set(variational) | {h.key for h in hinges}

    curves, index = [], {}
    joins = []
    problems = []
    for i, s in enumerate(sheets):
        problem = copy.copy(s.outcome.problem)
        named = len(s.keys)
        # The sheet's problem lists its named curves first (s.keys' order), then the curves of its
        # own making: the base face's trimmed edges it keeps, G0 and G1 incidences. Those stay its
        # own constraints; only named curves shared or variational become joins.
        listed = list(s.outcome.problem.curves)
        own, mine = [], {}
        for key, constraint in zip(s.keys, listed[:named]):
            if key not in joined:
                own.append(constraint)
                continue
            mine[key] = constraint
            if key not in index:
                index[key] = len(curves)
                curves.append(variational[key].native(nat) if key in variational
                              else _fixed_curve(nat, constraint.target))
        problem.curves = own + listed[named:]
        problems.append(problem)
        space = problem.space
        gap = 1e-6 * max(space.knots_u[-1] - space.knots_u[0], space.knots_v[-1] - space.knots_v[0])
        sides = _loop_sides(nat, {k: c.preimage for k, c in mine.items()}, gap)
        if not sides:  # the shared curves alone do not close: the sheet's own ones complete it
            every = dict(zip(s.keys, s.outcome.problem.curves))
            sides = _loop_sides(nat, {k: c.preimage for k, c in every.items()}, gap)
        for key, constraint in mine.items():
            if key not in sides:  # no loop says it: a curve along the domain's edge (a tube's end)
                sides[key] = _domain_side(space, constraint.preimage)
            join = nat.Join()
            join.sheet, join.curve = i, index[key]
            join.preimage = constraint.preimage
            join.exact = bool(constraint.exact)
            join.side = sides.get(key, 0)
            joins.append(join)

    native_hinges = []
    for h in hinges:
        if not (0.0 < h.angle <= 180.0) or not math.isfinite(h.angle):
            raise SheetError(f"{h.name}: the angle must be in (0, 180] degrees (got {h.angle}): set the "
                             "Hinge's Angle (180: smooth)")
        ends = []
        for label in (h.sheet_a, h.sheet_b):
            if label not in labels:
                raise SheetError(f"{h.name}: {label} is not one of the Solid's sheets: link two of the "
                                 "Solid's Sheets as the Hinge's Sheets")
            ends.append(labels.index(label))
        if ends[0] == ends[1]:
            raise SheetError(f"{h.name}: a hinge needs two different sheets: link the two Sheets that meet at "
                             "its curve")
        for end in ends:
            if h.key not in sheets[end].keys:
                raise SheetError(f"{h.name}: {h.key} is not a curve of {labels[end]}: a hinge needs "
                                 "a curve both sheets share; link one of those as its Curve")
            join = next(j for j in joins if j.sheet == end and j.curve == index[h.key])
            if join.side == 0:
                raise SheetError(f"{h.name}: {labels[end]}'s curves do not close a loop and the hinge's curve "
                                 "does not run along its edge, so it has no side of the curve: add the curves "
                                 "that bound it to the Sheet")
        hinge = nat.Hinge()
        hinge.curve, hinge.sheet_a, hinge.sheet_b = index[h.key], ends[0], ends[1]
        hinge.angle = math.radians(h.angle)
        native_hinges.append(hinge)

    model_problem = nat.ModelProblem()
    model_problem.sheets = problems
    model_problem.curves = curves
    model_problem.joins = joins
    model_problem.hinges = native_hinges
    model_problem.hinge_tolerance = HINGE_SETTLED
    model_problem.hinge_iterations = HINGE_ITERATIONS
    # The first sheet's mode and rank tolerance; the joins as tight as the tightest sheet's curves.
    options = copy.copy(sheets[0].outcome.options)
    options.fit_tolerance = min(float(s.outcome.options.fit_tolerance) for s in sheets)
    options.keep_going = keep_going
    try:
        result = nat.solve_model(model_problem, options)
    except (nat.InvalidInput, nat.ResourceLimit) as error:
        raise SheetError(advised(_named(str(error), labels, list(index), hinges),
                                 "check the Solid's Sheets, Hinges and shared curves")) from error
    except nat.Cancelled as error:
        raise SheetError(CANCELLED) from error

    faces = []
    for s, problem, poles in zip(sheets, problems, result.sheet_poles):
        surface = build(nat.BSplineSurface, space=problem.space, poles=poles)
        trim = getattr(s.outcome, "trim", None)
        try:  # bounded and oriented like the sheet's base face, as its own result
            brep = trim.face_brep(surface) if trim is not None else nat.face_brep(surface)
        except (nat.InvalidInput, nat.GeometryError) as error:
            raise SheetError(advised(f"{s.label}: the jointly solved sheet cannot be bounded like its base "
                                     f"face: {error}", BOUNDING_REMEDY)) from error
        faces.append(single_face(shape_from_brep(brep)))
    edges = {}
    for key, i in index.items():
        if key not in variational:
            continue  # a fixed curve stays the user's edge (exactly, arcs included)
        solved = build(nat.BSplineCurve, degree=curves[i].start.degree, knots=list(curves[i].start.knots),
                       poles=result.curve_poles[i])
        edges[key] = part_curve(solved).toShape()
    rep = result.report
    angles = [(math.degrees(r.min_angle), math.degrees(r.max_angle), math.degrees(r.max_error))
              for r in rep.hinges]
    summary = (f"joint solve of {len(sheets)} sheets, {len(curves)} join curves "
               f"({len(variational)} variational), {len(hinges)} hinges in {rep.hinge_iterations} "
               f"iterations, {rep.total_seconds:.2f} s")
    if not rep.converged:
        summary += f"; the hinges' aims still turned by {math.degrees(rep.last_turn):.2g} degrees"
    for h, (_lo, _hi, error) in zip(hinges, angles):
        if error > HINGE_FAILURE:  # not a seam a little off, but sheets folded away: build nothing
            raise SheetError(
                f"{h.name}: the sheets miss the hinge's {h.angle:.4g} degrees by up to {error:.3g} degrees "
                f"({summary}): let the curves that meet the seam at its ends leave it at the hinge's "
                "angle")
    return JointOutcome(faces=faces, curve_edges=edges, join_gaps=list(rep.join_gaps),
                        hinge_angles=angles, summary=summary)


def _fixed_curve(nat, target):
    curve = nat.SpaceCurve()
    curve.start = target
    curve.variational = False
    return curve


def _named(message: str, labels, keys, hinges) -> str:
    """The core names sheets, curves and hinges by index: say which ones."""
    def by_index(names):
        return lambda m: names[int(m.group(1))] if int(m.group(1)) < len(names) else m.group(0)

    message = re.sub(r"\bsheet (\d+)", by_index(labels), message)
    message = re.sub(r"\bspace curve (\d+)", by_index(keys), message)
    return re.sub(r"\bhinge (\d+)", by_index([h.name for h in hinges]), message)
