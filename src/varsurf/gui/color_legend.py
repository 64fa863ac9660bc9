# SPDX-License-Identifier: LGPL-2.1-or-later
"""A color map's legend in the 3D view: a bar at the view's right edge, its colors as the map's,
labelled with values and units, fixed on the screen whatever the camera does.

FreeCAD's SoFCColorBar can be created from Python (by its Coin type name) but its range and title
are set only from C++, so the bar is built here from plain Coin nodes: an orthographic camera of
its own under an SoAnnotation (drawn over the scene), inside FreeCAD's SoSkipBoundingGroup so that
View Fit and bounding boxes ignore it.
"""

from __future__ import annotations

from typing import Callable, Sequence, Tuple

from pivy import coin

#: The bar in view coordinates (-1 ... 1 across, either way): right edge, a tenth of the height
#: from top and bottom.
BAR_X = (0.86, 0.89)
BAR_Y = (-0.7, 0.7)
#: Color steps along the bar (the ramp is linear between them).
STEPS = 32
#: Labelled values: the ends, the middle and the quarters.
TICKS = 5


def tick_values(lo: float, hi: float, ticks: int = TICKS) -> Sequence[float]:
    """The labelled values, bottom to top."""
    return [lo + (hi - lo) * k / (ticks - 1) for k in range(ticks)]


def label(value: float) -> str:
    """A tick's text: four significant digits, and an exact 0 (not -1.2e-17)."""
    return "0" if value == 0.0 else f"{value:.4g}"


def legend_node(title: str, lo: float, hi: float, color_of: Callable[[float], Tuple[float, float, float]]):
    """A node drawing the bar from lo (bottom) to hi (top), colored by color_of(value), with
    TICKS labels and ``title`` (what and which unit) above it."""
    group = coin.SoType.fromName("SoSkipBoundingGroup").createInstance()
    group.getField("mode").set("EXCLUDE_BBOX")
    group.setName("VarSurfLegend")
    annotation = coin.SoAnnotation()
    group.addChild(annotation)
    pick = coin.SoPickStyle()
    pick.style = coin.SoPickStyle.UNPICKABLE
    annotation.addChild(pick)
    annotation.addChild(coin.SoResetTransform())
    camera = coin.SoOrthographicCamera()
    camera.viewportMapping = coin.SoCamera.LEAVE_ALONE  # -1 ... 1 fills the view both ways
    camera.position = (0.0, 0.0, 1.0)
    camera.height = 2.0
    camera.aspectRatio = 1.0
    camera.nearDistance = 0.5
    camera.farDistance = 1.5
    annotation.addChild(camera)
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    annotation.addChild(light)

    x0, x1 = BAR_X
    y0, y1 = BAR_Y
    points, colors, index = [], [], []
    for k in range(STEPS + 1):
        t = k / STEPS
        y = y0 + (y1 - y0) * t
        points.extend(((x0, y, 0.0), (x1, y, 0.0)))
        color = color_of(lo + (hi - lo) * t)
        colors.extend((color, color))
        if k:
            a = 2 * (k - 1)
            index.extend((a, a + 1, a + 3, a + 2, -1))
    bar = coin.SoSeparator()
    binding = coin.SoMaterialBinding()
    binding.value = coin.SoMaterialBinding.PER_VERTEX_INDEXED
    bar.addChild(binding)
    material = coin.SoMaterial()
    material.diffuseColor.setValues(0, len(colors), colors)
    bar.addChild(material)
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(points), points)
    bar.addChild(coords)
    faces = coin.SoIndexedFaceSet()
    faces.coordIndex.setValues(0, len(index), index)
    faces.materialIndex.setValues(0, len(index), index)
    bar.addChild(faces)
    annotation.addChild(bar)

    text = coin.SoSeparator()
    ink = coin.SoBaseColor()
    ink.rgb = (0.1, 0.1, 0.1)
    text.addChild(ink)
    font = coin.SoFont()
    font.size = 12.0
    text.addChild(font)
    for k, value in enumerate(tick_values(lo, hi)):
        y = y0 + (y1 - y0) * k / (TICKS - 1)
        text.addChild(_text_at(x1 + 0.01, y - 0.01, label(value)))
    text.addChild(_text_at(x1 + 0.08, y1 + 0.06, title, coin.SoText2.RIGHT))
    annotation.addChild(text)
    return group


def _text_at(x: float, y: float, string: str, justification=coin.SoText2.LEFT):
    node = coin.SoSeparator()
    move = coin.SoTranslation()
    move.translation = (x, y, 0.0)
    node.addChild(move)
    text = coin.SoText2()
    text.string = string
    text.justification = justification
    node.addChild(text)
    return node


def legend_texts(node) -> Sequence[str]:
    """The strings a legend node shows (its labels, then its title): what a test reads back."""
    search = coin.SoSearchAction()
    search.setType(coin.SoText2.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.setSearchingAll(True)
    search.apply(node)
    paths = search.getPaths()
    return [paths[i].getTail().string.getValues()[0] for i in range(paths.getLength())]
