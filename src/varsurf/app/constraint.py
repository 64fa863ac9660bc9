# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Constraint feature: one constraint or energy operator of a Sheet, as a document object.

An ``App::FeaturePython`` listed in its Sheet's ``Constraints``. Its position on the sheet is a
picked vertex (``Location``, projected onto the sheet's base) or normalized ``U``/``V``; operators
act on a normalized region. ``Weight`` is the constraint's weight or the operator's strength. App
side only: no GUI import.
"""

from __future__ import annotations

import FreeCAD
import Part

from varsurf.app.feature import FeatureProxy, failure, value
from varsurf.solve import constraints

TYPE = "VarSurf::Constraint"

# name, type, group, tooltip
_PROPERTIES = [
    ("Kind", "App::PropertyEnumeration", "Constraint", "What the constraint asks of the sheet"),
    ("Enabled", "App::PropertyBool", "Constraint", "Off: the Sheet ignores this constraint"),
    ("Location", "App::PropertyLinkSub", "Constraint", "A vertex: its projection onto the base gives (u, v); for Point it is also the target"),
    ("U", "App::PropertyFloat", "Constraint", "Normalized u in [0, 1], used when there is no Location"),
    ("V", "App::PropertyFloat", "Constraint", "Normalized v in [0, 1], used when there is no Location"),
    ("Vector", "App::PropertyVector", "Constraint", "Tangent, normal, plane normal, line or director direction"),
    ("Origin", "App::PropertyVector", "Constraint", "Plane, line or attractor point (Point: the target when there is no Location)"),
    ("UseOrigin", "App::PropertyBool", "Constraint", "Use Origin even when a Location is set (a Point without Location needs it)"),
    ("RegionU0", "App::PropertyFloat", "Region", "Normalized region start along u (operators, frozen region, region map)"),
    ("RegionU1", "App::PropertyFloat", "Region", "Normalized region end along u"),
    ("RegionV0", "App::PropertyFloat", "Region", "Normalized region start along v"),
    ("RegionV1", "App::PropertyFloat", "Region", "Normalized region end along v"),
    ("Weight", "App::PropertyFloat", "Constraint", "Weight of a constraint, or strength of an operator (>= 0)"),
    ("RegionLoop", "App::PropertyLinkSub", "Region", "Closed edges (e.g. a sketch): the region is the part of the sheet they enclose, projected onto the base; overrides RegionU0..V1"),
    ("Curve", "App::PropertyLinkSub", "Ribbon", "Ribbon, G1 and G2: the edge along which the sheet's orientation is set; CurveAttractor: the edge pulled onto; CurveMap: the source curve on the sheet"),
    ("Reference", "App::PropertyLinkSub", "Ribbon", "G1, G2, Ribbon: the face whose normal (G2: and curvature) the sheet follows along Curve (Ribbon: or a second edge; empty: the base's normal); SurfaceAttractor: the face pulled onto; CurveMap: the destination edge; RegionMap: the destination face"),
    ("Angle", "App::PropertyAngle", "Ribbon", "Ribbon: the sheet's normal is the Reference's turned by this angle about Curve"),
    ("CurvatureU", "App::PropertyFloat", "Curvature", "Curvature: the sheet's normal curvature along u at the point, in 1/mm (1 / radius; positive: it bends toward the side Vector points to)"),
    ("CurvatureV", "App::PropertyFloat", "Curvature", "Curvature: the sheet's normal curvature along v at the point, in 1/mm"),
    ("CurvatureDirections", "App::PropertyEnumeration", "Curvature", "Curvature: which of CurvatureU and CurvatureV the sheet must have (the other is left to its energy)"),
]


_DEFAULTS = {
    "Kind": list(constraints.KINDS),
    "Enabled": True,
    "U": 0.5,
    "V": 0.5,
    "Vector": FreeCAD.Vector(0, 0, 1),
    "RegionU1": 1.0,
    "RegionV1": 1.0,
    "Weight": 1.0,
    "CurvatureDirections": list(constraints.CURVATURE_DIRECTIONS),
}


def _location_point(obj):
    if obj.Location is None:
        return None
    link, subs = obj.Location
    subs = [s for s in subs if s]
    shape = Part.getShape(link, subs[0], needSubElement=True) if subs else link.Shape
    if shape.isNull() or not shape.Vertexes:
        raise constraints.ConstraintError(f"{obj.Label}: Location must be a vertex: link a vertex "
                                          "(VertexN) as its Location")
    p = shape.Vertexes[0].Point
    return (p.x, p.y, p.z)


def _sub_shape(obj, prop, kinds):
    """The one element `prop` links to, of one of the shape types `kinds` (e.g. ("Face",))."""
    link = getattr(obj, prop, None)
    if link is None:
        return None
    target, subs = link
    subs = [s for s in subs if s]
    what = " or ".join(k.lower() for k in kinds)
    if not subs:
        raise constraints.ConstraintError(f"{obj.Label}: {prop} must name one {what} of {target.Label}: "
                                          "select it again")
    shape = Part.getShape(target, subs[0], needSubElement=True)
    if shape.isNull() or shape.ShapeType not in kinds:
        raise constraints.ConstraintError(f"{obj.Label}: {prop} must be a {what} (got {subs[0]}): link "
                                          f"a {what} as its {prop}")
    return shape


def _loop_shape(obj):
    """The edges RegionLoop links to (all of the object's edges when no element is named)."""
    link = getattr(obj, "RegionLoop", None)
    if link is None:
        return None
    target, subs = link
    subs = [s for s in subs if s]
    if not subs:
        shape = target.Shape
    else:
        shape = Part.Compound([Part.getShape(target, sub, needSubElement=True) for sub in subs])
    if shape.isNull() or not shape.Edges:
        raise constraints.ConstraintError(f"{obj.Label}: RegionLoop must be closed edges (got {target.Label}): "
                                          "link the closed edges around the region")
    return shape


def spec_of(obj) -> constraints.ConstraintSpec:
    """The ConstraintSpec a Constraint object describes (validated)."""
    location = _location_point(obj)
    origin = None
    # A Point's target is its vertex; Origin stands in only when asked to (UseOrigin), so a
    # deleted vertex is an error rather than a silent pull toward (0, 0, 0).
    if obj.UseOrigin or (location is None and str(obj.Kind) != "Point"):
        origin = tuple(value(obj, "Origin"))
    spec = constraints.ConstraintSpec(
        kind=str(obj.Kind),
        name=obj.Label,
        location=location,
        uv=None if location is not None else (float(obj.U), float(obj.V)),
        vector=tuple(value(obj, "Vector")),
        origin=origin,
        region=(float(obj.RegionU0), float(obj.RegionU1), float(obj.RegionV0), float(obj.RegionV1)),
        weight=float(obj.Weight),
        edge=_sub_shape(obj, "Curve", ("Edge",)),
        reference=_sub_shape(obj, "Reference", ("Face", "Edge")),
        angle=float(value(obj, "Angle")),
        region_loop=_loop_shape(obj),
        curvature=(float(obj.CurvatureU), float(obj.CurvatureV)),
        curvature_directions=str(obj.CurvatureDirections),
    )
    spec.validate()
    return spec


class ConstraintFeature(FeatureProxy):
    """Proxy of a VarSurf Constraint (App::FeaturePython)."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderConstraint"
    PROPERTIES = _PROPERTIES
    DEFAULTS = _DEFAULTS

    def onDocumentRestored(self, obj):
        super().onDocumentRestored(obj)
        if self.state_problem() is not None:
            return
        # Files from before a kind was added list fewer kinds: offer them all, keep the choice.
        if list(obj.getEnumerationsOfProperty("Kind")) != list(constraints.KINDS):
            kind = str(obj.Kind)
            obj.Kind = list(constraints.KINDS)
            obj.Kind = kind

    def execute(self, obj):
        # Check the constraint's own data now, so a bad one is marked itself, not only its Sheet.
        try:
            spec_of(obj)
        except Exception as error:
            raise failure(obj, error) from error
