# SPDX-License-Identifier: LGPL-2.1-or-later
"""The FillHole feature: a part with one face replaced by a sheet, or a hole among its free edges
filled by one, G0 or G1 to the faces around it; its Shape is the whole new part (a solid when it
closes). Parametric: editing the part (a box's height, a fillet's radius) or an interior curve
recomputes it. The computation is varsurf.solve.hole."""

from __future__ import annotations

import re

import Part

from varsurf.app.feature import FeatureProxy, mark_failed, value
from varsurf.solve import errors, hole
from varsurf.solve.settings import SheetSettings

TYPE = "VarSurf::FillHole"
DEFAULT_TOLERANCE = 0.001

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Base", "App::PropertyLinkSub", "FillHole", "The part and either the face to replace (one FaceN) or the free edges around the hole (EdgeN...)", False),
    ("Curves", "App::PropertyLinkSubList", "FillHole", "Curves inside the hole that the sheet contains (e.g. a sketch's arcs)", False),
    ("Continuity", "App::PropertyEnumeration", "FillHole", "G1: the sheet is tangent to the face across each edge; G2: it also continues its curvature (iterated); G0: it only ends on the edges", False),
    ("Tolerance", "App::PropertyLength", "FillHole", "How closely the sheet meets its edges and curves (mm); the sewing joins within four times this", False),
    ("Closed", "App::PropertyBool", "Result", "True if the filled part is a closed solid", True),
    ("MaxEdgeTolerance", "App::PropertyFloat", "Result", "Worst edge/vertex tolerance after sewing (mm)", True),
    ("JoinNames", "App::PropertyStringList", "Result", "The hole's edges, in the order of the join figures", True),
    ("JoinGaps", "App::PropertyFloatList", "Result", "Per hole edge: the largest gap between the sheet and the face around it (mm), measured at 200 points", True),
    ("JoinAngles", "App::PropertyFloatList", "Result", "Per hole edge (G1): the largest angle between the sheet's and the face's tangent planes (degrees)", True),
    ("JoinCurvatureJumps", "App::PropertyFloatList", "Result", "Per hole edge (G1): the largest jump of normal curvature across it (percent; 0 would be G2)", True),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]

_ELEMENT = re.compile(r"^(Face|Edge)([1-9][0-9]*)$")


def hole_elements(obj):
    """(part shape, face indices to replace, free edges) from Base."""
    base = obj.Base
    if not base or base[0] is None:
        raise errors.SheetError("no Base: link the part and the face to replace (or the free edges of the hole)")
    part, subs = base[0], [s for s in base[1] if s]
    shape = getattr(part, "Shape", None)
    if shape is None or shape.isNull():
        raise errors.SheetError(f"{part.Label} has no shape to fill a hole in: recompute it, or link a solid "
                                "or shell as Base")
    faces, edges = [], []
    for sub in subs:
        found = _ELEMENT.match(sub)
        if not found:
            raise errors.SheetError(f"{part.Label}.{sub} is neither a face nor an edge: select the face to replace "
                                    "or the free edges around the hole")
        index = int(found.group(2)) - 1
        if found.group(1) == "Face":
            if index >= len(shape.Faces):
                raise errors.SheetError(f"{part.Label} has no {sub} (it has {len(shape.Faces)} faces): select it again")
            faces.append(index)
        else:
            if index >= len(shape.Edges):
                raise errors.SheetError(f"{part.Label} has no {sub} (it has {len(shape.Edges)} edges): select it again")
            edges.append(shape.Edges[index])
    if not faces and not edges:
        raise errors.SheetError(f"no face or edge of {part.Label} is selected: select the face to replace "
                                "or the free edges around the hole")
    return shape, faces, edges


def interior_curves(obj):
    curves = []
    for link, subs in obj.Curves or []:
        for sub in subs or [""]:
            shape = Part.getShape(link, sub, needSubElement=True) if sub else link.Shape
            curves += list(shape.Edges)
    return curves


class FillHoleFeature(FeatureProxy):
    """Proxy of a VarSurf FillHole (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderFillHole"
    PROPERTIES = _PROPERTIES
    DEFAULTS = {"Tolerance": DEFAULT_TOLERANCE}

    def add_properties(self, obj):
        super().add_properties(obj)
        enumerations = list(obj.getEnumerationsOfProperty("Continuity"))
        if enumerations != list(hole.CONTINUITIES):  # new, or saved before G2 existed
            was = str(obj.Continuity) if enumerations else "G1"  # G1: the default
            obj.Continuity = list(hole.CONTINUITIES)
            obj.Continuity = was

    def consumed(self, obj):
        base = getattr(obj, "Base", None)
        return [base[0]] if base and base[0] is not None else []  # the FillHole is the whole part

    def execute(self, obj):
        try:
            shape, faces, edges = hole_elements(obj)
            settings = SheetSettings(tolerance=float(value(obj, "Tolerance")))
            outcome = hole.fill_hole(shape, replace=faces, edges=edges, curves=interior_curves(obj),
                                     continuity_kind=str(obj.Continuity), settings=settings)
            if not outcome.valid:
                raise errors.SheetError("the filled part is not a valid shape: try a larger Tolerance, or G0 continuity")
        except Exception as error:
            raise mark_failed(obj, error) from error
        obj.Shape = outcome.shape
        obj.Closed = outcome.closed
        obj.MaxEdgeTolerance = outcome.max_tolerance
        obj.JoinNames = [j.name for j in outcome.joins]
        obj.JoinGaps = [j.gap for j in outcome.joins]
        obj.JoinAngles = [j.angle for j in outcome.joins if j.angle == j.angle]
        obj.JoinCurvatureJumps = [j.curvature_jump for j in outcome.joins if j.curvature_jump == j.curvature_jump]
        kind = "solid" if outcome.closed else f"open shell ({outcome.free_edges} free edges)"
        obj.Status = (f"OK: {kind}, worst edge tolerance {outcome.max_tolerance:.3g} mm, largest gap to the faces "
                      f"around {max(obj.JoinGaps, default=0.0):.3g} mm")
        if obj.JoinAngles:
            obj.Status += f", largest angle {max(obj.JoinAngles):.3g}°"
        if str(obj.Continuity) == "G2":
            obj.Status += (f", largest curvature jump {max(obj.JoinCurvatureJumps, default=0.0):.3g} % "
                           f"(G2 in {outcome.sheet.curvature_iterations} Newton steps)")
