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

from varsurf import assembly, joint, model
from varsurf.app import hinge as hinge_feature
from varsurf.app import sheet as sheet_feature
from varsurf.app import space_curve as space_curve_feature
from varsurf.app.feature import FeatureProxy, value

TYPE = "VarSurf::Solid"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Sheets", "App::PropertyLinkList", "Solid", "The Sheets to join; each is trimmed to the curves it shares with the others", False),
    ("Tolerance", "App::PropertyLength", "Solid", "How far a sheet may pass from a join curve (at least the sheets' own Tolerance); the shared edges' tolerances come from the measured deviation", False),
    ("Closed", "App::PropertyBool", "Result", "True if the sheets close into a solid", True),
    ("MaxEdgeTolerance", "App::PropertyFloat", "Result", "Worst edge/vertex tolerance after sewing (mm)", True),
    ("SeamGaps", "App::PropertyFloatList", "Result", "Per join curve: the largest distance from a sheet to it (mm)", True),
    ("SeamCurves", "App::PropertyStringList", "Result", "The curves the sheets are joined along (or bounded by), in the order of SeamGaps", True),
    ("SeamAngles", "App::PropertyFloatList", "Result", "Per shared edge: the smallest and largest angle between the faces across it (degrees, pairs; 180 is tangent-continuous)", True),
    ("Hinges", "App::PropertyLinkList", "Solid", "Hinges: the angle between two of the Sheets across a curve they share (solved with the sheets as one system)", False),
    ("HingeAngles", "App::PropertyFloatList", "Result", "Per hinge: the smallest and largest angle reached along its curve (degrees, pairs)", True),
    ("HingeErrors", "App::PropertyFloatList", "Result", "Per hinge: the largest difference from its Angle along the curve (degrees)", True),
    ("JointSolve", "App::PropertyString", "Result", "How the sheets were solved together (hinges, variational curves), or empty when each sheet's own solve stands", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]
DEFAULT_TOLERANCE = 2 * model.DEFAULT_TOLERANCE
#: A hinge farther than this from its angle anywhere along its curve is warned about (degrees).
HINGE_ANGLE_TOLERANCE = 0.05


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
        for key in set(sheet_feature.curve_keys(s)):
            counts[key] = counts.get(key, 0) + 1
    out = []
    for s in sheets:
        shared, own = [], []
        for key in sorted(set(sheet_feature.curve_keys(s))):
            name, sub = key.split(":")
            item = (key, Part.getShape(s.Document.getObject(name), sub, needSubElement=True))
            (shared if counts[key] >= 2 else own).append(item)
        out.append((s.Label, s.Shape.Faces[0], shared, own))
    return out


def _variational_curves(obj):
    """{key: VariationalCurve} of the SpaceCurve features among the Sheets' curves."""
    out = {}
    for s in obj.Sheets:
        for key in sheet_feature.curve_keys(s):
            link = s.Document.getObject(key.split(":")[0])
            if key not in out and space_curve_feature.is_space_curve(link):
                out[key] = space_curve_feature.variational_curve(link)[0]
    return out


def _solve_together(obj, inputs):
    """The inputs with faces (and variational curves) from one joint solve of the Sheets, when
    hinges or variational curves couple them; else as they are. Sets the hinge results."""
    hinges = [hinge_feature.spec_of(h) for h in (obj.Hinges or []) if h.Enabled]
    variational = _variational_curves(obj)
    if not hinges and not variational:
        obj.HingeAngles, obj.HingeErrors, obj.JointSolve = [], [], ""
        return inputs
    sheets = [joint.JointSheet(s.Label, sheet_feature.outcome_of(s), sheet_feature.curve_keys(s))
              for s in obj.Sheets]
    from varsurf import progress

    watch = progress.for_solve(obj.Label)
    try:
        result = joint.solve_joint(sheets, variational, hinges, keep_going=watch)
    finally:
        watch.stop()
    obj.HingeAngles = [a for lo, hi, _err in result.hinge_angles for a in (lo, hi)]
    obj.HingeErrors = [err for _lo, _hi, err in result.hinge_angles]
    obj.JointSolve = result.summary
    solved = result.curve_edges
    return [(label, face, [(k, solved.get(k, e)) for k, e in shared], [(k, solved.get(k, e)) for k, e in own])
            for (label, _face, shared, own), face in zip(inputs, result.faces)]


def _hinge_blame(obj):
    """A sheet pulled off its curves by a hinge: the hinge's angle contradicts the curves meeting
    its seam (where they end on it, they set both tangent planes), and the joint solve gives way
    at the curves. Say so."""
    names = [h.Label for h in (obj.Hinges or []) if h.Enabled]
    if not names:
        return ""
    return (f" (with hinges {', '.join(names)}: the curves meeting a hinged seam at its ends must "
            "leave it at the hinge's angle)")


class SolidFeature(FeatureProxy):
    """Proxy of a VarSurf Solid (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    PROPERTIES = _PROPERTIES
    DEFAULTS = {"Tolerance": DEFAULT_TOLERANCE}

    def execute(self, obj):
        try:
            inputs = _solve_together(obj, join_inputs(obj))
            try:
                outcome = assembly.build_solid(inputs, float(value(obj, "Tolerance")))
            except assembly.JoinGapError as error:
                raise model.SheetError(f"{error}{_hinge_blame(obj)}") from error
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
        obj.SeamCurves = outcome.seam_curves
        obj.SeamAngles = [v for pair in outcome.seam_angles for v in pair]
        for name, err in zip([h.Label for h in obj.Hinges if h.Enabled], obj.HingeErrors):
            if err > HINGE_ANGLE_TOLERANCE:
                FreeCAD.Console.PrintWarning(
                    f"VarSurf: {obj.Label}: {name} is off its angle by up to {err:.3g} degrees along the "
                    "curve (the sheets cannot bend that way there: more spans, or a compatible angle)\n")
        kind = "solid" if outcome.closed else f"open shell ({outcome.free_edges} free edges)"
        obj.Status = f"OK: {kind} of {outcome.faces} faces, worst edge tolerance {outcome.max_tolerance:.3g} mm"
