# SPDX-License-Identifier: LGPL-2.1-or-later
"""Local refinement (hierarchical layers, Welch & Witkin sec. 3, 4.4): its native options and
how its solve is reported."""

from __future__ import annotations

import math

from varsurf.solve.errors import SheetError


def hierarchy_options(nat, space, settings):
    """Native HierarchicalOptions of a Local refinement; settings.refine_regions are (level, u0, u1,
    v0, v1), u and v normalized."""
    tolerance, max_depth, influence_level = settings.tolerance, settings.max_depth, settings.influence_level
    options = nat.HierarchicalOptions()
    options.tolerance = float(tolerance)
    options.automatic = bool(settings.auto_refine)
    if not (isinstance(influence_level, int) and 0 <= influence_level <= max_depth):
        raise SheetError(f"InfluenceLevel must be an integer in 0..MaxDepth ({max_depth}) (got {influence_level}): "
                         "lower it, or raise MaxDepth")
    options.influence_level = influence_level
    if not (isinstance(max_depth, int) and 0 <= max_depth <= 8):
        raise SheetError(f"MaxDepth must be an integer in 0..8 (got {max_depth}): set it in that range")
    options.max_depth = max_depth
    boxes = []
    ua, ub = space.knots_u[0], space.knots_u[-1]
    va, vb = space.knots_v[0], space.knots_v[-1]
    for region in settings.refine_regions:
        level, u0, u1, v0, v1 = region
        if not all(math.isfinite(x) for x in (u0, u1, v0, v1)) or not (0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1):
            raise SheetError(f"a refine region needs 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1 (got {region}): "
                             "give RefineRegions inside the sheet")
        boxes.append(nat.RefineBox(int(level), ua + (ub - ua) * u0, ua + (ub - ua) * u1,
                                   va + (vb - va) * v0, va + (vb - va) * v1))
    options.manual = boxes
    return options


def mode_used(report, local) -> str:
    """The solve's mode and why; a hierarchical solve also says what its unknowns count: its free
    poles (x, y and z solved on one shared factorization), or their x, y and z in one coupled
    system when a constraint couples them; not its poles (DegreesOfFreedom)."""
    reason = str(report.mode_reason)
    if local is None:
        return reason
    unknowns = int(report.unknowns)
    levels = int(local.depth) + 1
    head = f"{reason}; locally refined: {int(local.dofs)} poles on {levels} level{'' if levels == 1 else 's'}, "
    if report.coupled:
        return head + f"{unknowns // 3} of them free, their x, y and z solved together ({unknowns} unknowns)"
    return head + f"{unknowns} of them free, x, y and z solved on one factorization ({unknowns} unknowns)"
