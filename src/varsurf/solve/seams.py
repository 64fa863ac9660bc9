# SPDX-License-Identifier: LGPL-2.1-or-later
"""Which ways a base face closes on itself: a cylinder, a 360° revolve or a sphere around its
axis, a torus both ways. There the sheet is closed too: its two ends are one seam across which
its displacement from the base is tied smooth, so the seam is an interior curve of the sheet (no
crease, no gap) rather than a boundary held in place."""

from __future__ import annotations

from dataclasses import dataclass

#: How close (relative to the base's extent) the two ends' positions and scaled derivatives must
#: be for the base to count as closed and smooth to that order across its seam. The exact
#: conversions of elementary surfaces meet to about 1e-15; a face closed within a modelling
#: tolerance (1e-7 of its size) is still closed to the user.
SEAM_MATCH = 1e-7


@dataclass(frozen=True)
class Seams:
    closed_u: bool = False
    closed_v: bool = False

    @property
    def any(self):
        return self.closed_u or self.closed_v


def of_base(nat, base) -> Seams:
    """The seams of the native base surface: a direction is closed when its two ends meet with
    the same tangent (the base is C1 or smoother across them: a crease there is an edge of the
    model, kept as a boundary)."""
    orders = [int(nat.seam_continuity(base.space, base.poles, d, SEAM_MATCH)) for d in (0, 1)]
    closed = [order >= 1 for order in orders]
    return Seams(closed[0], closed[1])
