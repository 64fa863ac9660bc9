# SPDX-License-Identifier: LGPL-2.1-or-later
"""A tube's closed sections in the order the tube passes them: along the line that best fits
their centres. A loft through sections out of order twists back on itself; sections whose
centres are at the same place along that line (concentric rings in one plane) cannot be
ordered, and are refused naming them."""

from __future__ import annotations

from typing import List, Sequence, Tuple

import numpy as np

from varsurf.solve.errors import SheetError

#: Centres closer than this (relative to the sections' extent) along the tube are one place.
SAME_PLACE = 1e-6
#: A join of a section's edges that turns more than this (degrees) is a corner the smooth
#: closed sheet cannot follow; below it the section's smooth curve rounds it.
CORNER_DEGREES = 1.0
#: Points (evenly along its length) that tell which way a section winds.
SMOOTH_SAMPLES = 128
#: How far (relative to its length) the smooth curve of a section of several edges may stray
#: from them: the loft's ends are the sheet's held boundary, and the section's edges must lie on
#: it within the projection's 1e-6 mm.
SMOOTH_TOLERANCE = 1e-7
#: Knots of sections closer than this (relative to the period) are one: a span that narrow makes
#: the sheet on it ill-conditioned (a rigidly moved scene's sheet then moved 0.36 mm at its seam).
SAME_KNOT = 1e-6
#: Spans per edge the smooth curve refines to at most.
MAX_EDGE_SPANS = 256


def section_order(labels: Sequence[str], centres: Sequence, extent: float) -> List[int]:
    """Indices of the sections in the tube's order along the line that best fits their centres,
    running so that the first section given comes before the last one given, or SheetError
    naming two sections that are at the same place along it."""
    if len(labels) != len(centres) or len(labels) < 2:
        raise SheetError(f"a tube needs two or more closed sections (got {len(labels)}): add sections")
    points = np.array([[float(c[0]), float(c[1]), float(c[2])] for c in centres])
    middle = points.mean(axis=0)
    # The principal direction of the centres: the line the tube runs along.
    _u, _s, vt = np.linalg.svd(points - middle)
    axis = vt[0]
    along = (points - middle) @ axis
    if along[0] > along[-1]:
        along = -along
    order = [int(i) for i in np.argsort(along, kind="stable")]
    for a, b in zip(order, order[1:]):
        if along[b] - along[a] <= SAME_PLACE * max(extent, 1e-300):
            raise SheetError(
                f"the tube's sections {labels[a]} and {labels[b]} are at the same place along the tube (their "
                f"centres {along[b] - along[a]:.3g} mm apart along it): they cannot be ordered; move one along "
                "the tube, or leave one out")
    return order


def periodic_basis(knots: Sequence[float], degree: int, period: float, params) -> np.ndarray:
    """The values of a periodic B-spline's basis functions at ``params`` (each in [0, period)):
    a len(params) x len(knots) matrix. ``knots`` are the flat knots in [0, period), repeated by
    multiplicity; the poles are in the order of OCCT's periodic curve with these knots (its pole 1
    is the function starting (degree + 1 - m0) knots before knots[0], m0 the multiplicity of
    knots[0]). Cox-de Boor on the knots continued periodically."""
    n, p = len(knots), degree
    base = np.asarray(knots, dtype=float)
    shift = p + 1 - int(np.count_nonzero(base == base[0]))
    ext = np.concatenate([base[n - p:] - period, base, base[:p + 1] + period])  # t[p] = knots[0]
    rows = np.zeros((len(params), n))
    for r, s in enumerate(params):
        span = int(np.searchsorted(ext, s, side="right")) - 1  # ext[span] <= s < ext[span + 1]
        span = min(max(span, p), n + p - 1)
        values = _basis_values(ext, span, s, p)
        for k in range(p + 1):  # function span - p + k starts at ext[span - p + k]
            rows[r, (span - 2 * p + k + shift) % n] += values[k]
    return rows


def periodic_fit(knots: Sequence[float], degree: int, period: float, params, points) -> np.ndarray:
    """Least-squares poles (len(knots) x 3) of the periodic B-spline with these flat knots
    through ``points`` at ``params``."""
    basis = periodic_basis(knots, degree, period, params)
    poles, *_ = np.linalg.lstsq(basis, np.asarray(points, dtype=float), rcond=None)
    return poles


def _basis_values(ext, span, s, p):
    """The p + 1 non-zero basis values at s in ext[span] <= s < ext[span + 1] (The NURBS Book,
    A2.2)."""
    values = np.zeros(p + 1)
    values[0] = 1.0
    left, right = np.zeros(p + 1), np.zeros(p + 1)
    for j in range(1, p + 1):
        left[j] = s - ext[span + 1 - j]
        right[j] = ext[span + j] - s
        saved = 0.0
        for k in range(j):
            temp = values[k] / (right[k + 1] + left[j - k])
            values[k] = saved + right[k + 1] * temp
            saved = left[j - k] * temp
        values[j] = saved
    return values


def clamped_basis(knots: Sequence[float], degree: int, params) -> np.ndarray:
    """The values of a clamped B-spline's basis functions (flat ``knots``, end knots repeated
    degree + 1 times) at ``params``: a len(params) x (len(knots) - degree - 1) matrix."""
    ext = np.asarray(knots, dtype=float)
    n, p = len(ext) - degree - 1, degree
    rows = np.zeros((len(params), n))
    for r, s in enumerate(params):
        span = min(max(int(np.searchsorted(ext, s, side="right")) - 1, p), n - 1)
        rows[r, span - p:span + 1] = _basis_values(ext, span, s, p)
    return rows


def _grouped(knots, period):
    """[(value, multiplicity)] of flat knots, values closer than 1e-12 of the period as one."""
    groups = []
    for k in sorted(knots):
        if groups and abs(k - groups[-1][0]) <= 1e-12 * period:
            groups[-1][1] += 1
        else:
            groups.append([k, 1])
    return groups


def merged_knots(knot_lists: Sequence[Sequence[float]], period: float = 1.0, gap: float = 0.1) -> List[float]:
    """Flat knots of a periodic space for all the periodic spaces given (knots in [0, period)):
    every multiple knot of any (where a section's edges join; those within SAME_KNOT of one
    another as one) at its largest multiplicity, and
    the simple knots (there only for freedom) unless one lies within ``gap`` of its own span of a
    knot already kept. Knots of two sections a hair apart would leave a span a hair wide: the
    sheet on it is ill-conditioned (a 4.5e-5 span made a duct's solve 100 times slower)."""
    kept = {}
    simple = []
    for knots in knot_lists:
        groups = _grouped(knots, period)
        for index, (value, count) in enumerate(groups):
            if count > 1:
                key = next((m for m in kept if min(abs(m - value), period - abs(m - value)) <= SAME_KNOT * period),
                           value)
                kept[key] = max(kept.get(key, 0), count)
            else:
                before = groups[index - 1][0] - (period if index == 0 else 0.0)
                after = groups[(index + 1) % len(groups)][0] + (period if index + 1 == len(groups) else 0.0)
                simple.append((value, gap * min(value - before, after - value)))
    for value, near in sorted(simple):
        if all(min(abs(value - m), period - abs(value - m)) >= max(near, 1e-12 * period) for m in kept):
            kept[value] = 1
    return sorted(k for k, count in kept.items() for _ in range(count))


def on_knots(knots: Sequence[float], poles, new_knots: Sequence[float], degree: int,
             period: float = 1.0) -> Tuple[np.ndarray, float]:
    """(poles on the periodic knots ``new_knots``, largest sampled distance) of the curve with
    ``knots`` and ``poles``: least squares on samples of the curve in every span of both knot
    vectors. Where ``new_knots`` contain ``knots`` this is knot insertion (exact to rounding)."""
    unique = sorted(set(new_knots) | set(knots)) + [period]
    params = [a + (b - a) * (j + 0.5) / (degree + 2) for a, b in zip(unique, unique[1:]) if b > a
              for j in range(degree + 2)]
    values = periodic_basis(knots, degree, period, params) @ np.asarray(poles, dtype=float)
    fitted = periodic_fit(new_knots, degree, period, params, values)
    checks = [a + (b - a) * (j + 1) / (degree + 3) for a, b in zip(unique, unique[1:]) if b > a
              for j in range(degree + 2)]
    error = np.linalg.norm(periodic_basis(new_knots, degree, period, checks) @ fitted
                           - periodic_basis(knots, degree, period, checks) @ np.asarray(poles, dtype=float), axis=1)
    return fitted, float(error.max())


def skin(sections, degree: int = 3):
    """A surface closed in u through closed sections: ``sections`` are (flat knots in [0, 1),
    poles k x 3, centre) periodic B-splines of one degree, in their order along the tube. Returns
    (u knots, v knots (clamped, flat), poles nu x nv x 3, v degree, largest distance of a
    section's row from the section): each section moved onto the merged u knots; in v the pole
    columns are interpolated through the sections at chord-length parameters of their centres
    (degree min(3, sections - 1))."""
    count = len(sections)
    if count < 2:
        raise SheetError(f"a tube needs two or more sections (got {count}): add sections")
    u_knots = merged_knots([s[0] for s in sections])
    moved = [on_knots(k, p, u_knots, degree) for k, p, _c in sections]
    rows = np.array([poles for poles, _error in moved])  # sections x nu x 3
    centres = np.array([[float(x) for x in c] for _k, _p, c in sections])
    steps = np.linalg.norm(np.diff(centres, axis=0), axis=1)
    if not np.all(steps > 0.0):
        raise SheetError("two of the tube's sections have the same centre: they cannot both be passed in order; "
                         "move one along the tube, or leave one out")
    v = np.concatenate([[0.0], np.cumsum(steps)]) / steps.sum()
    q = min(3, count - 1)
    # Averaged interior knots (The NURBS Book, eq. 9.8): the interpolation matrix is regular.
    inner = [float(np.mean(v[j:j + q])) for j in range(1, count - q)]
    v_knots = [0.0] * (q + 1) + inner + [1.0] * (q + 1)
    basis = clamped_basis(v_knots, q, v)
    flat = rows.reshape(count, -1)
    columns = np.linalg.solve(basis, flat).reshape(count, -1, 3)
    return u_knots, v_knots, np.transpose(columns, (1, 0, 2)), q, max(error for _poles, error in moved)
