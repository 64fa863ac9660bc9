# SPDX-License-Identifier: LGPL-2.1-or-later
"""Painting a region of (u, v) on a surface in the 3D view: pressed on the surface, dragged and
released. A rectangle is drawn as a selection rectangle is, but over the surface's own
parameters; a loop follows the pointer's path and closes on release. The region shows on the
surface while it is drawn; the painted regions show as outlines."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
from pivy import coin
from PySide import QtCore, QtGui

from varsurf.gui.coin_lines import add_polyline

#: Points along each side of an outline (the surface bends between them).
_SIDE_POINTS = 24
#: A loop takes a pointer position this far (in normalized u, v) from its last point.
LOOP_STEP = 0.01
_DRAWING = (1.0, 0.85, 0.1)
_PAINTED = (0.95, 0.45, 0.1)


def _normalized(face, u, v):
    u0, u1, v0, v1 = face.ParameterRange
    return (min(max((u - u0) / (u1 - u0), 0.0), 1.0), min(max((v - v0) / (v1 - v0), 0.0), 1.0))


def outline(face, corners, closed=True):
    """Points on the face along a polygon of normalized (u, v) corners (a rectangle's four, a
    loop's many), sides subdivided so the outline follows the surface."""
    pu0, pu1, pv0, pv1 = face.ParameterRange
    corners = list(corners) + ([corners[0]] if closed else [])
    per_side = _SIDE_POINTS if len(corners) <= 5 else 2
    points = []
    for (a, b), (c, d) in zip(corners, corners[1:]):
        for k in range(per_side):
            s = k / per_side
            u, v = a + s * (c - a), b + s * (d - b)
            points.append(face.Surface.value(pu0 + u * (pu1 - pu0), pv0 + v * (pv1 - pv0)))
    last = corners[-1]
    points.append(face.Surface.value(pu0 + last[0] * (pu1 - pu0), pv0 + last[1] * (pv1 - pv0)))
    return [(p.x, p.y, p.z) for p in points]


def _corners(rect):
    u0, u1, v0, v1 = rect
    return [(u0, v0), (u1, v0), (u1, v1), (u0, v1)]


class RegionPainter(QtCore.QObject):
    """While it lives, a left-button drag that starts on `obj`'s face in the view draws a region
    of its (normalized) parameters: with `loop` False a rectangle, given to
    `on_painted(u0, u1, v0, v1)` when released; with `loop` True the pointer's path, given to
    `on_loop(points)`. Elsewhere the view navigates as usual. `show(rectangles, loops)` outlines
    painted regions. `stop()` ends it.

    The 3D view's GL widget is watched by a Qt event filter rather than through Coin event
    callbacks: the navigation style sees events before the scene's callbacks, and after a drag it
    took (one that started off the surface) it kept the next ones from them, so painting stopped
    (measured in the PDE panel's GUI test)."""

    def __init__(self, obj, on_painted, on_loop=None, view=None):
        super().__init__()
        self.obj, self.on_painted, self.on_loop = obj, on_painted, on_loop
        self.loop = False
        self.path = []
        self.view = view or Gui.getDocument(obj.Document.Name).ActiveView
        self.start = self.current = None
        self.root = coin.SoSeparator()
        self.root.setName("VarSurfRegionPainter")
        self.painted = coin.SoSeparator()
        self.drawing = coin.SoSeparator()
        self.root.addChild(self.painted)
        self.root.addChild(self.drawing)
        self.view.getSceneGraph().addChild(self.root)
        self.widget = gl_widget(self.view)
        if self.widget is not None:
            self.widget.installEventFilter(self)

    def _face(self):
        faces = self.obj.Shape.Faces if not self.obj.Shape.isNull() else []
        return faces[0] if faces else None

    def coin_position(self, point):
        """A widget position (Qt's pixels from the top left) in Coin's (from the bottom left)."""
        return coin_position(self.view, self.widget, point)

    def uv_at(self, position):
        """Normalized (u, v) of the object's face under a view position (Coin's pixels, from the
        bottom left), or None off the face."""
        info = self.view.getObjectInfo((int(round(position[0])), int(round(position[1]))))
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

    def _draw(self, parent, polygons, color, closed=True):
        parent.removeAllChildren()
        face = self._face()
        if face is None:
            return
        for corners in polygons:
            add_polyline(parent, outline(face, corners, closed), color, width=3.0, unlit=True)

    def show(self, regions, loops=()):
        """Outline the painted rectangles (u0, u1, v0, v1) and loops ((u, v) points)."""
        rects = [_corners(r) for r in regions if r[0] < r[1] and r[2] < r[3]]
        self._draw(self.painted, rects + [list(points) for points in loops if len(points) >= 3], _PAINTED)

    def eventFilter(self, watched, event):
        kind = event.type()
        if kind == QtCore.QEvent.MouseButtonPress and event.button() == QtCore.Qt.LeftButton:
            return self.press(self.coin_position(event.pos()))
        if kind == QtCore.QEvent.MouseMove and self.start is not None:
            self.move(self.coin_position(event.pos()))
            return True
        if kind == QtCore.QEvent.MouseButtonRelease and event.button() == QtCore.Qt.LeftButton \
                and self.start is not None:
            self.release(self.coin_position(event.pos()))
            return True
        return False

    def press(self, position):
        """A press at a view position: True (taken) on the surface, False (the view's) off it."""
        uv = self.uv_at(position)
        if uv is None:
            return False
        self.start = self.current = uv
        self.path = [uv]
        return True

    def move(self, position):
        uv = self.uv_at(position)
        if uv is None:  # beyond the surface's edge the region keeps its last point
            return
        self._reach(uv)
        if self.loop:
            self._draw(self.drawing, [self.path], _DRAWING, closed=False)
        else:
            self._draw(self.drawing, [_corners(self.rectangle())], _DRAWING)

    def release(self, position):
        uv = self.uv_at(position)
        if uv is not None:
            self._reach(uv)
        rect, path = self.rectangle(), self.path
        self.start = self.current = None
        self.path = []
        self.drawing.removeAllChildren()
        if self.loop:
            if len(path) >= 3 and self.on_loop is not None:
                self.on_loop(path)
        elif rect[0] < rect[1] and rect[2] < rect[3]:  # a click paints nothing
            self.on_painted(*rect)

    def _reach(self, uv):
        self.current = uv
        last = self.path[-1]
        if max(abs(uv[0] - last[0]), abs(uv[1] - last[1])) >= LOOP_STEP:
            self.path.append(uv)

    def stop(self):
        if self.widget is not None:
            self.widget.removeEventFilter(self)
            self.widget = None
        graph = self.view.getSceneGraph()
        if graph.findChild(self.root) >= 0:
            graph.removeChild(self.root)


def coin_position(view, widget, point):
    """A position on `view`'s GL widget (Qt's pixels from the top left) in Coin's pixels (from the
    bottom left), as getObjectInfo takes them."""
    width, height = view.getSize()
    return (point.x() * width / max(widget.width(), 1), height - 1 - point.y() * height / max(widget.height(), 1))


def gl_widget(view):
    """The GL widget that shows `view` (the QuarterWidget's viewport)."""
    try:
        return view.graphicsView().viewport()
    except (AttributeError, RuntimeError):  # a view without it: the visible 3D view
        pass
    for widget in Gui.getMainWindow().findChildren(QtGui.QWidget):
        if widget.metaObject().className() == "SIM::Coin3D::Quarter::QuarterWidget" and widget.isVisible():
            if view.getSize() and widget.viewport() is not None:
                return widget.viewport()
    return None
