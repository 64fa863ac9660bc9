"""The Solid feature: Sheets joined along the curves they share into a shell, and into a solid
when they close (Welch & Witkin sec. 5).

A ``Part::FeaturePython``: ``Sheets`` lists the Sheet objects; a join curve is an edge that two or
more of them list in their ``Curves``. Each join curve becomes edges built once from its 3D curve
with a pcurve on every sheet it bounds; each sheet is trimmed to the loop of its join curves, or,
when they do not close a loop, of all its curves (its own ones then bound the open shell).
App side only: no GUI import.
"""

from __future__ import annotations

import FreeCAD

from varsurf import assembly, model
from varsurf.app.feature import FeatureProxy, add_missing_properties

TYPE = "VarSurf::Solid"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Sheets", "App::PropertyLinkList", "Solid", "The Sheets to join; each is trimmed to the curves it shares with the others", False),
    ("Tolerance", "App::PropertyLength", "Solid", "How far a sheet may pass from a join curve (at least the sheets' own Tolerance); the shared edges' tolerances come from the measured deviation", False),
    ("Closed", "App::PropertyBool", "Result", "True if the sheets close into a solid", True),
    ("MaxEdgeTolerance", "App::PropertyFloat", "Result", "Worst edge/vertex tolerance after sewing (mm)", True),
    ("SeamGaps", "App::PropertyFloatList", "Result", "Per join curve: the largest distance from a sheet to it (mm)", True),
    ("SeamAngles", "App::PropertyFloatList", "Result", "Per shared edge: the smallest and largest angle between the faces across it (degrees, pairs; 180 is tangent-continuous)", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]
DEFAULT_TOLERANCE = 2 * model.DEFAULT_TOLERANCE


def _add_missing_properties(obj):
    add_missing_properties(obj, _PROPERTIES, {"Tolerance": DEFAULT_TOLERANCE})


def _curve_keys(sheet):
    return {(link.Name, sub) for link, subs in sheet.Curves for sub in subs if sub}


def join_inputs(obj):
    """[(label, face, [(key, shared edge)], [(key, own edge)])] for the Solid's Sheets, or
    SheetError."""
    import Part

    sheets = list(obj.Sheets or [])
    if not sheets:
        raise model.SheetError("Sheets is empty: select the Sheets to join")
    counts = {}
    for s in sheets:
        if s.Shape.isNull() or len(s.Shape.Faces) != 1:
            raise model.SheetError(f"{s.Label} has no result: recompute it first (is it in error?)")
        for key in _curve_keys(s):
            counts[key] = counts.get(key, 0) + 1
    out = []
    for s in sheets:
        shared, own = [], []
        for name, sub in sorted(_curve_keys(s)):
            link = s.Document.getObject(name)
            item = (f"{name}:{sub}", Part.getShape(link, sub, needSubElement=True))
            (shared if counts[(name, sub)] >= 2 else own).append(item)
        out.append((s.Label, s.Shape.Faces[0], shared, own))
    return out


class SolidFeature(FeatureProxy):
    """Proxy of a VarSurf Solid (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE

    def add_properties(self, obj):
        _add_missing_properties(obj)

    def execute(self, obj):
        try:
            outcome = assembly.build_solid(join_inputs(obj), float(obj.Tolerance))
            if not outcome.valid:
                raise model.SheetError("the sewn shape is not valid")
        except Exception as error:
            obj.Status = f"Error: {error}"
            obj.Closed = False
            FreeCAD.Console.PrintError(f"VarSurf: {obj.Label}: {error}\n")
            raise
        obj.Shape = outcome.shape
        obj.Closed = outcome.closed
        obj.MaxEdgeTolerance = outcome.max_tolerance
        obj.SeamGaps = outcome.seam_gaps
        obj.SeamAngles = [v for pair in outcome.seam_angles for v in pair]
        kind = "solid" if outcome.closed else f"open shell ({outcome.free_edges} free edges)"
        obj.Status = f"OK: {kind} of {outcome.faces} faces, worst edge tolerance {outcome.max_tolerance:.3g} mm"
