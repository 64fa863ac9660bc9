# SPDX-License-Identifier: LGPL-2.1-or-later
"""The spans a locally refined Sheet refined, outlined on the sheet (view property
ShowRefinement): one color per level, so a user sees where the detail went."""

from __future__ import annotations

from varsurf.gui.coin_lines import add_polyline
from varsurf.gui.scene_roots import own_root
from varsurf.solve.analysis import refined_outlines

PROPERTY = "ShowRefinement"
#: Outline colors by level (repeating).
LEVEL_COLORS = [(0.9, 0.5, 0.0), (0.1, 0.6, 0.9), (0.8, 0.1, 0.6), (0.2, 0.7, 0.2)]


def add_view_property(vobj):
    if PROPERTY not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyBool", PROPERTY, "VarSurf",
                         "Outline the spans local refinement refined, colored by level")
        setattr(vobj, PROPERTY, False)


class RefinementOverlay:
    def __init__(self, vobj):
        self.root = own_root(vobj, "VarSurfRefinement")
        self.count = 0

    def update(self, vobj):
        self.root.removeAllChildren()
        self.count = 0
        obj = vobj.Object
        spans = list(getattr(obj, "RefinedSpans", []) or [])
        if not getattr(vobj, PROPERTY, False) or not spans or obj.Shape.isNull() or not obj.Shape.Faces:
            return
        for level, points in refined_outlines(obj.Shape.Faces[0], spans):
            add_polyline(self.root, points, LEVEL_COLORS[level % len(LEVEL_COLORS)], 2.0, unlit=True)
            self.count += 1
