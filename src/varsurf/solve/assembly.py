# SPDX-License-Identifier: LGPL-2.1-or-later
"""Joined sheets into a shell or solid (Welch & Witkin sec. 5): each sheet trimmed to the loop of
the curves it shares with the others, the shared edges built once with a pcurve on every sheet.
No document and no GUI here.

A join curve is a 3D edge that several sheets contain. On each sheet its pre-image is found by
projecting it onto the solved surface; the native layer chains the pre-images of a sheet's join
curves into one closed loop and trims the sheet to the region inside.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Sequence

from varsurf.solve.errors import SheetError
from varsurf.solve.native import native
from varsurf.solve.shapes import part, shape_from_brep


class JoinGapError(SheetError):
    """A sheet farther from a join curve than the tolerance."""


@dataclass
class AssemblyOutcome:
    shape: object  # Part.Solid when the faces close, else a shell or compound
    closed: bool = False
    valid: bool = False
    max_tolerance: float = 0.0  # worst edge/vertex tolerance after sewing (mm)
    faces: int = 0
    free_edges: int = 0
    seam_gaps: List[float] = field(default_factory=list)  # per join curve: largest sheet-to-curve distance
    seam_curves: List[str] = field(default_factory=list)  # the curves of seam_gaps, in order
    # per join curve shared by two faces: the smallest and largest angle between the faces across
    # it (degrees; 180 is a tangent-continuous seam), sampled along the curve
    seam_angles: List[tuple] = field(default_factory=list)
    # per entry of seam_angles: where along the seam its smallest angle is, (x, y, z)
    seam_sharpest: List[tuple] = field(default_factory=list)
    # the solid's thickness WALL_DEPTH of its size inside its seams: the thinnest found (mm), where
    # (x, y, z), and at what depth (mm); inf when no seam is shared by two faces
    thinnest_wall: float = math.inf
    thinnest_wall_at: tuple = ()
    wall_depth: float = 0.0


def _loop_gap(surface) -> float:
    """How close pre-image ends must be to join: 1e-6 of the larger side of the domain."""
    return 1e-6 * max(surface.space.knots_u[-1] - surface.space.knots_u[0],
                      surface.space.knots_v[-1] - surface.space.knots_v[0])


def _closes(nat, surface, edges) -> bool:
    """Whether the edges' pre-images on the surface chain into one closed loop."""
    try:
        pre = [nat.project_curve(surface, nat.curve_from_edge_brep(e.exportBrepToString())).curve
               for _key, e in (item if isinstance(item, tuple) else (None, item) for item in edges)]
        nat.chain_loop(pre, _loop_gap(surface))
        return True
    except (nat.InvalidInput, nat.GeometryError):
        return False


def _closed_ends(face, edges, tolerance):
    """For a face closed around one direction whose join curves all lie on its two ends (a tube
    between two caps): (its two ends as edges, (largest distance, which end) per curve); else
    None."""
    surface = face.Surface
    u0, u1, v0, v1 = face.ParameterRange
    if surface.isUClosed() and not surface.isVClosed():
        ends = [surface.vIso(v).toShape(u0, u1) for v in (v0, v1)]
    elif surface.isVClosed() and not surface.isUClosed():
        ends = [surface.uIso(u).toShape(v0, v1) for u in (u0, u1)]
    else:
        return None
    found = []
    for item in edges:
        edge = item[1] if isinstance(item, tuple) else item
        points = edge.discretize(JOIN_SAMPLES)
        per_end = [max(end.distToShape(part().Vertex(p))[0] for p in points) for end in ends]
        which = min((0, 1), key=per_end.__getitem__)
        if per_end[which] > tolerance:
            return None
        found.append((per_end[which], which))
    return ends, found


def _end_pieces(end, edge):
    """The pieces of a closed sheet's end (a closed edge) between the ends of a join curve that
    lies on it: the whole end for a closed curve; two pieces for one across the end's closing
    point."""
    if edge.isClosed():
        return [end]
    curve, a, b = end.Curve, end.FirstParameter, end.LastParameter
    near = 1e-9 * (b - a)

    def readings(point):  # the closing point reads as either end of the range
        t = curve.parameter(point)
        return (a, b) if min(t - a, b - t) <= near else (t,)

    middle = curve.parameter(edge.valueAt(0.5 * (edge.FirstParameter + edge.LastParameter)))
    starts, stops = readings(edge.valueAt(edge.FirstParameter)), readings(edge.valueAt(edge.LastParameter))
    for t0 in starts:
        for t1 in stops:
            lo, hi = min(t0, t1), max(t0, t1)
            if lo < middle < hi:
                return [curve.toShape(lo, hi)]
    lo, hi = min(starts[0], stops[0]), max(starts[0], stops[0])  # across the closing point
    return [curve.toShape(hi, b), curve.toShape(a, lo)]


#: Points along a join curve at which a closed sheet's ends are checked to hold it.
JOIN_SAMPLES = 24


def _bounding(nat, surface, shared, own):
    """The own curves that close the sheet's loop with its shared ones. A curve with an end that
    meets no other curve's end (one across the sheet's interior, a closed one) does not bound it:
    it shapes the sheet but is not part of its loop."""
    gap = _loop_gap(surface)
    ends = {}
    for item in list(shared) + list(own):
        try:
            edge = item[1] if isinstance(item, tuple) else item
            pre = nat.project_curve(surface, nat.curve_from_edge_brep(edge.exportBrepToString())).curve
        except (nat.InvalidInput, nat.GeometryError):
            continue  # kept as it is: chaining the loop reports it
        ends[id(item)] = (pre.poles[0], pre.poles[-1])  # clamped: the first and last poles

    def dangling(item, keep):
        mine = ends.get(id(item))
        others = [ends[id(o)] for o in list(shared) + keep if o is not item and id(o) in ends]
        return mine is not None and any(all(math.dist(end, e) > gap for pair in others for e in pair)
                                        for end in mine)

    keep = list(own)
    while True:  # dropping a curve can leave another dangling
        loose = {id(item) for item in keep if dangling(item, keep)}
        if not loose:
            return keep
        keep = [item for item in keep if id(item) not in loose]


@dataclass
class _ClosedEnds:
    sheets: dict  # sheet number -> [(distance, which end)] per join curve of a closed sheet
    pieces: dict  # join curve key -> the pieces of that sheet's end it lies on


def _on_closed_ends(sheets, tolerance) -> _ClosedEnds:
    """The closed sheets whose join curves lie on their two ends, and the pieces of those ends
    that the other sheets are joined along instead of the curves: the closed sheet's face is then
    sewn to them along its own edges (the curves themselves, a sketch's arcs a hundredth of the
    tolerance off its ends, gave edges whose STEP re-read failed OCCT's check). A curve across
    an end's closing point is joined along two pieces."""
    found = _ClosedEnds({}, {})
    for number, entry in enumerate(sheets):
        edges = list(entry[2])
        closed = _closed_ends(entry[1], edges, tolerance) if edges else None
        if closed is None:
            continue
        ends, on = closed
        found.sheets[number] = on
        for item, (_gap, which) in zip(edges, on):
            found.pieces[_key(item)] = _end_pieces(ends[which], item[1] if isinstance(item, tuple) else item)
    return found


def _key(item):
    return item[0] if isinstance(item, tuple) else item.hashCode()


def _expanded(edges, pieces):
    """(curve key, join curve key, edge) of each join curve, the curves on a closed sheet's end
    replaced by the pieces of that end (curve keys (key, k) when there are two)."""
    for item in edges:
        key, edge = item if isinstance(item, tuple) else (item.hashCode(), item)
        found = pieces.get(key, [edge])
        for k, piece in enumerate(found):
            yield ((key, k) if len(found) > 1 else key), key, piece


def _ends_apart(edges) -> float:
    """How far (mm) an open curve's end is from the nearest other end (its own other end too), at most:
    what a loop that does not close lacks, in model units."""
    ends = [v.Point for e in edges if not e.isClosed() for v in e.Vertexes]
    apart = 0.0
    for i, p in enumerate(ends):
        apart = max(apart, min(((p - q).Length for j, q in enumerate(ends) if j != i), default=0.0))
    return apart


def build_solid(sheets: Sequence, tolerance: float) -> AssemblyOutcome:
    """Join sheets along their shared curves into a shell, a solid when it closes.

    sheets: [(label, Part.Face of the solved sheet, [join curves], [own curves])] — each
        sheet's join curves are those it shares with other sheets, as (key, Part.Edge) with one
        key per curve (or Part.Edge objects, identified by their hash); its own curves (optional)
        complete its loop when the join curves alone do not close one.
    tolerance: how far (mm) a sheet may pass from a join curve; the shared edges' tolerances
        are then set from the measured deviation.
    """
    nat = native()
    if not (tolerance > 0.0 and math.isfinite(tolerance)):
        raise SheetError(f"the tolerance must be a positive length (got {tolerance}): set the Solid's "
                         "Tolerance above 0 mm")
    if len(sheets) < 1:
        raise SheetError("a solid needs at least one sheet: link its Sheets")
    curves, index, gaps, joined, whole = [], {}, {}, [], []
    on_ends = _on_closed_ends(sheets, tolerance)
    for number, entry in enumerate(sheets):
        label, face, edges = entry[0], entry[1], list(entry[2])
        own = list(entry[3]) if len(entry) > 3 else []
        if not edges:
            raise SheetError(f"{label} shares no curve with the other sheets: nothing bounds it; give it "
                             "a curve of another of the Solid's Sheets, or take it out of the Solid")
        if number in on_ends.sheets:  # a tube between its join curves: its face as it is
            for item, (gap, _which) in zip(edges, on_ends.sheets[number]):
                gaps[_key(item)] = max(gaps.get(_key(item), 0.0), gap)
            whole.append(face)
            continue
        if any(_key(item) in on_ends.pieces for item in edges):
            # Joined along a closed sheet's end, which lies up to the tolerance outside the
            # curves this sheet was trimmed to: its whole surface, not its trimmed (u, v) box.
            face = part().Face(face.Surface)
        surface = nat.surface_from_face_brep(face.exportBrepToString())
        if own and not _closes(nat, surface, edges):
            # the shared curves alone do not close: its own ones on the loop complete it
            edges = edges + _bounding(nat, surface, edges, own)
        ids, pre_images, joined_edges = [], [], []
        for key, join, edge in _expanded(edges, on_ends.pieces):
            joined_edges.append(edge)
            if key not in index:
                index[key] = len(curves)
                curves.append(nat.curve_from_edge_brep(edge.exportBrepToString()))
            curve = curves[index[key]]
            try:
                # A curve may pass beyond a trimmed sheet's (u, v) box by the tolerance, as it may
                # pass beside the sheet.
                pre = nat.project_curve(surface, curve, tolerance=tolerance)
            except (nat.InvalidInput, nat.GeometryError) as error:
                raise SheetError(f"{label} does not reach a join curve: {error}; let the Sheet pass "
                                 "through every curve it shares with the other Sheets") from error
            if pre.max_distance > tolerance:
                raise JoinGapError(f"{label} passes {pre.max_distance:.3g} mm from a join curve "
                                   f"(more than the tolerance {tolerance:.3g} mm)")
            gaps[join] = max(gaps.get(join, 0.0), float(pre.max_distance))
            ids.append(index[key])
            pre_images.append(pre.curve)
        try:  # checked here too, so that the message names the sheet
            nat.chain_loop(pre_images, _loop_gap(surface))
        except nat.InvalidInput as error:
            apart = _ends_apart(joined_edges)
            where = (f"their ends are up to {apart:.3g} mm apart" if apart > tolerance
                     else "their ends meet in space but not on the sheet (around a seam?)")
            raise SheetError(f"{label}: its join curves do not close a loop: {where} ({error}); give the Sheet "
                             "the curves that close its loop") from error
        joined.append(nat.JoinedSheet(surface=surface, curves=ids, preimages=pre_images))
    try:
        result = nat.join_sheets(curves, joined, tolerance) if joined else None
        if whole:
            # A closed sheet's ends are not one loop in its parameters (an annulus around its
            # seam): its untrimmed face is sewn to the others' along its ends.
            faces = shape_from_brep(result.brep).Faces if result is not None else []
            result = nat.sew_faces_brep([f.exportBrepToString() for f in list(faces) + whole], tolerance)
    except (nat.InvalidInput, nat.GeometryError) as error:
        raise SheetError(str(error)) from error
    shape = shape_from_brep(result.brep)
    # An open shell has no walls: the measurement (projections on every seam) is left out.
    depth = WALL_DEPTH * shape.BoundBox.DiagonalLength if result.closed else None
    angles, sharpest, (wall, wall_at) = _seam_angles(shape, depth)
    return AssemblyOutcome(
        shape=shape,
        seam_angles=angles,
        seam_sharpest=sharpest,
        thinnest_wall=wall,
        thinnest_wall_at=wall_at,
        wall_depth=depth or 0.0,
        closed=bool(result.closed),
        valid=bool(result.valid),
        max_tolerance=float(result.max_tolerance),
        faces=int(result.faces),
        free_edges=int(result.free_edges),
        seam_gaps=list(gaps.values()),
        seam_curves=[str(key) for key in gaps],
    )


#: Points per shared edge at which the angle across the seam is measured.
SEAM_SAMPLES = 24


def _edge_uv(edge, faces):
    """For each of `faces` (the two sharing `edge`), a function t -> (u, v) on it: the edge's
    pcurves when they can be matched to the faces (exact and fast), else projection. Projecting
    every sample onto a B-spline surface cost 0.45 ms a point, most of a rounded box's rebuild."""
    reps = []
    for i in (0, 1):
        try:
            c2d, surface, placement, _first, _last = edge.curveOnSurface(i)
        except Exception:
            break
        if not placement.isIdentity():
            break
        reps.append((c2d, surface))
    lookups = []
    if len(reps) == 2:
        t = 0.5 * (edge.FirstParameter + edge.LastParameter)
        for face in faces:
            def gap(rep, face=face):
                uv = rep[0].value(t)
                return (rep[1].value(uv.x, uv.y) - face.Surface.value(uv.x, uv.y)).Length
            best = min(reps, key=gap)
            if gap(best) > 1e-9 * max(1.0, edge.BoundBox.DiagonalLength):
                lookups = []
                break
            lookups.append(lambda t, c2d=best[0]: (c2d.value(t).x, c2d.value(t).y))
    if len(lookups) != 2 or reps[0][1] is reps[1][1]:
        lookups = [lambda t, f=f: f.Surface.parameter(edge.valueAt(t)) for f in faces]
    return lookups


#: How far inside a seam its wall is measured, as a fraction of the solid's size (the pillow's
#: 0.47 mm: where its untrimmed sheets left a lip 0.006 mm thick).
WALL_DEPTH = 0.005
#: Every this many angle samples along a seam, the wall is measured too (up to six projections).
WALL_STRIDE = 2


def _surface_distance(face, point):
    u, v = face.Surface.parameter(point)
    return (face.Surface.value(u, v) - point).Length


def _across(face, other, point, normal, tangent, depth):
    """From the seam's ``point``, ``depth`` into ``face`` (across the seam in its tangent plane,
    onto its surface): how far that is from ``other``'s surface. inf if neither way stays on
    the face."""
    step = normal.cross(tangent)
    if step.Length == 0.0:
        return math.inf
    step.normalize()
    for direction in (step, -step):
        inside = point + direction * depth
        u, v = face.Surface.parameter(inside)
        on = face.Surface.value(u, v)
        # Where the surface ends at the seam (a tube's end) the nearest point is the seam itself:
        # that is no step into the face.
        if face.isPartOfDomain(u, v) and (on - inside).Length <= 0.5 * depth:
            return _surface_distance(other, on)
    return math.inf


def _wall(a, b, point, na, nb, tangent, depth):
    """The solid's thickness ``depth`` inside the seam of faces a and b at ``point``: from the point
    that far into either face, the distance to the other face's surface (the smaller). A wedge of
    angle w is depth sin(w) thick there; faces that curve toward each other beyond the seam (a
    lip) are thinner than their angle at the seam says."""
    return min(_across(a, b, point, na, tangent, depth), _across(b, a, point, nb, tangent, depth))


def _seam_angles(shape, depth):
    """(min, max) angle between the two faces across each edge they share, in degrees: 180 minus
    the angle between their outward normals, sampled along the edge; where each minimum is; and
    the thinnest wall ``depth`` inside the seams, (thickness, (x, y, z)), or (inf, ()) without a
    depth."""
    angles, sharpest = [], []
    wall, wall_at = math.inf, ()
    faces = shape.Faces
    owners = {}
    for i, f in enumerate(faces):
        for e in f.Edges:
            owners.setdefault(e.hashCode(), []).append(i)
    for e in shape.Edges:
        pair = owners.get(e.hashCode(), [])
        if len(pair) != 2:
            continue
        a, b = faces[pair[0]], faces[pair[1]]
        uv_a, uv_b = _edge_uv(e, (a, b))
        t0, t1 = e.FirstParameter, e.LastParameter
        values, places = [], []
        for k in range(1, SEAM_SAMPLES - 1):
            t = t0 + (t1 - t0) * k / (SEAM_SAMPLES - 1)
            na = a.normalAt(*uv_a(t))
            nb = b.normalAt(*uv_b(t))
            values.append(180.0 - math.degrees(na.getAngle(nb)))
            places.append(t)
            if depth is not None and (k % WALL_STRIDE == 1 or values[-1] == min(values)):  # and the sharpest
                p = e.valueAt(t)
                thickness = _wall(a, b, p, na, nb, e.tangentAt(t), depth)
                if thickness < wall:
                    wall, wall_at = thickness, (p.x, p.y, p.z)
        if values:
            angles.append((min(values), max(values)))
            p = e.valueAt(places[values.index(min(values))])
            sharpest.append((p.x, p.y, p.z))
    return angles, sharpest, (wall, wall_at)


#: A seam whose faces meet at less than this (degrees) is a knife edge: FreeCAD's booleans,
#: fillets and offsets fail on it without saying so (a pillow's rim at 0.6 to 2.1 degrees: 5 of
#: 14 half-space cuts right, a drilled hole with no common).
KNIFE_EDGE = 5.0
#: A hinge explains a knife edge whose smallest angle is this close (degrees) to the hinge's.
HINGE_MATCH = 1.0


def knife_edges(outcome: AssemblyOutcome, hinge_angles=()):
    """(smallest angle, (x, y, z) where it is) of each seam sharper than KNIFE_EDGE that no hinge
    asked for (a hinge at nearly that angle), sharpest first."""
    found = []
    for (low, _high), place in zip(outcome.seam_angles, outcome.seam_sharpest):
        if low < KNIFE_EDGE and not any(abs(low - h) <= HINGE_MATCH for h in hinge_angles):
            found.append((low, place))
    return sorted(found)
