# SPDX-License-Identifier: LGPL-2.1-or-later
"""How well a sheet joins a neighbouring face along an edge, measured on the two faces (OCCT
evaluates them: independent of the solver, which only knows its own samples).

At points along the edge, each face's foot point is found; there:
- the gap is the distance between the two faces' points (without a neighbour: from the edge to
  the sheet);
- the angle is between the two tangent planes (G1: 0);
- the curvature jump is the difference of the normal curvatures across the edge (in the
  direction normal to the edge in the sheet's tangent plane; both signed along the sheet's
  normal), relative to the larger of the two, and to no less than one over the faces' size, so
  that two nearly flat faces do not show a large relative jump of nothing (G2: 0 %).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

#: Points along each edge (the issue's "at least 200").
SAMPLES = 200


@dataclass
class Join:
    """The largest misfit of a sheet to its neighbour along one edge."""

    name: str
    gap: float  # mm
    angle: float = math.nan  # degrees between the tangent planes; nan without a neighbour
    curvature_jump: float = math.nan  # percent; nan without a neighbour
    samples: int = 0


#: A seeded foot is taken when it is this close to the point, relative to the faces' size: then
#: no other point of a face can be nearer by more than that (only a surface folding back within
#: it could), and the measure is that of the global projection. Farther feet (a gap, an offset
#: neighbour) go to OCCT's global projection.
SEEDED_REACH = 1e-6


def _newton_foot(surface, point, u, v, bounds, reach):
    """(u, v) of the surface's closest point to ``point`` by Newton's method on the squared
    distance from (u, v), or None unless it converges, within the surface's bounds, to a point
    within ``reach`` of ``point``.

    Why: OCCT's global projection (Surface.parameter) takes about 1.6 ms on a bicubic B-spline
    face; it was 3.2 s of a 4.8 s five-sided G1 hole fill (2 000 feet along the joined edges).
    Consecutive points along an edge have feet close to each other's, where Newton converges in
    two or three steps."""
    u0, u1, v0, v1 = bounds
    scale_u, scale_v = max(u1 - u0, 1e-300), max(v1 - v0, 1e-300)
    for _ in range(16):
        r = surface.value(u, v) - point
        su, sv = surface.getDN(u, v, 1, 0), surface.getDN(u, v, 0, 1)
        g1, g2 = su.dot(r), sv.dot(r)
        a = su.dot(su) + surface.getDN(u, v, 2, 0).dot(r)
        b = su.dot(sv) + surface.getDN(u, v, 1, 1).dot(r)
        c = sv.dot(sv) + surface.getDN(u, v, 0, 2).dot(r)
        det = a * c - b * b
        if not (a > 0.0 and det > 0.0):  # not a minimum of the distance here
            return None
        # Steps are kept inside the bounds (a foot on the boundary is reached along it).
        next_u = min(max(u - (c * g1 - b * g2) / det, u0), u1)
        next_v = min(max(v - (a * g2 - b * g1) / det, v0), v1)
        du, dv = next_u - u, next_v - v
        u, v = next_u, next_v
        if abs(du) <= 1e-13 * scale_u and abs(dv) <= 1e-13 * scale_v:
            break
    else:
        return None
    return (u, v) if (surface.value(u, v) - point).Length <= reach else None


def parameters_along(surface, points, reach: float):
    """(u, v) of the surface's point nearest each of ``points`` (consecutive points along a curve
    on or near it): each foot seeded from the previous one's (see _newton_foot), OCCT's global
    projection for the first and for any farther than ``reach``."""
    bounds = surface.bounds()
    feet, seed = [], None
    for p in points:
        found = _newton_foot(surface, p, seed[0], seed[1], bounds, reach) if seed and reach > 0.0 else None
        seed = found if found else surface.parameter(p)
        feet.append(seed)
    return feet


def _foot(face, point, seed=None, reach=0.0):
    """(u, v) of the face's surface point nearest ``point``, its position and its unit normal
    (the surface's own normal, so that curvatures keep their sign). ``seed``: the (u, v) of a
    nearby point's foot, from which Newton's method is tried first."""
    surface = face.Surface
    found = _newton_foot(surface, point, seed[0], seed[1], surface.bounds(), reach) if seed else None
    u, v = found if found else surface.parameter(point)
    return u, v, surface.value(u, v), surface.normal(u, v)


def normal_curvature(surface, u, v, direction) -> float:
    """The surface's normal curvature at (u, v) along a tangent ``direction`` (Euler's formula
    from the principal curvatures and directions), signed along the surface's own normal."""
    k_max, k_min = surface.curvature(u, v, "Max"), surface.curvature(u, v, "Min")
    d_max, d_min = surface.curvatureDirections(u, v)
    a, b = direction.dot(d_max), direction.dot(d_min)
    norm = a * a + b * b
    if norm <= 0.0:
        return 0.0
    return (k_max * a * a + k_min * b * b) / norm


def measure(name: str, sheet, edge, neighbour=None, samples: int = SAMPLES, size: Optional[float] = None,
            seeded: bool = True) -> Join:
    """The Join of ``sheet`` (a face) to ``neighbour`` (a face, or None) along ``edge``. With
    ``seeded`` each foot starts from the previous point's (see SEEDED_REACH); without, every
    foot is OCCT's global projection (the same figures, slower)."""
    if size is None:
        box = sheet.BoundBox
        if neighbour is not None:
            box.add(neighbour.BoundBox)
        size = box.DiagonalLength
    floor = 1.0 / size if size > 0.0 else 0.0
    reach = SEEDED_REACH * size if seeded else 0.0
    gap = angle = jump = 0.0
    points = edge.discretize(Number=max(int(samples), 2))
    on_sheet_seed = on_neighbour_seed = None
    for p in points:
        u, v, on_sheet, n_sheet = _foot(sheet, p, on_sheet_seed, reach)
        on_sheet_seed = (u, v) if seeded else None
        if neighbour is None:
            gap = max(gap, (on_sheet - p).Length)
            continue
        s, t, on_neighbour, n_neighbour = _foot(neighbour, p, on_neighbour_seed, reach)
        on_neighbour_seed = (s, t) if seeded else None
        gap = max(gap, (on_sheet - on_neighbour).Length)
        cosine = min(1.0, abs(n_sheet.dot(n_neighbour)))
        angle = max(angle, math.degrees(math.acos(cosine)))
        tangent = edge.tangentAt(edge.Curve.parameter(p)) if hasattr(edge.Curve, "parameter") else None
        if tangent is None or tangent.Length == 0.0:
            continue
        across = n_sheet.cross(tangent)
        if across.Length == 0.0:
            continue
        across.normalize()
        k_sheet = normal_curvature(sheet.Surface, u, v, across)
        side = 1.0 if n_neighbour.dot(n_sheet) >= 0.0 else -1.0
        k_neighbour = side * normal_curvature(neighbour.Surface, s, t, across)
        scale = max(abs(k_sheet), abs(k_neighbour), floor)
        if scale > 0.0:
            jump = max(jump, 100.0 * abs(k_sheet - k_neighbour) / scale)
    if neighbour is None:
        return Join(name, gap, samples=len(points))
    return Join(name, gap, angle, jump, len(points))


def shape_operator(surface, u: float, v: float):
    """The unit normal (the surface's own) and the second fundamental form of ``surface`` (a
    Part surface) at (u, v) as a symmetric 3D tensor K (II(T, T) = T . K T for tangent T), from
    the fundamental forms: K = J G^-1 B G^-1 J^T (J = [Su Sv]). Unlike principal directions this
    is defined at umbilic points (planes, spheres)."""
    su, sv = surface.getDN(u, v, 1, 0), surface.getDN(u, v, 0, 1)
    suu, suv, svv = surface.getDN(u, v, 2, 0), surface.getDN(u, v, 1, 1), surface.getDN(u, v, 0, 2)
    n = su.cross(sv)
    if n.Length == 0.0:
        raise ValueError("the surface is degenerate there (no normal)")
    n.normalize()
    g11, g12, g22 = su.dot(su), su.dot(sv), sv.dot(sv)
    det = g11 * g22 - g12 * g12
    i11, i12, i22 = g22 / det, -g12 / det, g11 / det  # G^-1
    b11, b12, b22 = n.dot(suu), n.dot(suv), n.dot(svv)
    # M = G^-1 B G^-1 (2 x 2), then K = J M J^T.
    a11, a12, a21, a22 = i11 * b11 + i12 * b12, i11 * b12 + i12 * b22, i12 * b11 + i22 * b12, i12 * b12 + i22 * b22
    m11, m12, m22 = a11 * i11 + a12 * i12, a11 * i12 + a12 * i22, a21 * i12 + a22 * i22
    cols = ((su.x, sv.x), (su.y, sv.y), (su.z, sv.z))

    def k(r, c):
        (p0, p1), (q0, q1) = cols[r], cols[c]
        return p0 * (m11 * q0 + m12 * q1) + p1 * (m12 * q0 + m22 * q1)

    return n, (k(0, 0), k(1, 1), k(2, 2), k(0, 1), k(0, 2), k(1, 2))


#: Two G1 joins' neighbours whose tangent planes differ by more than this (degrees) where the
#: joins' edges meet ask the sheet for two tangent planes at one point.
CORNER_ANGLE = 0.01


@dataclass
class Corner:
    """Where two G1 joins meet and their neighbours' tangent planes differ."""

    first: str
    second: str
    point: tuple  # (x, y, z)
    angle: float  # degrees between the two neighbours' tangent planes there

    def message(self) -> str:
        x, y, z = self.point
        return (f"{self.first} and {self.second} meet at ({x:.4g}, {y:.4g}, {z:.4g}), where their faces' "
                f"tangent planes differ by {self.angle:.3g}°: the sheet cannot be tangent to both there; join one "
                "of them G0, or let the faces meet tangentially there")


#: Two G2 joins' neighbours whose curvatures (second fundamental forms) differ by more than this
#: (percent of the larger, as a join's curvature jump) where the joins' edges meet ask the sheet
#: for two curvatures at one point.
CORNER_CURVATURE = 1.0


@dataclass
class CurvatureCorner:
    """Where two G2 joins meet and their neighbours' curvatures differ."""

    first: str
    second: str
    point: tuple  # (x, y, z)
    jump: float  # percent

    def message(self) -> str:
        x, y, z = self.point
        return (f"{self.first} and {self.second} meet at ({x:.4g}, {y:.4g}, {z:.4g}), where their faces' "
                f"curvatures differ by {self.jump:.3g} %: the sheet cannot continue both curvatures there "
                "(join one of them G1)")


def _plane_form(face, point, frame=None):
    """The face's second fundamental form at its point nearest ``point`` in an orthonormal
    ``frame`` (e1, e2) of a tangent plane (its own if None), signed along frame's normal."""
    surface = face.Surface
    u, v = surface.parameter(point)
    n, k = shape_operator(surface, u, v)
    if frame is None:
        e1 = surface.getDN(u, v, 1, 0)
        e1.normalize()
        frame = (e1, n.cross(e1), n)
    e1, e2, normal = frame
    sign = 1.0 if n.dot(normal) >= 0.0 else -1.0
    kxx, kyy, kzz, kxy, kxz, kyz = k

    def form(a, b):
        return sign * (a.x * (kxx * b.x + kxy * b.y + kxz * b.z) + a.y * (kxy * b.x + kyy * b.y + kyz * b.z)
                       + a.z * (kxz * b.x + kyz * b.y + kzz * b.z))

    return (form(e1, e1), form(e1, e2), form(e2, e2)), frame


def curvature_corners(joins, tolerance: float):
    """The CurvatureCorners of ``joins`` — (name, edge, neighbour face) of G2 joins — whose edges
    share an end (within ``tolerance``) where the neighbours' second fundamental forms differ by
    more than CORNER_CURVATURE percent (of the larger, and of no less than one over the faces'
    size): a G2 sheet must take both there."""
    found = []
    for (name_a, face_a), (name_b, face_b), p in _meeting_ends(joins, tolerance):
        box = face_a.BoundBox
        box.add(face_b.BoundBox)
        floor = 1.0 / box.DiagonalLength if box.DiagonalLength > 0.0 else 0.0
        form_a, frame = _plane_form(face_a, p)
        form_b, _ = _plane_form(face_b, p, frame)
        scale = max(max(abs(x) for x in form_a), max(abs(x) for x in form_b), floor)
        jump = 100.0 * max(abs(x - y) for x, y in zip(form_a, form_b)) / scale if scale > 0.0 else 0.0
        if jump > CORNER_CURVATURE:
            found.append(CurvatureCorner(name_a, name_b, (p.x, p.y, p.z), jump))
    return found


def _meeting_ends(joins, tolerance: float):
    """((name, face), (name, face), point) for every two of ``joins`` — (name, edge, neighbour
    face) — and each end of the first's edge within ``tolerance`` of an end of the second's."""
    for i, (name_a, edge_a, face_a) in enumerate(joins):
        for name_b, edge_b, face_b in joins[i + 1:]:
            for p in (v.Point for v in edge_a.Vertexes):
                if min((p - q.Point).Length for q in edge_b.Vertexes) <= tolerance:
                    yield (name_a, face_a), (name_b, face_b), p


def incompatible_corners(joins, tolerance: float):
    """The Corners of ``joins`` — (name, edge, neighbour face) of G1 joins — whose edges share an
    end (within ``tolerance``) where the neighbours' tangent planes differ by more than
    CORNER_ANGLE."""
    found = []
    for (name_a, face_a), (name_b, face_b), p in _meeting_ends(joins, tolerance):
        n_a, n_b = _foot(face_a, p)[3], _foot(face_b, p)[3]
        angle = math.degrees(math.acos(min(1.0, abs(n_a.dot(n_b)))))
        if angle > CORNER_ANGLE:
            found.append(Corner(name_a, name_b, (p.x, p.y, p.z), angle))
    return found
