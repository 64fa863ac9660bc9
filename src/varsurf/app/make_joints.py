# SPDX-License-Identifier: LGPL-2.1-or-later
"""The make-functions for what couples sheets in a Solid: variational space curves and hinges.

    curve = varsurf.make_space_curve((sketch, "Edge1"))         # handles at both ends and midway
    ... sheets list (curve, "Edge1") among their curves ...
    solid = varsurf.make_solid(sheets)
    varsurf.make_hinge(solid, sheet_a, sheet_b, (sketch, "Edge2"), angle=180)
    varsurf.move_handle(curve, 1, App.Vector(0, 0, 10)); App.ActiveDocument.recompute()
"""

from __future__ import annotations

from typing import Optional, Sequence

import FreeCAD
import Part

from varsurf.app import references
from varsurf.app.hinge import HingeFeature
from varsurf.app.make import attach_view_provider
from varsurf.app.space_curve import SpaceCurveFeature

#: Where a new space curve's handles sit (0..1 along the base edge).
DEFAULT_HANDLE_PARAMETERS = (0.0, 0.5, 1.0)


def make_space_curve(base, handle_parameters: Optional[Sequence[float]] = None,
                     handles: Optional[Sequence] = None, spans: Optional[int] = None,
                     name: str = "SpaceCurve"):
    """Add a variational SpaceCurve starting from the edge ``base`` = (object, "EdgeN").

    handle_parameters: where its handles sit, 0..1 along the edge (default both ends and the
    middle); handles: their positions (default: on the edge, so nothing moves until one is moved).
    """
    obj_ref, sub = references.edge_ref(base)
    edge = Part.getShape(obj_ref, sub, needSubElement=True)
    params = [float(s) for s in (handle_parameters if handle_parameters is not None else DEFAULT_HANDLE_PARAMETERS)]
    if handles is None:
        a, b = edge.FirstParameter, edge.LastParameter
        handles = [edge.valueAt(a + (b - a) * s) for s in params]
    obj = obj_ref.Document.addObject("Part::FeaturePython", name)
    SpaceCurveFeature(obj)
    obj.Base = (obj_ref, [sub])
    obj.HandleParameters = params
    obj.Handles = [FreeCAD.Vector(*p) for p in handles]
    if spans is not None:
        obj.Spans = int(spans)
    attach_view_provider(obj, "ViewProviderSpaceCurve")
    return obj


def move_handle(curve, index: int, position) -> None:
    """Move handle ``index`` of a SpaceCurve to ``position`` (recompute to see the sheets follow)."""
    handles = list(curve.Handles)
    if not 0 <= int(index) < len(handles):
        raise ValueError(f"{curve.Label} has {len(handles)} handles, no handle {index}: give an index "
                         f"in 0..{len(handles) - 1}")
    handles[int(index)] = FreeCAD.Vector(position)
    curve.Handles = handles


def make_hinge(solid, sheet_a, sheet_b, curve, angle: float = 180.0, name: str = "Hinge"):
    """Add a Hinge to ``solid``: the angle (degrees, (0, 180]; 180 smooth) between ``sheet_a``
    and ``sheet_b`` across ``curve`` = (object, "EdgeN"), an edge both Sheets list."""
    for s in (sheet_a, sheet_b):
        if s not in list(solid.Sheets or []):
            raise ValueError(f"{s.Label} is not one of {solid.Label}'s Sheets: add it to the Solid first")
    obj_ref, sub = references.edge_ref(curve)
    obj = solid.Document.addObject("App::FeaturePython", name)
    HingeFeature(obj)
    obj.Sheets = [sheet_a, sheet_b]
    obj.Curve = (obj_ref, [sub])
    obj.Angle = float(angle)
    solid.Hinges = list(solid.Hinges or []) + [obj]
    attach_view_provider(obj, "ViewProviderHinge")
    return obj
