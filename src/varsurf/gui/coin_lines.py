# SPDX-License-Identifier: LGPL-2.1-or-later
"""One polyline in a Coin scene: what handles, color maps and refinement outlines all draw."""

from __future__ import annotations

from pivy import coin


def add_polyline(parent, points, color, width=2.0, unlit=False):
    """Append a polyline through `points` to `parent`. `color` is one RGB triple, or one per point
    (blended along the line); unlit lines keep their color from every side."""
    sep = coin.SoSeparator()
    style = coin.SoDrawStyle()
    style.lineWidth = width
    sep.addChild(style)
    if unlit:
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        sep.addChild(light)
    material = coin.SoMaterial()
    per_point = len(color) == len(points) and not isinstance(color[0], (int, float))
    if per_point:
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_VERTEX
        sep.addChild(binding)
        material.diffuseColor.setValues(0, len(color), [tuple(c) for c in color])
    else:
        material.diffuseColor.setValue(*color)
        material.emissiveColor.setValue(*(0.3 * c for c in color))
    sep.addChild(material)
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(points), [tuple(p) for p in points])
    sep.addChild(coords)
    line = coin.SoLineSet()
    line.numVertices.setValue(len(points))
    sep.addChild(line)
    parent.addChild(sep)
    return sep
