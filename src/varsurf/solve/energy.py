# SPDX-License-Identifier: LGPL-2.1-or-later
"""The sheet's energy: the thin plate's weights, per unit of the base's relative parameter speeds,
or the PDE energy's coefficient a(u, v)."""

from __future__ import annotations

import math

import numpy as np

from varsurf.solve.errors import SheetError


def parameter_lengths(surface, samples=12):
    """Mean |S_u| and |S_v| (mm per unit parameter) of a native surface over its domain, divided
    by their geometric mean: how much longer a unit of u is than a unit of v.

    The energy integrates over the base's parameters; a cylinder's or a cone's are an angle and a
    length. Measured in those, scaling the model re-weighted the two directions (a 1 mm and a
    100 mm scene gave shapes differing by 0.9 % of their size). Weights given per unit of these
    relative lengths weigh both directions alike in any base; bases whose two parameters have one
    speed (planes in mm, square [0, 1] B-spline faces) keep their energy exactly. Only the ratio is
    taken, not the lengths themselves: the energy's overall size, which a Pressure is balanced
    against, stays what it was for such bases."""
    space = surface.space
    u0, u1 = space.knots_u[0], space.knots_u[-1]
    v0, v1 = space.knots_v[0], space.knots_v[-1]
    total_u = total_v = 0.0
    for i in range(samples):
        u = u0 + (u1 - u0) * (i + 0.5) / samples
        for j in range(samples):
            v = v0 + (v1 - v0) * (j + 0.5) / samples
            rows = surface.derivatives(u, v, 1)
            total_u += math.sqrt(sum(float(x) ** 2 for x in rows[1]))
            total_v += math.sqrt(sum(float(x) ** 2 for x in rows[2]))
    if not (math.isfinite(total_u) and math.isfinite(total_v) and total_u > 0.0 and total_v > 0.0):
        raise SheetError("the base face's parametrization is degenerate (no length along one direction): pick "
                         "another face, or leave Base empty to start from the curves' plane")
    mean = math.sqrt(total_u * total_v)
    return total_u / mean, total_v / mean


def energy_weights(nat, stretch, bend, stretch_tensor, bend_tensor, lengths=(1.0, 1.0)):
    """The native ThinPlateWeights: isotropic, or from (11, 12, 22) tensors, per unit of the
    parameters u * lengths[0], v * lengths[1] (see parameter_lengths).

    With s = L_u u, t = L_v v: |x_s|^2 ds dt = (L_v / L_u) |x_u|^2 du dv, x_s . x_t ds dt = x_u . x_v
    du dv, |x_ss|^2 ds dt = L_v / L_u^3 |x_uu|^2 du dv, |x_st|^2 ds dt = |x_uv|^2 / (L_u L_v) du dv."""
    alpha = float(stretch) * np.eye(2)
    beta = float(bend) * np.ones((2, 2))
    for label, tensor in (("StretchTensor", stretch_tensor), ("BendTensor", bend_tensor)):
        if tensor is None or len(tensor) == 0:
            continue
        if len(tensor) != 3 or not all(math.isfinite(float(x)) for x in tensor):
            raise SheetError(f"{label} takes three finite numbers (11, 12, 22), got {list(tensor)}: give "
                             "three, or none for the isotropic energy")
        m = np.array([[tensor[0], tensor[1]], [tensor[1], tensor[2]]], dtype=float)
        if label == "StretchTensor":
            alpha = m
        else:
            beta = m
    lu, lv = lengths
    alpha = alpha * np.array([[lv / lu, 1.0], [1.0, lu / lv]])
    beta = beta * np.array([[lv / lu ** 3, 1.0 / (lu * lv)], [1.0 / (lu * lv), lu / lv ** 3]])
    try:
        return nat.ThinPlateWeights(alpha=alpha, beta=beta)
    except nat.InvalidInput as error:
        raise SheetError(f"energy weights: {error}; give tensors that are positive semidefinite (or none)") from error


def pde_coefficient(nat, settings, space):
    """The native PdeCoefficient of a PDE sheet on `space` (None for the thin plate): PdeA, and the
    PdeRegions' rectangles (normalized u, v) mapped onto the space's domain. A sheet whose boundary
    is not held takes the energy's plate form, whose free sides are held like a free plate's (the
    operator's own square lets them flare; see PdeCoefficient.plate_form).

    Unlike the thin plate's weights, a is measured in the normalized parameters (Du & Qin's
    u, v in 0..1), not per unit of the base's speeds: it is a shape control (the ratio of the
    length scales of changes along u and along v), and the same a gives the same shape on any
    domain."""
    if settings.energy != "PDE":
        return None
    u0, u1 = space.knots_u[0], space.knots_u[-1]
    v0, v1 = space.knots_v[0], space.knots_v[-1]
    painted = []
    for a, ru0, ru1, rv0, rv1 in settings.pde_regions:
        region = nat.Region(u0 + ru0 * (u1 - u0), u0 + ru1 * (u1 - u0), v0 + rv0 * (v1 - v0), v0 + rv1 * (v1 - v0))
        painted.append(nat.PaintedCoefficient(region, float(a)))
    coefficient = nat.PdeCoefficient(a=float(settings.pde_a), painted=painted, blend=float(settings.pde_blend))
    coefficient.plate_form = not settings.fix_boundary
    try:
        coefficient.validate(space)
    except nat.InvalidInput as error:
        raise SheetError(f"PDE energy: {error}; check PdeA, PdeRegions and PdeBlend") from error
    return coefficient
