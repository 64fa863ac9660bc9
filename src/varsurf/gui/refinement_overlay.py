"""The spans a locally refined Sheet refined, outlined on the sheet (view property
ShowRefinement): one color per level, so a user sees where the detail went."""

from __future__ import annotations

from pivy import coin

from varsurf.analysis import refined_outlines

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
        self.root = coin.SoSeparator()
        vobj.RootNode.addChild(self.root)
        self.count = 0

    def update(self, vobj):
        self.root.removeAllChildren()
        self.count = 0
        obj = vobj.Object
        spans = list(getattr(obj, "RefinedSpans", []) or [])
        if not getattr(vobj, PROPERTY, False) or not spans or obj.Shape.isNull() or not obj.Shape.Faces:
            return
        style = coin.SoDrawStyle()
        style.lineWidth = 2.0
        self.root.addChild(style)
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        self.root.addChild(light)
        for level, points in refined_outlines(obj.Shape.Faces[0], spans):
            sep = coin.SoSeparator()
            material = coin.SoMaterial()
            material.diffuseColor.setValue(*LEVEL_COLORS[level % len(LEVEL_COLORS)])
            sep.addChild(material)
            coords = coin.SoCoordinate3()
            coords.point.setValues(0, len(points), points)
            sep.addChild(coords)
            line = coin.SoLineSet()
            line.numVertices.setValue(len(points))
            sep.addChild(line)
            self.root.addChild(sep)
            self.count += 1
