# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Sheet's analysis color map in the 3D view: the grid of varsurf.solve.analysis as a Coin mesh,
drawn just in front of the sheet's own shading (a polygon offset), with a legend (color_legend).
Color maps use per-vertex colors; zebra stripes are a black-and-white texture whose coordinate is
the stripe phase, interpolated per pixel, so stripe edges stay sharp on a coarse grid."""

from __future__ import annotations

import FreeCAD as App
import Part
from pivy import coin

from varsurf.app.analysis import reference_of
from varsurf.gui.coin_lines import add_polyline
from varsurf.gui.color_legend import legend_node
from varsurf.gui.scene_roots import own_root
from varsurf.solve import analysis

PROPERTY = "Analysis"
RANGE_PROPERTY = "AnalysisRange"
SCALE_PROPERTY = "AnalysisScale"
STRIPES_PROPERTY = "ZebraStripes"
DIRECTION_PROPERTY = "ZebraDirection"
#: View properties whose change redraws the map.
REDRAW = (PROPERTY, SCALE_PROPERTY, STRIPES_PROPERTY, DIRECTION_PROPERTY)
UNITS = {"Deviation": "mm", "CurveDeviation": "mm", "MeanCurvature": "1/mm", "GaussianCurvature": "1/mm²"}
TITLES = {"Deviation": "Deviation", "CurveDeviation": "Curve distance", "MeanCurvature": "Mean curvature",
          "GaussianCurvature": "Gaussian curvature"}
#: Texels per stripe pair of the zebra texture: half white, half black. Enough texels that the
#: texture's linear filtering blurs only a 64th of a stripe pair.
ZEBRA_TEXELS = 64


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
                         "The values the colors span (blue to red), as the legend shows them")
        vobj.setEditorMode(RANGE_PROPERTY, 1)
    if SCALE_PROPERTY not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyFloat", SCALE_PROPERTY, "VarSurf",
                         "The value at the color bar's ends: -scale blue, 0 green, +scale red. 0: the "
                         "largest magnitude in the data. Set the same scale on sheets to compare them")
    if STRIPES_PROPERTY not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyInteger", STRIPES_PROPERTY, "VarSurf",
                         "Zebra: black-and-white stripe pairs over a half turn of the normal (1 to 200)")
        setattr(vobj, STRIPES_PROPERTY, analysis.STRIPES)
    if DIRECTION_PROPERTY not in vobj.PropertiesList:
        vobj.addProperty("App::PropertyVector", DIRECTION_PROPERTY, "VarSurf",
                         "Zebra: the direction the stripes are measured from (the normal's angle to it)")
        setattr(vobj, DIRECTION_PROPERTY, App.Vector(0, 0, 1))


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
        self.legend = None

    def update(self, vobj):
        self.root.removeAllChildren()
        self.grid = None
        self.curves = None
        self.legend = None
        mode = str(getattr(vobj, PROPERTY, "None"))
        obj = vobj.Object
        if mode == "None" or obj.Shape.isNull():
            setattr(vobj, RANGE_PROPERTY, "")
            return
        if mode == "CurveDeviation":
            self._curves(vobj, obj)
            return
        stripes = int(getattr(vobj, STRIPES_PROPERTY, analysis.STRIPES))
        direction = tuple(getattr(vobj, DIRECTION_PROPERTY, App.Vector(0, 0, 1)))
        try:
            grid = analysis.analyse(obj.Shape, mode, reference=reference_of(obj), direction=direction,
                                    stripes=stripes)
            lo, hi = analysis.color_range(mode, grid, float(getattr(vobj, SCALE_PROPERTY, 0.0)))
        except Exception as error:
            setattr(vobj, RANGE_PROPERTY, f"unavailable: {error}")
            App.Console.PrintWarning(App.Qt.translate(
                "VarSurf", "VarSurf: {}: no {} map ({}); change the view properties of the map").format(
                    obj.Label, mode, error) + "\n")
            return
        if mode == "Zebra":
            d = App.Vector(*direction).normalize()
            setattr(vobj, RANGE_PROPERTY, f"{stripes} stripes from ({d.x:.3g}, {d.y:.3g}, {d.z:.3g})")
        else:
            setattr(vobj, RANGE_PROPERTY, f"{lo:.4g} … {hi:.4g} {UNITS[mode]}")
        offset = coin.SoPolygonOffset()  # in front of the sheet's own faces
        offset.factor = -1.0
        offset.units = -2.0
        self.root.addChild(offset)
        if mode == "Zebra":
            self._zebra_texture(grid)
        else:
            binding = coin.SoMaterialBinding()
            binding.value = coin.SoMaterialBinding.PER_VERTEX_INDEXED
            self.root.addChild(binding)
            material = coin.SoMaterial()
            colors = analysis.colors(mode, grid, float(getattr(vobj, SCALE_PROPERTY, 0.0)))
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
        if mode == "Zebra":
            faces.textureCoordIndex.setValues(0, len(index), index)
        else:
            faces.materialIndex.setValues(0, len(index), index)
        faces.normalIndex.setValues(0, len(index), index)
        self.root.addChild(faces)
        self.grid = grid
        if mode != "Zebra":
            self._add_legend(f"{TITLES[mode]} ({UNITS[mode]})", lo, hi)

    def _zebra_texture(self, grid):
        """A repeating texture, white then black along s, with s = the stripe phase per vertex
        (t unused): OpenGL interpolates s per pixel, so a stripe's edge is sharp wherever it
        crosses a triangle."""
        texture = coin.SoTexture2()
        white = ZEBRA_TEXELS // 2
        pixels = bytes([255] * white + [0] * (ZEBRA_TEXELS - white))
        texture.image.setValue(coin.SbVec2s(ZEBRA_TEXELS, 1), 1, pixels)
        texture.wrapS = coin.SoTexture2.REPEAT
        texture.wrapT = coin.SoTexture2.CLAMP
        texture.model = coin.SoTexture2.REPLACE  # pure black and white, as reflected stripes are
        self.root.addChild(texture)
        coords = coin.SoTextureCoordinate2()
        phases = [(v if v == v else 0.0, 0.5) for v in grid.values]  # NaN (no normal): white
        coords.point.setValues(0, len(phases), phases)
        self.root.addChild(coords)
        binding = coin.SoTextureCoordinateBinding()
        binding.value = coin.SoTextureCoordinateBinding.PER_VERTEX_INDEXED
        self.root.addChild(binding)

    def _add_legend(self, title, lo, hi, ramp_range=None):
        """The legend from lo to hi, colored as the map over ramp_range (default lo ... hi)."""
        a, b = ramp_range or (lo, hi)
        self.legend = legend_node(title, lo, hi, lambda value: analysis.ramp(value, a, b))
        self.root.addChild(self.legend)

    def _curves(self, vobj, obj):
        """Each curve of the sheet, thick, colored by its distance to the sheet (0 green)."""
        try:
            found = analysis.curve_deviations(obj.Shape, _sheet_edges(obj))
        except Exception as error:
            setattr(vobj, RANGE_PROPERTY, f"unavailable: {error}")
            return
        scale = float(getattr(vobj, SCALE_PROPERTY, 0.0))
        top = scale if scale > 0.0 else max((max(c.distances) for c in found if c.distances), default=0.0)
        setattr(vobj, RANGE_PROPERTY, f"0 … {top:.3g} mm")
        for curve in found:
            add_polyline(self.root, curve.points, [analysis.ramp(d, -top, top) for d in curve.distances],
                         6.0, unlit=True)
        self.curves = found
        self._add_legend(f"{TITLES['CurveDeviation']} (mm)", 0.0, top, (-top, top))
