# SPDX-License-Identifier: LGPL-2.1-or-later
"""Fields to judge a solved sheet by, sampled on a grid over its face: deviation from a reference
(the base or the rest shape), mean and Gaussian curvature (fairness), and zebra stripes (the
reflection of stripes parallel to a direction: kinks and curvature jumps show as broken stripes);
and along each of its curves, the distance from the curve to the sheet (CurveDeviation).

Plain geometry on Part faces (OCCT evaluates the surface and its curvature); the GUI colors a mesh
with it (varsurf.gui.analysis_overlay). What a Sheet object is measured against, and its L-curve
plot, are in varsurf.app.analysis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Tuple

from varsurf.solve.shapes import single_face

MODES = ("None", "Deviation", "CurveDeviation", "MeanCurvature", "GaussianCurvature", "Zebra")
#: Grid cells per direction.
GRID = 48
#: Zebra: black-and-white stripe pairs over the half turn of the normal (the default).
STRIPES = 12


@dataclass
class AnalysisGrid:
    """Grid points (row-major, (n+1)^2), their normals, values, and the quads' triangles
    (Zebra: ``stripes`` is the number of stripe pairs the values count)."""

    n: int
    stripes: int = 0
    points: List[Tuple[float, float, float]] = field(default_factory=list)
    normals: List[Tuple[float, float, float]] = field(default_factory=list)
    values: List[float] = field(default_factory=list)
    triangles: List[Tuple[int, int, int]] = field(default_factory=list)

    @property
    def range(self) -> Tuple[float, float]:
        finite = [v for v in self.values if math.isfinite(v)]
        return (min(finite), max(finite)) if finite else (0.0, 0.0)


def analyse(shape, mode: str, reference=None, direction=(0.0, 0.0, 1.0), n: int = GRID,
            stripes: int = STRIPES) -> AnalysisGrid:
    """Sample `mode` on an (n+1) x (n+1) grid over the face's parameter box.

    Deviation: signed distance (mm) from the reference face along its normal, by projecting each
    point onto it (None: the deviation is not defined, ValueError). MeanCurvature and
    GaussianCurvature: 1/mm and 1/mm^2. Zebra: the stripe phase, ``stripes`` times the normal's
    angle to `direction` over a half turn (0 ... stripes); a stripe is white where the phase's
    fraction is below 0.5 (zebra_white). The phase varies smoothly, so a view can interpolate it per
    pixel and draw crisp stripe edges (a texture coordinate), which per-vertex colors cannot.
    """
    if mode not in MODES or mode in ("None", "CurveDeviation"):
        raise ValueError("a grid analysis is one of "
                         f"{', '.join(m for m in MODES if m not in ('None', 'CurveDeviation'))}"
                         f" (got {mode!r})")
    if not 1 <= n <= 400:
        raise ValueError(f"analysis grid must have 1 to 400 cells per direction (got {n})")
    if mode == "Zebra" and not 1 <= stripes <= 200:
        raise ValueError(f"zebra needs 1 to 200 stripes (got {stripes})")
    face = single_face(shape, "analysis")
    surface = face.Surface
    ref = None
    if mode == "Deviation":
        if reference is None:
            raise ValueError("deviation needs a reference face (the base, or an installed rest shape)")
        ref = single_face(reference, "analysis")
    u0, u1, v0, v1 = face.ParameterRange
    d = _unit(direction)
    grid = AnalysisGrid(n=n, stripes=stripes if mode == "Zebra" else 0)
    for i in range(n + 1):
        u = u0 + (u1 - u0) * i / n
        for j in range(n + 1):
            v = v0 + (v1 - v0) * j / n
            p = face.valueAt(u, v)
            try:
                normal = face.normalAt(u, v)
            except Exception:  # a degenerate point (a pole): no normal there
                normal = None
            grid.points.append((p.x, p.y, p.z))
            grid.normals.append((normal.x, normal.y, normal.z) if normal is not None else (0.0, 0.0, 1.0))
            grid.values.append(_value(mode, surface, ref, u, v, p, normal, d, stripes))
    for i in range(n):
        for j in range(n):
            a, b = i * (n + 1) + j, (i + 1) * (n + 1) + j
            grid.triangles.append((a, b, b + 1))
            grid.triangles.append((a, b + 1, a + 1))
    return grid


#: Points per curve at which CurveDeviation is measured.
CURVE_SAMPLES = 64


@dataclass
class CurveDeviation:
    """One curve's sample points and their distances (mm) to the sheet."""

    points: List[Tuple[float, float, float]]
    distances: List[float]


def curve_deviations(shape, edges, samples: int = CURVE_SAMPLES) -> List[CurveDeviation]:
    """Distance from points along each edge to the sheet's surface (by projection onto it)."""
    if samples < 2:
        raise ValueError("a curve needs at least 2 samples")
    face = single_face(shape, "analysis")
    out = []
    for edge in edges:
        points, distances = [], []
        for p in edge.discretize(samples):
            u, v = face.Surface.parameter(p)
            distances.append((face.Surface.value(u, v) - p).Length)
            points.append((p.x, p.y, p.z))
        out.append(CurveDeviation(points, distances))
    return out


def _value(mode, surface, ref, u, v, p, normal, d, stripes):
    if mode == "Deviation":
        ru, rv = ref.Surface.parameter(p)
        q = ref.valueAt(ru, rv)
        offset = p - q
        try:
            sign = 1.0 if offset.dot(ref.normalAt(ru, rv)) >= 0.0 else -1.0
        except Exception:
            sign = 1.0
        return sign * offset.Length
    if mode in ("MeanCurvature", "GaussianCurvature"):
        try:
            return float(surface.curvature(u, v, "Mean" if mode == "MeanCurvature" else "Gauss"))
        except Exception:
            return math.nan
    if normal is None:
        return math.nan
    angle = math.acos(max(-1.0, min(1.0, normal.x * d[0] + normal.y * d[1] + normal.z * d[2])))
    return stripes * angle / math.pi


def _unit(v):
    length = math.sqrt(sum(c * c for c in v))
    if not length > 0.0:
        raise ValueError("zebra direction must not be zero")
    return tuple(c / length for c in v)


def ramp(value: float, lo: float, hi: float) -> Tuple[float, float, float]:
    """Blue (lo) - green - red (hi); grey for a missing value. A range symmetric about 0 keeps 0
    green."""
    if not math.isfinite(value):
        return (0.6, 0.6, 0.6)
    t = 0.5 if hi <= lo else min(1.0, max(0.0, (value - lo) / (hi - lo)))
    if t < 0.5:
        s = t / 0.5
        return (0.0, s, 1.0 - s)
    s = (t - 0.5) / 0.5
    return (s, 1.0 - s, 0.0)


def zebra_white(phase: float) -> bool:
    """Whether a zebra phase falls in a white stripe (each stripe pair: white, then black)."""
    return phase - math.floor(phase) < 0.5


def colors(mode: str, grid: AnalysisGrid, scale: float = 0.0) -> List[Tuple[float, float, float]]:
    """Per-vertex colors: black or white for zebra, the blue-green-red ramp otherwise (over
    color_range)."""
    if mode == "Zebra":
        return [((1.0, 1.0, 1.0) if zebra_white(v) else (0.0, 0.0, 0.0)) if math.isfinite(v) else (0.6, 0.6, 0.6)
                for v in grid.values]
    lo, hi = color_range(mode, grid, scale)
    return [ramp(v, lo, hi) for v in grid.values]


def color_range(mode: str, grid: AnalysisGrid, scale: float = 0.0) -> Tuple[float, float]:
    """The range the colors span: -scale ... scale for signed fields, by default (scale 0) the
    data's largest magnitude, so 0 stays green; the stripe phases for zebra."""
    if mode == "Zebra":
        return (0.0, float(grid.stripes))
    if scale < 0.0 or not math.isfinite(scale):
        raise ValueError(f"the color scale must be 0 (the data's range) or positive (got {scale})")
    if scale > 0.0:
        return (-scale, scale)
    lo, hi = grid.range
    m = max(abs(lo), abs(hi))
    return (-m, m)


#: Points along each side of a refined span's outline.
SIDE_SAMPLES = 6


def refined_outlines(face, spans):
    """Per refined span of a locally refined sheet (RefinedSpans: level, u0, u1, v0, v1 in fives):
    its level and the closed 3D polyline of its border on the face, lifted a hair along the normal
    so a view does not hide it in the sheet."""
    if len(spans) % 5:
        raise ValueError("refined spans come in fives: level, u0, u1, v0, v1")
    lift = 1e-3 * max(face.BoundBox.DiagonalLength, 1.0)
    out = []
    for k in range(0, len(spans), 5):
        level, u0, u1, v0, v1 = int(spans[k]), *spans[k + 1:k + 5]
        steps = [s / SIDE_SAMPLES for s in range(SIDE_SAMPLES)]
        uv = ([(u0 + (u1 - u0) * t, v0) for t in steps] + [(u1, v0 + (v1 - v0) * t) for t in steps]
              + [(u1 - (u1 - u0) * t, v1) for t in steps] + [(u0, v1 - (v1 - v0) * t) for t in steps]
              + [(u0, v0)])
        points = []
        for u, v in uv:
            p = face.valueAt(u, v)
            try:
                p = p + face.normalAt(u, v) * lift
            except Exception:  # a degenerate point: no normal to lift along
                pass
            points.append((p.x, p.y, p.z))
        out.append((level, points))
    return out
