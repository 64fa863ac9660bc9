# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Solid feature: Sheets joined along the curves they share into a shell, and into a solid
when they close (Welch & Witkin sec. 5).

A ``Part::FeaturePython``: ``Sheets`` lists the Sheet objects; a join curve is an edge that two or
more of them list in their ``Curves``. Each join curve becomes edges built once from its 3D curve
with a pcurve on every sheet it bounds; each sheet is trimmed to the loop of its join curves, or,
when they do not close a loop, of all its curves (its own ones then bound the open shell).
App side only: no GUI import.
"""

from __future__ import annotations

import math

import FreeCAD
import Part

from varsurf.app import hinge as hinge_feature
from varsurf.app import progress
from varsurf.app import sheet as sheet_feature
from varsurf.app import space_curve as space_curve_feature
from varsurf.app.feature import FeatureProxy, mark_failed, value
from varsurf.solve import assembly, errors, joint, settings

TYPE = "VarSurf::Solid"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Sheets", "App::PropertyLinkList", "Solid", "The Sheets to join; each is trimmed to the curves it shares with the others", False),
    ("Tolerance", "App::PropertyLength", "Solid", "How far a sheet may pass from a join curve; give at least the sheets' own Tolerance (they meet their curves only that closely). The shared edges' tolerances come from the measured deviation", False),
    ("ToleranceFromSheets", "App::PropertyBool", "Solid", "Tolerance follows the Sheets: twice the largest of their Tolerance, so a model of any size is joined as closely as its sheets meet their curves. Typing a Tolerance turns this off", False),
    ("Closed", "App::PropertyBool", "Result", "True if the sheets close into a solid", True),
    ("MaxEdgeTolerance", "App::PropertyFloat", "Result", "Worst edge/vertex tolerance after sewing (mm)", True),
    ("SeamGaps", "App::PropertyFloatList", "Result", "Per join curve: the largest distance from a sheet to it (mm)", True),
    ("SeamCurves", "App::PropertyStringList", "Result", "The curves the sheets are joined along (or bounded by), in the order of SeamGaps", True),
    ("SeamAngles", "App::PropertyFloatList", "Result", "Per shared edge: the smallest and largest angle between the faces across it (degrees, pairs; 180 is tangent-continuous)", True),
    ("ThinnestWall", "App::PropertyFloat", "Result", "The solid's thinnest wall near its seams: its thickness 0.5 % of its size inside them (mm); FreeCAD's booleans, fillets and offsets fail on walls near zero", True),
    ("Hinges", "App::PropertyLinkList", "Solid", "Hinges: the angle between two of the Sheets across a curve they share (solved with the sheets as one system)", False),
    ("HingeAngles", "App::PropertyFloatList", "Result", "Per hinge: the smallest and largest angle reached along its curve (degrees, pairs)", True),
    ("HingeErrors", "App::PropertyFloatList", "Result", "Per hinge: the largest difference from its Angle along the curve (degrees)", True),
    ("JointSolve", "App::PropertyString", "Result", "How the sheets were solved together (hinges, variational curves), or empty when each sheet's own solve stands", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]
#: A Solid following its sheets joins them within this multiple of their largest Tolerance: a
#: sheet meets its curves within its own, and the join measures the distance again (projection).
SHEETS_TOLERANCE_FACTOR = 2.0
DEFAULT_TOLERANCE = SHEETS_TOLERANCE_FACTOR * settings.DEFAULT_TOLERANCE
#: A hinge farther than this from its angle anywhere along its curve is warned about (degrees).
HINGE_ANGLE_TOLERANCE = 0.05


def join_inputs(obj):
    """[(label, face, [(key, shared edge)], [(key, own edge)])] for the Solid's Sheets, or
    SheetError."""
    sheets = list(obj.Sheets or [])
    if not sheets:
        raise errors.SheetError("Sheets is empty: select the Sheets to join")
    counts = {}
    for s in sheets:
        if s.Shape.isNull() or len(s.Shape.Faces) != 1:
            raise errors.SheetError(f"{s.Label} has no result: recompute it first (is it in error?)")
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
    return (f" (with hinges {', '.join(names)}: let the curves that meet a hinged seam at its ends "
            "leave it at the hinge's angle)")


def _in_error(sheet) -> bool:
    """Whether a Sheet failed its last recompute."""
    return not sheet.isValid() or str(getattr(sheet, "Status", "")).startswith("Error")


def sheets_error(obj) -> str:
    """What is wrong while some of the Solid's Sheets are in error (their last result is stale),
    else an empty string."""
    broken = [s for s in (obj.Sheets or []) if _in_error(s)]
    if not broken:
        return ""
    reasons = []
    for s in broken:
        status = str(getattr(s, "Status", ""))
        reason = status[len("Error: "):] if status.startswith("Error: ") else s.getStatusString()
        reasons.append(f"{s.Label} is in error ({reason})")
    return "; ".join(reasons) + f": repair {'it' if len(broken) == 1 else 'them'} and the Solid follows"


def sheets_tolerance(obj) -> float:
    """SHEETS_TOLERANCE_FACTOR times the largest Tolerance of the Solid's Sheets."""
    tolerances = [float(value(s, "Tolerance")) for s in (obj.Sheets or []) if "Tolerance" in s.PropertiesList]
    return SHEETS_TOLERANCE_FACTOR * max(tolerances) if tolerances else DEFAULT_TOLERANCE


_writing_tolerance = False  # the Solid itself is setting Tolerance (not the user)


def _tolerance(obj) -> float:
    """The tolerance the Solid joins with: its sheets' (written to Tolerance) while it follows
    them, else its own Tolerance."""
    global _writing_tolerance
    if not bool(getattr(obj, "ToleranceFromSheets", False)):
        return float(value(obj, "Tolerance"))
    tolerance = sheets_tolerance(obj)
    if abs(float(value(obj, "Tolerance")) - tolerance) > 1e-12 * tolerance:
        _writing_tolerance = True
        try:
            obj.Tolerance = tolerance
        finally:
            _writing_tolerance = False
    return tolerance


def _tolerance_hint(obj, tolerance) -> str:
    """A Solid's Tolerance below its sheets' own: say so, with what to do."""
    own = sheets_tolerance(obj) / SHEETS_TOLERANCE_FACTOR
    if tolerance >= own:
        return ""
    return (f" (the Solid's Tolerance is below its sheets' own, up to {own:.3g} mm: raise it, or turn "
            "ToleranceFromSheets on)")


def is_solid(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE


class _SheetErrorWatch:
    """FreeCAD skips what depends on an object whose recompute failed and leaves it marked up to
    date, so a Solid would go on showing OK over a Sheet in error. After each recompute of a
    document, each Solid over a Sheet in error is recomputed on its own: it fails too, naming the
    sheet, and is recomputed with the sheet once that is repaired."""

    busy = False

    def slotRecomputedDocument(self, doc):
        if self.busy:
            return
        self.busy = True
        try:
            for obj in list(doc.Objects):
                if not is_solid(obj) or obj.Proxy.state_problem() is not None:
                    continue
                problem = sheets_error(obj)
                if problem and str(getattr(obj, "Status", "")) != f"Error: {problem}":
                    obj.recompute()
        finally:
            self.busy = False


_WATCH = None


def _watch_sheets():
    """Install the document observer that keeps Solids in step with their Sheets' errors."""
    global _WATCH
    if _WATCH is None:
        _WATCH = _SheetErrorWatch()
        FreeCAD.addDocumentObserver(_WATCH)


class SolidFeature(FeatureProxy):
    """Proxy of a VarSurf Solid (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderSolid"
    PROPERTIES = _PROPERTIES
    DEFAULTS = {"Tolerance": DEFAULT_TOLERANCE, "ToleranceFromSheets": True}

    def __init__(self, obj):
        super().__init__(obj)
        _watch_sheets()

    def onDocumentRestored(self, obj):
        older = "ToleranceFromSheets" not in obj.PropertiesList
        super().onDocumentRestored(obj)
        if self.state_problem() is not None:
            return
        if older:  # files from before Solids followed their sheets keep their Tolerance
            obj.ToleranceFromSheets = False
        _watch_sheets()

    def onChanged(self, obj, prop):
        # A Tolerance typed by the user (not written by the Solid, a file being read or undo/redo)
        # stops the Solid following its sheets.
        if prop != "Tolerance" or _writing_tolerance or "ToleranceFromSheets" not in obj.PropertiesList:
            return
        doc = obj.Document
        if doc is None or doc.Restoring or doc.Transacting or "Restore" in obj.State:
            return
        if obj.ToleranceFromSheets:
            obj.ToleranceFromSheets = False

    def consumed(self, obj):
        return list(obj.Sheets)  # the Solid shows their faces

    def execute(self, obj):
        try:
            problem = sheets_error(obj)
            if problem:  # their last results are stale: nothing is joined
                raise errors.SheetError(problem)
            inputs = _solve_together(obj, join_inputs(obj))
            tolerance = _tolerance(obj)
            try:
                outcome = assembly.build_solid(inputs, tolerance)
            except assembly.JoinGapError as error:
                raise errors.SheetError(f"{error}{_hinge_blame(obj)}{_tolerance_hint(obj, tolerance)}") from error
            if not outcome.valid:
                raise errors.SheetError("the sewn shape is not valid: raise the Solid's Tolerance, or check that "
                                        "the Sheets meet along the curves they share (SeamGaps)")
        except Exception as error:
            raise mark_failed(obj, error) from error
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
        if math.isfinite(outcome.thinnest_wall):  # measured for closed solids only
            obj.ThinnestWall = outcome.thinnest_wall
            x, y, z = outcome.thinnest_wall_at
            obj.Status += (f"; thinnest wall {outcome.thinnest_wall:.3g} mm at {outcome.wall_depth:.3g} mm inside "
                           f"a seam, at ({x:.4g}, {y:.4g}, {z:.4g})")
        _warn_of_knife_edges(obj, outcome)


def _warn_of_knife_edges(obj, outcome):
    """Say where the faces meet so sharply that FreeCAD's own operations will fail on the seam."""
    hinges = [h.Angle.Value if hasattr(h.Angle, "Value") else float(h.Angle) for h in obj.Hinges if h.Enabled]
    knives = assembly.knife_edges(outcome, hinges)
    if not knives:
        return
    angle, (x, y, z) = knives[0]
    many = f"{len(knives)} seams are knife edges" if len(knives) > 1 else "a seam is a knife edge"
    obj.Status += f"; {many}, the sharpest {angle:.2g}° at ({x:.4g}, {y:.4g}, {z:.4g})"
    FreeCAD.Console.PrintWarning(
        f"VarSurf: {obj.Label}: {many}: its faces meet at {angle:.2g}° at ({x:.4g}, {y:.4g}, {z:.4g}) "
        f"(below {assembly.KNIFE_EDGE:g}°); booleans, fillets and offsets of FreeCAD fail on such a seam. "
        "Let the sheets meet at a wider angle (less pressure, curves that open the seam), or hold the angle "
        "with a Hinge if it is meant\n")
