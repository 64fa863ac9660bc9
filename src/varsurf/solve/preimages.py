# SPDX-License-Identifier: LGPL-2.1-or-later
"""Where a sheet's curves and constraints lie on its base face: each curve's pre-image (its
curve in the base's parameters), and the refusals that name a curve the sheet cannot take."""

from __future__ import annotations

from varsurf.solve import constraints as constraint_specs
from varsurf.solve.errors import SheetError, advised
from varsurf.solve.native import build, native


def canonical_direction(nat, curve):
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


def projection_failure(name, direction, error):
    """The message of a curve whose pre-image cannot be found, naming the real cause."""
    if direction is not None:
        seen = tuple(round(c, 6) for c in direction)
        if "beyond the face" in error:
            return (f"{name} runs beyond the base face seen along {seen} (the Sheet's Projection): {error}; "
                    "move the curve over the face, or project it another way")
        return (f"{name} cannot be projected onto the base face along {seen}: {error}; set the Sheet's "
                "Projection to another direction, or to Normal")
    if "crosses the seam of the closed face" in error:  # on the face, but around it
        return f"{name} goes around the closed base face across its seam: {error}"
    if "jumps" in error:
        return (f"{name}'s orthogonal projection onto the base face jumps (the curve lies too far from a curved "
                f"base for its nearest points to follow it): {error}. Project it along a direction instead: set "
                "the Sheet's Projection to Direction (or Automatic, for a sketch facing the base)")
    if "along the sheet's normal" in error:  # over the face, but seen edge-on
        return f"{name} cannot be projected onto the base face: {error}"
    return (f"{name} runs beyond the base face (it must lie over the face to be projected onto it): {error}; "
            "shorten the curve to end over the face, or pick a base face that covers it")


def _project(nat, base, curve, name, direction, beyond):
    """The pre-image of one curve, or SheetError naming it (also when it passes more than
    ``beyond`` mm beyond the base face)."""
    try:
        return nat.project_curve(base, curve, direction=direction, tolerance=beyond)
    except nat.InvalidInput as error:
        raise SheetError(projection_failure(name, direction, str(error))) from error
    except nat.GeometryError as error:
        raise SheetError(advised(f"{name} cannot be projected onto the base face: {error}",
                                 "move the curve nearer the face, or pick another base face")) from error


def _pieces(nat, base, curve, name, direction, closed, beyond):
    """[(pre-image, target piece)] of one curve: itself, or on a closed base (a sheet around a
    cylinder) its pieces between the points where it crosses the seam, each with a pre-image
    ending on the seam."""
    try:
        return [(_project(nat, base, curve, name, direction, beyond), curve)]
    except SheetError as error:
        cause = error.__cause__
        if not (closed and direction is None and isinstance(cause, nat.InvalidInput)
                and "crosses the seam" in str(cause)):
            raise
    try:
        pieces = list(nat.split_at_seams(base, curve))
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(advised(f"{name} cannot be cut where it crosses the base face's seam: {error}",
                                 "split the curve at the seam yourself")) from error
    return [(_project(nat, base, piece, name, direction, beyond), piece) for piece in pieces]


def curve_constraints(nat, base, edges, names, projections, settings, closed=False):
    """(native CurveConstraints, target curves, more CurveConstraints) of the named edges on the
    base: one constraint and one target per edge, in their order, and after them the further
    pieces of the curves that cross the seam of a closed base (``closed``), which the sheet must
    contain too. The targets are the whole curves (what the result is measured against)."""
    exact = set(settings.exact_curves)
    constraints, targets, more = [], [], []
    # A curve on the base face's boundary may pass beyond it by a hundredth of the tolerance (a
    # tube's end section, which the base's smooth section follows within 1e-7 of its length); its
    # pre-image is then on the boundary. The native default, 1e-6 mm, is the floor.
    beyond = max(1e-6, 1e-2 * settings.tolerance)
    for edge, name, direction in zip(edges, names, projections):
        if getattr(edge, "ShapeType", None) != "Edge":
            raise SheetError(f"{name} is not an edge: link an edge (EdgeN) of the object as a curve")
        try:
            curve = canonical_direction(nat, nat.curve_from_edge_brep(edge.exportBrepToString()))
        except (nat.InvalidInput, nat.GeometryError) as error:
            raise SheetError(f"{name} cannot be converted to a B-spline curve: {error}; remove it from the "
                             "sheet's Curves, or redraw it (a point or a zero-length edge is no curve)") from error
        pieces = _pieces(nat, base, curve, name, direction, closed, beyond)
        for pre, piece in pieces:
            # Where the curve's foot point is on the face's boundary, a kept boundary cannot move to
            # it (the solver sees those samples on fixed poles only): say so instead of refining in
            # vain.
            if settings.fix_boundary and pre.boundary_distance > settings.tolerance:
                x, y, z = (float(c) for c in piece.evaluate(pre.boundary_t))
                raise SheetError(
                    f"{name} is {pre.boundary_distance:.3g} mm from the base face where it reaches the face's "
                    f"kept boundary (at ({x:.4g}, {y:.4g}, {z:.4g})): the kept boundary cannot move "
                    "there; let the curve meet the boundary, or turn FixBoundary off"
                )
        # The pieces share the curve's weight by their parameter spans (a curve's samples share it).
        span = curve.last() - curve.first()
        held = [build(nat.CurveConstraint, preimage=pre.curve, target=piece,
                      weight=(piece.last() - piece.first()) / span, exact=name in exact) for pre, piece in pieces]
        constraints.append(held[0])
        more.extend(held[1:])
        targets.append(curve)
    return constraints, targets, more


def kept_boundary(nat, trim):
    """CurveConstraints holding a (trimmed) base face's own edges, not only its rectangle's."""
    try:
        held = trim.boundary()
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(advised(f"the base face's boundary cannot be kept: {error}", "turn FixBoundary off"))\
            from error
    return [build(nat.CurveConstraint, preimage=b.preimage, target=b.target, weight=1.0) for b in held]


def refuse_outside_trim(trim, preimages, placed, tolerance):
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
