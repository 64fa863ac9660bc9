# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Hinge feature: the angle between two Sheets across a curve they share (Welch & Witkin
4.2.2 and sec. 5). 180 degrees makes the seam tangent-continuous (G1).

An ``App::FeaturePython`` listed in a Solid's ``Hinges``: the Solid solves its sheets together
and holds each hinge's angle all along the curve; it reports the angles reached. App side only.
"""

from __future__ import annotations

from varsurf.app.feature import FeatureProxy, failure, value
from varsurf.solve import errors
from varsurf.solve.joint import HingeSpec

TYPE = "VarSurf::Hinge"
DEFAULT_ANGLE = 180.0

# name, type, group, tooltip, output?
_PROPERTIES = [
    ("Sheets", "App::PropertyLinkList", "Hinge", "The two Sheets meeting at the hinge", False),
    ("Curve", "App::PropertyLinkSub", "Hinge", "The curve both Sheets pass through (an edge both list in their Curves)", False),
    ("Angle", "App::PropertyAngle", "Hinge", "Angle between the sheets across the curve, in (0, 180] degrees; 180 is a smooth (tangent-continuous) seam", False),
    ("Enabled", "App::PropertyBool", "Hinge", "Off: the Solid ignores this hinge", False),
]


def is_hinge(obj) -> bool:
    return getattr(getattr(obj, "Proxy", None), "Type", None) == TYPE


def curve_key(obj) -> str:
    if obj.Curve is None:
        raise errors.SheetError(f"{obj.Label}: Curve is empty: select the shared edge")
    link, subs = obj.Curve
    subs = [s for s in subs if s]
    if len(subs) != 1 or not subs[0].startswith("Edge"):
        raise errors.SheetError(f"{obj.Label}: Curve must reference exactly one edge: pick the edge the two Sheets "
                                "share")
    return f"{link.Name}:{subs[0]}"


def spec_of(obj):
    """The joint solve's HingeSpec of a Hinge (SheetError if its links are wrong)."""
    sheets = list(obj.Sheets or [])
    if len(sheets) != 2:
        raise errors.SheetError(f"{obj.Label}: a hinge needs exactly two Sheets (has {len(sheets)}): set its Sheets to "
                                "the two it joins")
    angle = value(obj, "Angle")
    angle = float(angle.Value if hasattr(angle, "Value") else angle)
    return HingeSpec(name=obj.Label, key=curve_key(obj), sheet_a=sheets[0].Label,
                     sheet_b=sheets[1].Label, angle=angle)


class HingeFeature(FeatureProxy):
    """Proxy of a VarSurf Hinge (App::FeaturePython): data only, solved by its Solid."""

    Type = TYPE
    TYPE = TYPE
    VIEW_PROVIDER = "ViewProviderHinge"
    PROPERTIES = _PROPERTIES
    DEFAULTS = {"Angle": DEFAULT_ANGLE, "Enabled": True}

    def execute(self, obj):
        try:
            spec_of(obj)  # a broken link is reported on the hinge itself
        except errors.SheetError as error:
            raise failure(obj, error) from error
