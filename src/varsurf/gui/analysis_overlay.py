# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Sheet's analysis color map in the 3D view: the grid of varsurf.solve.analysis as a Coin mesh with
per-vertex colors, drawn just in front of the sheet's own shading (a polygon offset)."""

from __future__ import annotations

import FreeCAD as App
import Part
from pivy import coin

from varsurf.app.analysis import reference_of
from varsurf.gui.coin_lines import add_polyline
from varsurf.gui.scene_roots import own_root
from varsurf.solve import analysis

PROPERTY = "Analysis"
RANGE_PROPERTY = "AnalysisRange"


def add_view_properties(vobj):
    """The view properties of the color map (added once; kept in the file)."""
    if PROPERTY not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyEnumeration", PROPERTY, "VarSurf",
                         "Color map on the sheet: deviation from the base (or installed rest shape), "
                         "mean or Gaussian curvature, or zebra stripes")
        setattr(vobj, PROPERTY, list(analysis.MODES))
        setattr(vobj, PROPERTY, "None")
    if RANGE_PROPERTY not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyString", RANGE_PROPERTY, "VarSurf",
                         "The values the colors span (blue to red)")
        vobj.setEditorMode(RANGE_PROPERTY, 1)


def _sheet_edges(obj):
    edges = []
    for link, subs in getattr(obj, "Curves", None) or []:
        for sub in subs:
            if sub:
                edges.append(Part.getShape(link, sub, needSubElement=True))
    return edges


class AnalysisOverlay:
    """A switchable Coin mesh under the Sheet's view provider root."""

    def __init__(self, vobj):
        self.root = own_root(vobj, "VarSurfAnalysis")
        self.grid = None
        self.curves = None

    def update(self, vobj):
        self.root.removeAllChildren()
        self.grid = None
        self.curves = None
        mode = str(getattr(vobj, PROPERTY, "None"))
        obj = vobj.Object
        if mode == "None" or obj.Shape.isNull():
            setattr(vobj, RANGE_PROPERTY, "")
            return
        if mode == "CurveDeviation":
            self._curves(vobj, obj)
            return
        try:
            grid = analysis.analyse(obj.Shape, mode, reference=reference_of(obj))
        except Exception as error:
            setattr(vobj, RANGE_PROPERTY, f"unavailable: {error}")
            App.Console.PrintWarning(
                App.Qt.translate("VarSurf", "VarSurf: {}: no {} map ({})").format(obj.Label, mode, error) + "\n")
            return
        lo, hi = analysis.color_range(mode, grid)
        unit = {"Deviation": "mm", "MeanCurvature": "1/mm", "GaussianCurvature": "1/mm²"}.get(mode, "")
        setattr(vobj, RANGE_PROPERTY, f"{lo:.4g} … {hi:.4g} {unit}".strip())
        offset = coin.SoPolygonOffset()  # in front of the sheet's own faces
        offset.factor = -1.0
        offset.units = -2.0
        self.root.addChild(offset)
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_VERTEX_INDEXED
        self.root.addChild(binding)
        material = coin.SoMaterial()
        colors = analysis.colors(mode, grid)
        material.diffuseColor.setValues(0, len(colors), colors)
        self.root.addChild(material)
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(grid.points), grid.points)
        self.root.addChild(coords)
        normals = coin.SoNormal()
        normals.vector.setValues(0, len(grid.normals), grid.normals)
        self.root.addChild(normals)
        nbinding = coin.SoNormalBinding()
        nbinding.value = coin.SoNormalBinding.PER_VERTEX_INDEXED
        self.root.addChild(nbinding)
        hints = coin.SoShapeHints()  # lit from both sides
        hints.vertexOrdering = coin.SoShapeHints.UNKNOWN_ORDERING
        self.root.addChild(hints)
        faces = coin.SoIndexedFaceSet()
        index = []
        for a, b, c in grid.triangles:
            index.extend((a, b, c, -1))
        faces.coordIndex.setValues(0, len(index), index)
        faces.materialIndex.setValues(0, len(index), index)
        faces.normalIndex.setValues(0, len(index), index)
        self.root.addChild(faces)
        self.grid = grid

    def _curves(self, vobj, obj):
        """Each curve of the sheet, thick, colored by its distance to the sheet (0 green)."""
        try:
            found = analysis.curve_deviations(obj.Shape, _sheet_edges(obj))
        except Exception as error:
            setattr(vobj, RANGE_PROPERTY, f"unavailable: {error}")
            return
        top = max((max(c.distances) for c in found if c.distances), default=0.0)
        setattr(vobj, RANGE_PROPERTY, f"0 … {top:.3g} mm")
        for curve in found:
            add_polyline(self.root, curve.points, [analysis.ramp(d, -top, top) for d in curve.distances],
                         6.0, unlit=True)
        self.curves = found
