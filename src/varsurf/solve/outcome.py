# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a solved sheet is, and what a user wants to know about it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import List


@dataclass
class SheetOutcome:
    """A solved sheet and its figures of merit."""

    shape: object  # Part.Face of the result, in the base face's coordinates
    surface: object  # _native.BSplineSurface
    curve_names: List[str] = field(default_factory=list)
    max_deviations: List[float] = field(default_factory=list)  # mm, one per curve
    pole_count_u: int = 0
    pole_count_v: int = 0
    degree_u: int = 0
    degree_v: int = 0
    solve_seconds: float = 0.0  # native solve
    total_seconds: float = 0.0  # conversion + solve + result face + measurement
    constraint_rank: int = 0
    unknowns: int = 0
    report: object = None  # _native.SolveReport
    constraint_names: List[str] = field(default_factory=list)
    constraint_residuals: List[float] = field(default_factory=list)  # in constraint_units
    constraint_units: List[str] = field(default_factory=list)  # "mm" or "deg"
    iterations: int = 0  # nonlinear steps (repellers, pressure)
    converged: bool = True
    # G2 joins are not linear: Newton steps taken and the largest relative curvature jump left
    # at the solver's samples (the joins' measured jumps are in ``joins``).
    curvature_iterations: int = 0
    curvature_jump: float = 0.0
    solve_mode: str = ""  # the mode used, and why
    lcurve_residuals: List[float] = field(default_factory=list)  # TSVD/MTSVD: rho_k
    lcurve_norms: List[float] = field(default_factory=list)  # eta_k
    lcurve_corner: int = 0  # the chosen truncation k
    # Local refinement: levels above the base, degrees of freedom (poles) of the hierarchical
    # sheet, and whether every curve was met before the depth limit (Uniform: 0, the poles, True).
    refinement_depth: int = 0
    degrees_of_freedom: int = 0
    refinement_met: bool = True
    refined_spans: List[tuple] = field(default_factory=list)  # (level, u0, u1, v0, v1) each
    # The native SheetProblem of the final solve (curves in curve_names order) and its options:
    # what a joint solve of several sheets (varsurf.solve.joint) starts from.
    problem: object = None
    options: object = None
    # How the result joins its neighbours along each G0 and G1 constraint's edge (continuity.Join:
    # gap, tangent-plane angle and curvature jump, measured by OCCT on the result face).
    joins: List[object] = field(default_factory=list)
    # Where two G1 joins meet and their neighbours ask for different tangent planes.
    corners: List[object] = field(default_factory=list)
    # A sheet made from curves alone and trimmed to the closed loop among them: that loop's curves.
    boundary_curves: List[str] = field(default_factory=list)
    # The base face's trim (native BaseTrim): trim.face_brep(surface) bounds and orients any
    # surface of this sheet's space like the result (a drag's or a joint solve's).
    trim: object = None

    @property
    def max_deviation(self) -> float:
        return max(self.max_deviations, default=0.0)

    def summary(self) -> str:
        lines = [
            f"poles {self.pole_count_u} x {self.pole_count_v}, degree {self.degree_u} x {self.degree_v}",
            f"unknowns {self.unknowns}, constraint rank {self.constraint_rank}, {self.solve_mode}",
            f"solve {self.solve_seconds:.3f} s, total {self.total_seconds:.3f} s",
        ]
        for name, dev in zip(self.curve_names, self.max_deviations):
            lines.append(f"{name}: max deviation {dev:.3g} mm")
        for name, res, unit in zip(self.constraint_names, self.constraint_residuals, self.constraint_units):
            lines.append(f"{name}: residual {res:.3g} {unit}")
        return "\n".join(lines)
