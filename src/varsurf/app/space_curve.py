# SPDX-License-Identifier: LGPL-2.1-or-later
"""The SpaceCurve feature: a variational space curve (Welch & Witkin sec. 5, Figure 2).

A ``Part::FeaturePython`` whose ``Shape`` is one edge: the ``Base`` edge reshaped by its handles,
the points at ``HandleParameters`` (0..1 along the base) moved to ``Handles``, with the least
bending of the displacement. Sheets list this edge among their Curves like any other; in a Solid
its poles become unknowns of the joint solve, so moving a handle moves the curve and every sheet
joined along it. App side only.
"""

from __future__ import annotations

import Part

from varsurf.app.feature import FeatureProxy, mark_failed
from varsurf.solve import errors, shapes, space_curve
from varsurf.solve.native import native

TYPE = "VarSurf::SpaceCurve"

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Base", "App::PropertyLinkSub", "SpaceCurve", "The edge the curve starts from: its rest shape", False),
    ("HandleParameters", "App::PropertyFloatList", "SpaceCurve", "Where the handles sit on the curve, 0..1 along the base edge", False),
    ("Handles", "App::PropertyVectorList", "SpaceCurve", "Where each handle's curve point must go (one per HandleParameters)", False),
    ("Spans", "App::PropertyIntegerConstraint", "SpaceCurve", "Spans of the curve's B-spline: the freedom it has to bend", False),
    ("Stretch", "App::PropertyFloat", "SpaceCurve", "Weight of the displacement's first derivative (>= 0)", False),
    ("Bend", "App::PropertyFloat", "SpaceCurve", "Weight of the displacement's second derivative (>= 0)", False),
    ("Status", "App::PropertyString", "Result", "OK, or what went wrong", True),
]


def base_edge(obj):
    if obj.Base is None:
        raise errors.SheetError("Base is empty: select the edge the curve starts from")
    link, subs = obj.Base
    subs = [s for s in subs if s]
    if len(subs) != 1 or not subs[0].startswith("Edge"):
        raise errors.SheetError(f"Base must reference exactly one edge of {link.Label}: pick one edge (EdgeN) in the "
                                "Base property")
    edge = Part.getShape(link, subs[0], needSubElement=True)
    if edge.isNull():
        raise errors.SheetError(f"{link.Label}:{subs[0]} does not exist (anymore): the object has changed; select "
                                "the edge again")
    return edge


def variational_curve(obj):
    """(VariationalCurve for joint solves, rest Part curve) of a SpaceCurve's inputs."""
    edge = base_edge(obj)
    rest = space_curve.rest_curve(edge, int(obj.Spans))
    nat = native()
    handles = space_curve.handles_at(rest, list(obj.HandleParameters), list(obj.Handles))
    for label, value in (("Stretch", obj.Stretch), ("Bend", obj.Bend)):
        if not value >= 0.0 or value == float("inf"):
            raise errors.SheetError(f"{label} must be finite and >= 0 (got {value}): set the curve's {label} "
                                    "to 0 or more")
    return space_curve.VariationalCurve(
        start=space_curve.to_native(nat, rest), handles=handles,
        stretch=float(obj.Stretch), bend=float(obj.Bend), closed=edge.isClosed()), rest


def is_space_curve(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE


class SpaceCurveFeature(FeatureProxy):
    """Proxy of a VarSurf SpaceCurve (Part::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderSpaceCurve"
    PROPERTIES = _PROPERTIES
    DEFAULTS = {
        "Spans": (space_curve.DEFAULT_SPANS, 1, 512, 1),
        "Stretch": space_curve.DEFAULT_STRETCH,
        "Bend": space_curve.DEFAULT_BEND,
    }

    def execute(self, obj):
        try:
            curve, _rest = variational_curve(obj)
            solved = space_curve.solve_alone(curve)
        except Exception as error:
            raise mark_failed(obj, error) from error
        obj.Shape = shapes.part_curve(solved).toShape()
        obj.Status = f"OK: {len(curve.handles)} handles, {len(solved.poles)} poles"
