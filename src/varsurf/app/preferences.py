# SPDX-License-Identifier: LGPL-2.1-or-later
"""The user's defaults for new sheets (Edit > Preferences > VarSurf, Resources/ui/preferences.ui),
read from FreeCAD's parameters. Values out of range fall back to the built-in defaults."""

from __future__ import annotations

import math

import FreeCAD

from varsurf.solve import settings

PARAM_PATH = "User parameter:BaseApp/Preferences/Mod/VarSurf"

# name -> (kind, built-in default, valid?)
_ENTRIES = {
    "Degree": ("Int", settings.SHEET_MIN_DEGREE, lambda v: 2 <= v <= 9),
    "MinSpans": ("Int", settings.DEFAULT_MIN_SPANS, lambda v: 1 <= v <= 512),
    "MaxSpans": ("Int", settings.DEFAULT_MAX_SPANS, lambda v: 1 <= v <= 1024),
    "Stretch": ("Float", settings.DEFAULT_STRETCH, lambda v: math.isfinite(v) and v >= 0.0),
    "Bend": ("Float", settings.DEFAULT_BEND, lambda v: math.isfinite(v) and v >= 0.0),
    "Tolerance": ("Float", settings.DEFAULT_TOLERANCE, lambda v: math.isfinite(v) and v > 0.0),
    "SolveMode": ("Int", 0, lambda v: 0 <= v < len(settings.SOLVE_MODES)),  # a combo box's index
    # Resource limits of one solve: seconds, and megabytes (0: half the physical memory).
    "SolveTimeLimit": ("Float", settings.DEFAULT_TIME_LIMIT, lambda v: math.isfinite(v) and v > 0.0),
    "SolveMemoryLimit": ("Int", 0, lambda v: v >= 0),
}


def group():
    return FreeCAD.ParamGet(PARAM_PATH)


def get(name: str):
    kind, default, valid = _ENTRIES[name]
    value = group().GetInt(name, default) if kind == "Int" else group().GetFloat(name, float(default))
    return value if valid(value) else default


def sheet_defaults() -> dict:
    """make_sheet's keyword defaults from the preferences."""
    return {
        "degree": get("Degree"),
        "min_spans": get("MinSpans"),
        "max_spans": max(get("MaxSpans"), get("MinSpans")),
        "stretch": get("Stretch"),
        "bend": get("Bend"),
        "tolerance": get("Tolerance"),
        "solve_mode": settings.SOLVE_MODES[get("SolveMode")],
    }


def solve_limits() -> dict:
    """The time and memory limits of a solve (SheetSettings.time_limit and memory_limit)."""
    megabytes = get("SolveMemoryLimit")
    return {"time_limit": get("SolveTimeLimit"),
            "memory_limit": megabytes * 1e6 if megabytes > 0 else settings.default_memory_limit()}


def tolerance_is_automatic() -> bool:
    """Whether new sheets take their tolerance from the model's size: no tolerance stored, or 0
    (the preferences page's "Automatic", which it stores when OK is pressed without a change)."""
    return not ("Tolerance" in group().GetFloats() and group().GetFloat("Tolerance") > 0.0)
