# SPDX-License-Identifier: LGPL-2.1-or-later
"""Painting a rectangle of (u, v) on a surface in the 3D view: pressed on the surface, dragged
and released, as a selection rectangle is drawn, but over the surface's own parameters. The
rectangle shows on the surface while it is drawn; the painted regions show as outlines."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
from pivy import coin

from varsurf.gui.coin_lines import add_polyline

#: Points along each side of an outline (the surface bends between them).
_SIDE_POINTS = 24
_DRAWING = (1.0, 0.85, 0.1)
_PAINTED = (0.95, 0.45, 0.1)


def _normalized(face, u, v):
    u0, u1, v0, v1 = face.ParameterRange
    return (min(max((u - u0) / (u1 - u0), 0.0), 1.0), min(max((v - v0) / (v1 - v0), 0.0), 1.0))


def outline(face, rect):
    """Points of a (u0, u1, v0, v1) rectangle's border (normalized parameters) on the face."""
    pu0, pu1, pv0, pv1 = face.ParameterRange
    u0, u1, v0, v1 = rect
    corners = ((u0, v0), (u1, v0), (u1, v1), (u0, v1), (u0, v0))
    points = []
    for (a, b), (c, d) in zip(corners, corners[1:]):
        for k in range(_SIDE_POINTS):
            s = k / _SIDE_POINTS
            u, v = a + s * (c - a), b + s * (d - b)
            points.append(face.Surface.value(pu0 + u * (pu1 - pu0), pv0 + v * (pv1 - pv0)))
    points.append(points[0])
    return [(p.x, p.y, p.z) for p in points]


class RegionPainter:
    """While it lives, a left-button drag that starts on `obj`'s face in the view draws a
    rectangle of its (normalized) parameters and gives it to `on_painted(u0, u1, v0, v1)` when
    released; elsewhere the view navigates as usual. `show(regions)` outlines painted rectangles.
    `stop()` ends it."""

    def __init__(self, obj, on_painted, view=None):
        self.obj, self.on_painted = obj, on_painted
        self.view = view or Gui.getDocument(obj.Document.Name).ActiveView
        self.start = self.current = None
        self.root = coin.SoSeparator()
        self.root.setName("VarSurfRegionPainter")
        self.painted = coin.SoSeparator()
        self.drawing = coin.SoSeparator()
        self.root.addChild(self.painted)
        self.root.addChild(self.drawing)
        self.view.getSceneGraph().addChild(self.root)
        self.callbacks = [
            (coin.SoMouseButtonEvent.getClassTypeId(),
             self.view.addEventCallbackPivy(coin.SoMouseButtonEvent.getClassTypeId(), self._button)),
            (coin.SoLocation2Event.getClassTypeId(),
             self.view.addEventCallbackPivy(coin.SoLocation2Event.getClassTypeId(), self._motion)),
        ]

    def _face(self):
        faces = self.obj.Shape.Faces if not self.obj.Shape.isNull() else []
        return faces[0] if faces else None

    def uv_at(self, position):
        """Normalized (u, v) of the object's face under a view position (Coin's pixels, from the
        bottom left), or None off the face."""
        info = self.view.getObjectInfo((int(position[0]), int(position[1])))
        face = self._face()
        if not info or info.get("Object") != self.obj.Name or face is None:
            return None
        u, v = face.Surface.parameter(App.Vector(info["x"], info["y"], info["z"]))
        return _normalized(face, u, v)

    def rectangle(self):
        if self.start is None or self.current is None:
            return None
        (a, b), (c, d) = self.start, self.current
        return min(a, c), max(a, c), min(b, d), max(b, d)

    def _draw(self, parent, rects, color):
        parent.removeAllChildren()
        face = self._face()
        if face is None:
            return
        for rect in rects:
            add_polyline(parent, outline(face, rect), color, width=3.0, unlit=True)

    def show(self, regions):
        """Outline the painted rectangles (u0, u1, v0, v1)."""
        self._draw(self.painted, [r for r in regions if r[0] < r[1] and r[2] < r[3]], _PAINTED)

    def _button(self, callback):
        event = callback.getEvent()
        if event.getButton() != coin.SoMouseButtonEvent.BUTTON1:
            return
        position = event.getPosition().getValue()
        if event.getState() == coin.SoButtonEvent.DOWN:
            uv = self.uv_at(position)
            if uv is None:
                return  # off the surface: the view navigates
            self.start = self.current = uv
            callback.setHandled()
        elif event.getState() == coin.SoButtonEvent.UP and self.start is not None:
            uv = self.uv_at(position)
            if uv is not None:
                self.current = uv
            rect = self.rectangle()
            self.start = self.current = None
            self.drawing.removeAllChildren()
            callback.setHandled()
            if rect[0] < rect[1] and rect[2] < rect[3]:  # a click paints nothing
                self.on_painted(*rect)

    def _motion(self, callback):
        if self.start is None:
            return
        uv = self.uv_at(callback.getEvent().getPosition().getValue())
        if uv is not None:  # beyond the surface's edge the rectangle keeps its last corner
            self.current = uv
            self._draw(self.drawing, [self.rectangle()], _DRAWING)
        callback.setHandled()

    def stop(self):
        for kind, callback in self.callbacks:
            self.view.removeEventCallbackPivy(kind, callback)
        self.callbacks = []
        graph = self.view.getSceneGraph()
        if graph.findChild(self.root) >= 0:
            graph.removeChild(self.root)
