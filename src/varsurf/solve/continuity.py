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


def _foot(face, point):
    """(u, v) of the face's surface point nearest ``point``, its position and its unit normal
    (the surface's own normal, so that curvatures keep their sign)."""
    surface = face.Surface
    u, v = surface.parameter(point)
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


def measure(name: str, sheet, edge, neighbour=None, samples: int = SAMPLES, size: Optional[float] = None) -> Join:
    """The Join of ``sheet`` (a face) to ``neighbour`` (a face, or None) along ``edge``."""
    if size is None:
        box = sheet.BoundBox
        if neighbour is not None:
            box.add(neighbour.BoundBox)
        size = box.DiagonalLength
    floor = 1.0 / size if size > 0.0 else 0.0
    gap = angle = jump = 0.0
    points = edge.discretize(Number=max(int(samples), 2))
    for p in points:
        u, v, on_sheet, n_sheet = _foot(sheet, p)
        if neighbour is None:
            gap = max(gap, (on_sheet - p).Length)
            continue
        s, t, on_neighbour, n_neighbour = _foot(neighbour, p)
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
                f"tangent planes differ by {self.angle:.3g}°: the sheet cannot be tangent to both there")


def incompatible_corners(joins, tolerance: float):
    """The Corners of ``joins`` — (name, edge, neighbour face) of G1 joins — whose edges share an
    end (within ``tolerance``) where the neighbours' tangent planes differ by more than
    CORNER_ANGLE."""
    found = []
    for i, (name_a, edge_a, face_a) in enumerate(joins):
        for name_b, edge_b, face_b in joins[i + 1:]:
            for p in (v.Point for v in edge_a.Vertexes):
                if min((p - q.Point).Length for q in edge_b.Vertexes) > tolerance:
                    continue
                n_a, n_b = _foot(face_a, p)[3], _foot(face_b, p)[3]
                angle = math.degrees(math.acos(min(1.0, abs(n_a.dot(n_b)))))
                if angle > CORNER_ANGLE:
                    found.append(Corner(name_a, name_b, (p.x, p.y, p.z), angle))
    return found
