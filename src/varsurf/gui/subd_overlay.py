# SPDX-License-Identifier: LGPL-2.1-or-later
"""What a SubdSurface's panel draws over it: the mesh of one level (where its vertices, the ones a
pick pins, lie) and a pin's region of influence (the finest vertices it moves) as dots on the
limit surface. Picking a vertex: a click on the surface in the 3D view."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
import numpy
from pivy import coin
from PySide import QtCore

from varsurf.gui.region_painter import coin_position, gl_widget
from varsurf.gui.scene_roots import own_root

_LEVEL = (0.1, 0.2, 0.7)
_REGION = (1.0, 0.45, 0.05)


def _unlit(parent, color, width=1.0, point_size=1.0):
    style = coin.SoDrawStyle()
    style.lineWidth, style.pointSize = width, point_size
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*color)
    for node in (style, light, material):
        parent.addChild(node)


def level_edges(faces):
    """Each edge of a level's faces once, as vertex pairs."""
    edges = set()
    for face in faces:
        for a, b in zip(face, list(face[1:]) + [face[0]]):
            edges.add((min(a, b), max(a, b)))
    return sorted(edges)


class SubdOverlay:
    """The level's mesh and a region of influence drawn over a SubdSurface."""

    def __init__(self, vobj):
        self.root = own_root(vobj, "VarSurfSubdOverlay")
        self.level = coin.SoSeparator()
        self.region = coin.SoSeparator()
        self.root.addChild(self.level)
        self.root.addChild(self.region)

    def show_level(self, points, faces):
        self.level.removeAllChildren()
        _unlit(self.level, _LEVEL, width=1.0)
        coords = coin.SoCoordinate3()
        values = numpy.ascontiguousarray(points, dtype=numpy.float64).reshape(-1, 3)
        coords.point.setValues(0, len(values), values)
        self.level.addChild(coords)
        lines = coin.SoIndexedLineSet()
        index = [i for a, b in level_edges(faces) for i in (a, b, -1)]
        lines.coordIndex.setValues(0, len(index), index)
        self.level.addChild(lines)

    def show_region(self, points):
        """Dots at `points` (the moved finest vertices' limit points); none for an empty list."""
        self.region.removeAllChildren()
        values = numpy.ascontiguousarray(points, dtype=numpy.float64).reshape(-1, 3)
        if not len(values):
            return
        _unlit(self.region, _REGION, point_size=4.0)
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(values), values)
        self.region.addChild(coords)
        self.region.addChild(coin.SoPointSet())

    def close(self, vobj):
        if vobj.RootNode.findChild(self.root) >= 0:
            vobj.RootNode.removeChild(self.root)


class VertexPicker(QtCore.QObject):
    """While it lives, a left click on `obj` in the view gives the point clicked to
    `on_pick(App.Vector)` (the click is taken); elsewhere the view navigates as usual. A Qt event
    filter on the GL widget, as the region painter (navigation styles see Coin's events first)."""

    def __init__(self, obj, on_pick, view=None):
        super().__init__()
        self.obj, self.on_pick = obj, on_pick
        self.view = view or Gui.getDocument(obj.Document.Name).ActiveView
        self.widget = gl_widget(self.view)
        if self.widget is not None:
            self.widget.installEventFilter(self)

    def point_at(self, position):
        """The point of the object under a view position (Coin's pixels), or None."""
        info = self.view.getObjectInfo((int(round(position[0])), int(round(position[1]))))
        if not info or info.get("Object") != self.obj.Name:
            return None
        return App.Vector(info["x"], info["y"], info["z"])

    def eventFilter(self, watched, event):
        if event.type() == QtCore.QEvent.MouseButtonPress and event.button() == QtCore.Qt.LeftButton:
            point = self.point_at(coin_position(self.view, self.widget, event.pos()))
            if point is None:
                return False
            self.on_pick(point)
            return True
        return False

    def stop(self):
        if self.widget is not None:
            self.widget.removeEventFilter(self)
            self.widget = None
