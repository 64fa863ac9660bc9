# SPDX-License-Identifier: LGPL-2.1-or-later
"""A sheet's settings: what a Sheet's properties hold (energy, tolerance, spline space, solve
and refinement), their defaults and their checks."""

from __future__ import annotations

import dataclasses
import math
import os
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

from varsurf.solve.errors import SheetError

#: Thin plate by default: no stretching term, unit bending. Stretch (alpha) pulls the sheet toward
#: the smallest area (a membrane), bend (beta) toward the smallest curvature.
DEFAULT_STRETCH = 0.0
DEFAULT_BEND = 1.0
#: Largest distance (mm) at which a curve counts as met. The solver fits each group of curves
#: only until its RMS residual is a quarter of this (the discrepancy principle: max deviations
#: run 1-3x the RMS) and leaves the remaining directions to the energy, so the sheet stays fair
#: instead of chasing data its space can hold only with wild poles.
DEFAULT_TOLERANCE = 0.01
#: A new sheet's tolerance when none is set: this fraction of the model's size, rounded down to
#: 1, 2 or 5 times a power of ten (0.01 mm for a 100 mm part, 0.1 mm for a 1 m one).
RELATIVE_TOLERANCE = 1e-4
FIT_TO_TOLERANCE = 0.25
#: The base face's knot vectors are refined (knot insertion: the base shape is unchanged) to at
#: least this many spans per direction; curves off the iso lines need that freedom.
DEFAULT_MIN_SPANS = 16
#: Bases of lower degree (planes and ruled faces convert to degree 1) are elevated to at least
#: cubic by default so the sheet can bend smoothly; a Sheet may ask for a higher degree.
SHEET_MIN_DEGREE = 3
#: Highest degree a Sheet may ask for (OCCT allows 25; beyond 9 the basis is ill-conditioned).
MAX_DEGREE = 9
#: When the curves cannot be held within the tolerance even with wild poles (the solver's
#: "conflict"), the spans are doubled up to this count before giving up.
DEFAULT_MAX_SPANS = 64
#: Solve modes a Sheet offers (see _native.SolveMode): Automatic picks by size and says which.
SOLVE_MODES = ("Automatic", "Exact", "Penalty", "PenaltyQR", "CG", "TSVD", "MTSVD")
#: Relative singular value below which constraint rows are numerically dependent.
DEFAULT_RANK_TOLERANCE = 1e-9
#: How a sheet is bounded: Automatic (a sheet without base face by the closed loop among its
#: curves when they hold one, a sheet on a base face by the base's own boundary), Loop (by the
#: closed loop among its curves, with or without base face: a hole's loop on a larger face), None
#: (the whole base face, or the whole best-fit rectangle).
TRIMS = ("Automatic", "Loop", "None")
#: Energies a Sheet minimizes: the thin plate (Stretch, Bend; Welch & Witkin) or the generalized
#: Bloor-Wilson PDE (d_ss + a^2 d_tt)^2 P = 0 of Du & Qin, whose a(s, t) sets how much shorter the
#: length scale of changes along u is than along v (s, t: u and v normalized to 0..1).
ENERGIES = ("ThinPlate", "PDE")
#: Largest PDE coefficient accepted: a^4 weighs the v derivatives, and beyond this the energy's
#: two directions differ by more than 1e12 (rounding then decides the shape, not the PDE).
MAX_PDE_A = 1000.0
#: Refinement modes: Uniform doubles the spans everywhere until the curves are met; Local refines
#: only the spans under the curves that are off (hierarchical layers, Welch & Witkin sec. 3, 4.4).
REFINEMENTS = ("Uniform", "Local")
DEFAULT_MAX_DEPTH = 5

# Resource limits of one sheet's solve (all its refinement rounds): past the time, or beyond the
# memory estimate, the solve stops with a message instead of hanging FreeCAD or exhausting memory.
DEFAULT_TIME_LIMIT = 600.0  # seconds


def default_memory_limit() -> float:
    """Half the machine's physical memory, in bytes (the rest is FreeCAD's and the system's)."""
    try:
        return 0.5 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return 4e9


#: Fewest points per curve at which the result's distance to the curve is measured (the
#: measurement adds its own where the curve needs them and refines the peaks between them).
DEVIATION_SAMPLES = 200


def tolerance_for_size(size: float) -> float:
    """RELATIVE_TOLERANCE of `size` (mm), rounded down to 1, 2 or 5 x 10^k; DEFAULT_TOLERANCE for a
    size that is not a positive finite length."""
    if not (math.isfinite(size) and size > 0.0):
        return DEFAULT_TOLERANCE
    raw = RELATIVE_TOLERANCE * size
    power = 10.0 ** math.floor(math.log10(raw))
    return max(m for m in (1.0, 2.0, 5.0) if m * power <= raw * (1 + 1e-12)) * power


@dataclass(frozen=True)
class SheetSettings:
    """Everything about a sheet that is not its geometry (base face, curves, constraints, rest
    shape): one value, as a Sheet's properties hold it. ``changed(**values)`` returns a copy with
    some replaced; ``check()`` raises SheetError naming the first value out of range."""

    stretch: float = DEFAULT_STRETCH  # alpha: first derivatives (membrane)
    bend: float = DEFAULT_BEND  # beta: second derivatives (thin plate)
    #: Anisotropic weights (a11, a12, a22) and (b11, b12, b22), replacing stretch and bend.
    stretch_tensor: Optional[Sequence[float]] = None
    bend_tensor: Optional[Sequence[float]] = None
    pressure: float = 0.0  # inflate (> 0) or deflate (< 0), in the energy's units
    energy: str = "ThinPlate"  # one of ENERGIES
    pde_a: float = 1.0  # PDE: a where nothing is painted
    #: PDE: a painted on rectangles, (a, u0, u1, v0, v1) with u and v normalized (later over earlier)
    pde_regions: Sequence[Tuple[float, float, float, float, float]] = ()
    pde_blend: float = 0.0  # PDE: width of the band a blends across a region's border (0..0.5)
    fix_boundary: bool = True  # keep the base face's boundary (and its trim's edges)
    #: One of TRIMS: bound the sheet by the closed loop among its curves (boundary.py).
    trim: str = "Automatic"
    tolerance: float = DEFAULT_TOLERANCE  # mm at which a curve counts as met
    exact_curves: Sequence[str] = ()  # curve names met exactly wherever the space allows
    degree: int = SHEET_MIN_DEGREE  # smallest degree in u and v
    min_spans: int = DEFAULT_MIN_SPANS
    max_spans: int = DEFAULT_MAX_SPANS
    solve_mode: str = "Automatic"  # one of SOLVE_MODES
    rank_tolerance: float = DEFAULT_RANK_TOLERANCE
    refinement: str = "Uniform"  # one of REFINEMENTS
    max_depth: int = DEFAULT_MAX_DEPTH  # Local: levels above min_spans
    #: Local: regions refined by hand, (level, u0, u1, v0, v1) with u and v normalized.
    refine_regions: Sequence[Tuple[float, float, float, float, float]] = ()
    auto_refine: bool = True  # Local: refine where the curves are off
    influence_level: int = 0  # Local: coarser levels keep the start shape
    time_limit: Optional[float] = None  # seconds; None: DEFAULT_TIME_LIMIT
    memory_limit: Optional[float] = None  # bytes; None: default_memory_limit()

    def changed(self, **values) -> "SheetSettings":
        return dataclasses.replace(self, **values)

    def check(self) -> None:
        for label, value in (("Stretch", self.stretch), ("Bend", self.bend)):
            if not value >= 0.0:  # also rejects NaN
                raise SheetError(f"{label} must be a number >= 0 (got {value}): set the Sheet's {label} to 0 or more")
        if self.energy not in ENERGIES:
            raise SheetError(f"Energy must be one of {', '.join(ENERGIES)} (got {self.energy!r}): pick one of them")
        if self.energy == "PDE":
            self._check_pde()
        elif self.stretch == 0.0 and self.bend == 0.0 and not self.stretch_tensor and not self.bend_tensor:
            raise SheetError("Stretch and Bend are both 0: the sheet would have no energy to minimize; give Bend (or "
                             "Stretch) a positive weight")
        if not (self.tolerance > 0.0 and math.isfinite(self.tolerance)):
            raise SheetError(f"Tolerance must be a positive length (got {self.tolerance}): set a Tolerance above 0 mm, "
                             "e.g. a thousandth of the model's size")
        if not 1 <= int(self.min_spans) <= int(self.max_spans) <= 512:
            raise SheetError(f"spans must satisfy 1 <= MinSpans <= MaxSpans <= 512 (got {self.min_spans}, "
                             f"{self.max_spans}): set MinSpans no larger than MaxSpans")
        if not (isinstance(self.degree, int) and 2 <= self.degree <= MAX_DEGREE):
            raise SheetError(f"Degree must be an integer in 2..{MAX_DEGREE} (got {self.degree}): set it to 3 (bicubic) "
                             "unless you need another")
        if self.solve_mode not in SOLVE_MODES:
            raise SheetError(f"SolveMode must be one of {', '.join(SOLVE_MODES)} (got {self.solve_mode!r}): "
                             "pick one of them")
        if not 0.0 < self.rank_tolerance < 1.0:
            raise SheetError(f"rank tolerance must be in (0, 1) (got {self.rank_tolerance}): give one between 0 and 1, "
                             f"e.g. the default {DEFAULT_RANK_TOLERANCE:g}")
        if self.trim not in TRIMS:
            raise SheetError(f"Trim must be one of {', '.join(TRIMS)} (got {self.trim!r}): pick one of them")
        if self.refinement not in REFINEMENTS:
            raise SheetError(f"Refinement must be one of {', '.join(REFINEMENTS)} (got {self.refinement!r}): pick one "
                             "of them")
        if not math.isfinite(self.pressure):
            raise SheetError(f"Pressure must be finite (got {self.pressure}): set the Sheet's Pressure to a number "
                             "(0: none)")
        if not (self.time_seconds() > 0.0 and self.memory_bytes() > 0.0):  # NaN too
            raise SheetError(f"the time and memory limits must be positive (got {self.time_seconds()} s, "
                             f"{self.memory_bytes()} bytes): set them in VarSurf's preferences (0 MB: "
                             "automatic)")

    def _check_pde(self) -> None:
        if not (math.isfinite(self.pde_a) and 0.0 < self.pde_a <= MAX_PDE_A):
            raise SheetError(f"PdeA must be a number in (0, {MAX_PDE_A:g}] (got {self.pde_a}): set the Sheet's PdeA "
                             "above 0 (1: the same length scale along u and v)")
        if not (math.isfinite(self.pde_blend) and 0.0 <= self.pde_blend <= 0.5):
            raise SheetError(f"PdeBlend must be in [0, 0.5] (got {self.pde_blend}): a fraction of the sheet's domain, "
                             "0 for a sharp border")
        for k, region in enumerate(self.pde_regions):
            a, u0, u1, v0, v1 = (float(x) for x in region)
            if not (math.isfinite(a) and 0.0 < a <= MAX_PDE_A):
                raise SheetError(f"PdeRegions: region {k + 1} paints a = {a}; give it a number in (0, {MAX_PDE_A:g}]")
            if not (0.0 <= u0 < u1 <= 1.0 and 0.0 <= v0 < v1 <= 1.0):
                raise SheetError(f"PdeRegions: region {k + 1} spans u {u0}..{u1}, v {v0}..{v1}; give 0 <= u0 < u1 <= 1 "
                                 "and 0 <= v0 < v1 <= 1 (u and v normalized to the sheet's domain)")

    def time_seconds(self) -> float:
        return DEFAULT_TIME_LIMIT if self.time_limit is None else float(self.time_limit)

    def memory_bytes(self) -> float:
        return default_memory_limit() if self.memory_limit is None else float(self.memory_limit)
