# SPDX-License-Identifier: LGPL-2.1-or-later
"""A tube's closed sections in the order the tube passes them: along the line that best fits
their centres. A loft through sections out of order twists back on itself; sections whose
centres are at the same place along that line (concentric rings in one plane) cannot be
ordered, and are refused naming them."""

from __future__ import annotations

from typing import List, Sequence

import numpy as np

from varsurf.solve.errors import SheetError

#: Centres closer than this (relative to the sections' extent) along the tube are one place.
SAME_PLACE = 1e-6


def section_order(labels: Sequence[str], centres: Sequence, extent: float) -> List[int]:
    """Indices of the sections in the tube's order along the line that best fits their centres,
    running so that the first section given comes before the last one given, or SheetError
    naming two sections that are at the same place along it."""
    if len(labels) != len(centres) or len(labels) < 2:
        raise SheetError(f"a tube needs two or more closed sections (got {len(labels)})")
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
