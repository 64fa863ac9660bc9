# SPDX-License-Identifier: LGPL-2.1-or-later
"""Coin3D handles of a Constraint in the 3D view: a draggable pin for a Point, arrows for normals,
tangents and directors, a plane patch or a line for points held in a plane or on a line, a star
for attractors (red for a repeller), the curve with ticks along it for ribbons and G1/G2 joins.

Dragging a pin moves the Point's target and re-solves its Sheet live (varsurf.app.drag.PointDrag);
releasing it commits one undoable step.
"""

from __future__ import annotations

import math

import FreeCAD as App
import FreeCADGui as Gui
import Part
from pivy import coin
from PySide import QtCore

from varsurf.app import drag, dynamic_drag
from varsurf.solve import constraints
from varsurf.solve.native import native
from varsurf.gui.coin_lines import add_polyline
from varsurf.gui.scene_roots import own_root
from varsurf.gui.drag_preview import DragPreview

V = App.Vector
PIN = (0.95, 0.55, 0.05)
ARROW = (0.1, 0.45, 0.9)
ATTRACT = (0.1, 0.65, 0.25)
REPEL = (0.85, 0.1, 0.1)
RIBBON = (0.55, 0.2, 0.75)
CURVATURE = (0.85, 0.35, 0.6)
#: Handles are this fraction of the sheet's diagonal.
HANDLE_SIZE = 0.03
#: Ticks drawn along a ribbon's curve.
RIBBON_TICKS = 12
#: Points on each half of a Curvature constraint's arcs.
CURVATURE_POINTS = 16
#: Points on a CurveMap's curves (every quarter of them joined source to destination).
CURVE_MAP_POINTS = 65
#: A released dynamic drag is written after at most this many frames (3 s) if it has not settled.
SETTLE_FRAMES = 180

_dragging = []  # the ConstraintHandles whose pin is being dragged (at most one)
#: Kinds whose Origin is drawn as a draggable pin.
ORIGIN_KINDS = ("PointInPlane", "PointOnLine", "PointAttractor", "PlaneAttractor", "LineAttractor",
                "Repeller")


def sheet_of(constraint):
    """The Sheet that lists `constraint` (None if it is not in one)."""
    for obj in constraint.InList:
        if constraint in (getattr(obj, "Constraints", None) or []):
            return obj
    return None


def _material(parent, color):
    m = coin.SoMaterial()
    m.diffuseColor.setValue(*color)
    m.emissiveColor.setValue(*(0.3 * c for c in color))
    parent.addChild(m)


def _line(parent, points, color, width=2.0):
    add_polyline(parent, points, color, width)


def _arrow(parent, base, direction, length, color):
    """A shaft and a cone from base along direction."""
    if direction.Length == 0.0:
        return
    d = V(direction).normalize()
    sep = coin.SoSeparator()
    _material(sep, color)
    xf = coin.SoTransform()
    xf.translation.setValue(*(base + d * (0.5 * length)))
    xf.rotation.setValue(coin.SbRotation(coin.SbVec3f(0, 1, 0), coin.SbVec3f(d.x, d.y, d.z)))
    sep.addChild(xf)
    shaft = coin.SoCylinder()
    shaft.radius = 0.04 * length
    shaft.height = length
    sep.addChild(shaft)
    tip = coin.SoTranslation()
    tip.translation.setValue(0, 0.5 * length, 0)
    sep.addChild(tip)
    cone = coin.SoCone()
    cone.bottomRadius = 0.12 * length
    cone.height = 0.3 * length
    sep.addChild(cone)
    parent.addChild(sep)


def _star(parent, at, size, color):
    for axis in (V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)):
        _line(parent, [at - axis * size, at + axis * size], color, 3.0)
    sep = coin.SoSeparator()
    _material(sep, color)
    t = coin.SoTranslation()
    t.translation.setValue(*at)
    sep.addChild(t)
    ball = coin.SoSphere()
    ball.radius = 0.25 * size
    sep.addChild(ball)
    parent.addChild(sep)


def _plane_patch(parent, at, normal, size, color):
    if normal.Length == 0.0:
        return
    n = V(normal).normalize()
    a = n.cross(V(1, 0, 0) if abs(n.x) < 0.9 else V(0, 1, 0)).normalize()
    b = n.cross(a)
    corners = [at + (a * sa + b * sb) * size for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1), (-1, -1))]
    _line(parent, corners, color)
    _arrow(parent, at, n, size, color)


def _on_sheet(sheet, constraint):
    """Where a (u, v) constraint sits on the sheet, and the sheet's normal there."""
    if sheet is None or sheet.Shape.isNull() or not sheet.Shape.Faces:
        return None, None
    face = sheet.Shape.Faces[0]
    if constraint.Location is not None:
        try:
            at = drag.point_target(constraint) if constraint.Kind == "Point" else _location(constraint)
        except Exception:
            return None, None
        u, v = face.Surface.parameter(at)
    else:
        u0, u1, v0, v1 = face.ParameterRange
        u, v = u0 + constraint.U * (u1 - u0), v0 + constraint.V * (v1 - v0)
    return face.valueAt(u, v), face.normalAt(u, v)


def _location(constraint):
    link, subs = constraint.Location
    subs = [s for s in subs if s]
    shape = Part.getShape(link, subs[0], needSubElement=True) if subs else link.Shape
    return V(shape.Vertexes[0].Point)


def pin_position(dragger, scale):
    t = dragger.translation.getValue()
    return V(t[0], t[1], t[2]) * scale


def add_pin(parent, target, size, on_begin, on_move, on_end):
    """A point dragger at `target`, drawn `size` big, with an orange ball riding on it; the
    callbacks get the dragged position. Returns the dragger."""
    sep = coin.SoSeparator()
    scale = coin.SoScale()
    scale.scaleFactor.setValue(size, size, size)
    sep.addChild(scale)
    dragger = coin.SoDragPointDragger()
    dragger.translation.setValue(*(target / size))
    ball = coin.SoSeparator()  # seen from afar
    _material(ball, PIN)
    follow = coin.SoTranslation()
    follow.translation.connectFrom(dragger.translation)
    ball.addChild(follow)
    sphere = coin.SoSphere()
    sphere.radius = 0.6
    ball.addChild(sphere)
    sep.addChild(ball)
    dragger.addStartCallback(lambda *_: on_begin())
    dragger.addMotionCallback(lambda *_: on_move(pin_position(dragger, size)))
    dragger.addFinishCallback(lambda *_: on_end(pin_position(dragger, size)))
    sep.addChild(dragger)
    parent.addChild(sep)
    return dragger


class ConstraintHandles:
    """The Coin scene of one Constraint's handles; `root` goes into its view provider."""

    def __init__(self):
        self.root = coin.SoSeparator()
        self.constraint = None
        self.dragger = None
        self.scale = 1.0
        self.session = None
        self.preview = None  # the drawn surface while dragging
        self.errors = []  # messages of refused drags (also in the report view)

    # -- drawing --
    def rebuild(self, constraint):
        if self in _dragging:
            return  # the pin under the pointer stays where it is until released
        self.constraint = constraint
        self.root.removeAllChildren()
        self.dragger = None
        if not getattr(constraint, "Enabled", False):
            return
        sheet = sheet_of(constraint)
        size = HANDLE_SIZE * max(sheet.Shape.BoundBox.DiagonalLength if sheet and not sheet.Shape.isNull() else 100.0,
                                 1.0)
        kind = constraint.Kind
        try:
            self._draw(kind, constraint, sheet, size)
        except Exception as error:  # a broken link draws nothing; the Sheet reports it
            App.Console.PrintLog(f"VarSurf: {constraint.Label}: no handle drawn ({error})\n")

    def _draw(self, kind, c, sheet, size):
        if kind == "Point":
            self._pin(drag.point_target(c), size)
            return
        if kind in ORIGIN_KINDS:  # its origin is a pin too: dragging it re-solves the sheet
            self.scale = 0.8 * size
            self.dragger = add_pin(self.root, V(c.Origin), self.scale, self.begin_origin_drag,
                                   lambda t: self.drag_to(t), lambda t: self.end_drag(t))
        if kind in ("Normal", "TangentU", "TangentV"):
            at, _n = _on_sheet(sheet, c)
            if at is not None:
                _arrow(self.root, at, V(c.Vector), 4 * size, ARROW)
        elif kind == "PointInPlane":
            _plane_patch(self.root, V(c.Origin), V(c.Vector), 2 * size, ARROW)
        elif kind == "PointOnLine":
            d = V(c.Vector)
            if d.Length > 0:
                d.normalize()
                _line(self.root, [V(c.Origin) - d * 6 * size, V(c.Origin) + d * 6 * size], ARROW, 3.0)
        elif kind in ("PointAttractor", "PlaneAttractor", "LineAttractor", "Repeller"):
            _star(self.root, V(c.Origin), size, REPEL if kind == "Repeller" else ATTRACT)
            if kind == "PlaneAttractor":
                _plane_patch(self.root, V(c.Origin), V(c.Vector), 2 * size, ATTRACT)
        elif kind == "Director" and sheet is not None and not sheet.Shape.isNull():
            face = sheet.Shape.Faces[0]
            u0, u1, v0, v1 = face.ParameterRange
            u = u0 + 0.5 * (c.RegionU0 + c.RegionU1) * (u1 - u0)
            v = v0 + 0.5 * (c.RegionV0 + c.RegionV1) * (v1 - v0)
            _arrow(self.root, face.valueAt(u, v), V(c.Vector), 4 * size, ARROW)
        elif kind in ("Ribbon", "G1", "G2") and c.Curve is not None:
            self._ribbon(c, sheet, size)
        elif kind == "Curvature":
            self._curvature(c, sheet, size)
        elif kind == "CurveMap" and c.Curve is not None and c.Reference is not None:
            self._curve_map(c)
        elif kind == "RegionMap" and c.Reference is not None and sheet is not None and not sheet.Shape.isNull():
            self._region_map(c, sheet)

    def _region_map(self, c, sheet):
        """The region's outline on the sheet, the destination face's, and where the corners go."""
        surface = sheet.Shape.Faces[0].Surface
        u0, u1, v0, v1 = surface.bounds()
        box = [(c.RegionU0, c.RegionV0), (c.RegionU1, c.RegionV0), (c.RegionU1, c.RegionV1), (c.RegionU0, c.RegionV1)]
        region = []
        for (a, b), (e, f) in zip(box, box[1:] + box[:1]):
            region += [surface.value(u0 + (a + (e - a) * k / 16) * (u1 - u0), v0 + (b + (f - b) * k / 16) * (v1 - v0))
                       for k in range(16)]
        _line(self.root, region + region[:1], RIBBON, 3.0)
        target, subs = c.Reference
        subs = [s for s in subs if s]
        face = Part.getShape(target, subs[0], needSubElement=True) if subs else target.Shape.Faces[0]
        a0, a1, b0, b1 = face.ParameterRange
        corners = [face.valueAt(a0 + x * (a1 - a0), b0 + y * (b1 - b0)) for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))]
        _line(self.root, corners + corners[:1], CURVATURE, 3.0)
        for k in range(4):
            _line(self.root, [region[16 * k], corners[k]], ARROW, 1.5)

    def _curve_map(self, c):
        """The source and destination curves and, between them, where points go: the
        destination as the solver maps it (constraints.mapped_destination), point for point by
        parameter."""
        nat = native()
        curves = []
        for link in (c.Curve, c.Reference):
            target, subs = link
            subs = [s for s in subs if s]
            edge = Part.getShape(target, subs[0], needSubElement=True) if subs else target.Shape.Edges[0]
            try:
                curves.append(nat.curve_from_edge_brep(edge.exportBrepToString()))
            except (nat.InvalidInput, nat.GeometryError):
                return  # the recompute reports it
        source = curves[0]
        destination = constraints.mapped_destination(source, curves[1], nat)
        t0, t1 = source.first(), source.last()
        ts = [t0 + (t1 - t0) * k / (CURVE_MAP_POINTS - 1) for k in range(CURVE_MAP_POINTS)]
        points = [[V(*map(float, curve.evaluate(t))) for t in ts] for curve in (source, destination)]
        _line(self.root, points[0], RIBBON, 3.0)
        _line(self.root, points[1], CURVATURE, 3.0)
        for a, b in list(zip(*points))[::(CURVE_MAP_POINTS - 1) // 4]:
            _line(self.root, [a, b], ARROW, 1.5)

    def _curvature(self, c, sheet, size):
        """Vector (the side positive curvature bends to) and the arcs of the asked curvatures the
        sheet must follow through the point along u and v (straight for 0)."""
        at, _normal = _on_sheet(sheet, c)
        side = V(c.Vector)
        if at is None or side.Length == 0:
            return
        side.normalize()
        _arrow(self.root, at, side, 4 * size, ARROW)
        surface = sheet.Shape.Faces[0].Surface
        u, v = surface.parameter(at)
        normal = surface.getDN(u, v, 1, 0).cross(surface.getDN(u, v, 0, 1))
        if normal.Length == 0:
            return
        normal.normalize()
        if normal.dot(side) < 0:
            normal = -normal
        asked = str(c.CurvatureDirections)
        for (du, dv), kappa, name in (((1, 0), float(c.CurvatureU), "U"), ((0, 1), float(c.CurvatureV), "V")):
            if asked not in ("U and V", name):
                continue
            t = surface.getDN(u, v, du, dv)
            t = t - normal * normal.dot(t)
            if t.Length == 0:
                continue
            t.normalize()
            reach = min(6 * size, 0.5 * math.pi / abs(kappa)) if kappa else 6 * size
            points = []
            for i in range(-CURVATURE_POINTS, CURVATURE_POINTS + 1):
                s_ = reach * i / CURVATURE_POINTS
                if abs(kappa * reach) < 1e-9:
                    points.append(at + t * s_)
                else:
                    bend = (1 - math.cos(kappa * s_)) / kappa
                    points.append(at + t * (math.sin(kappa * s_) / kappa) + normal * bend)
            _line(self.root, points, CURVATURE, 3.0)

    def _ribbon(self, c, sheet, size):
        link, subs = c.Curve
        subs = [s for s in subs if s]
        edge = Part.getShape(link, subs[0], needSubElement=True) if subs else link.Shape.Edges[0]
        points = edge.discretize(64)
        _line(self.root, points, RIBBON, 4.0)
        if sheet is None or sheet.Shape.isNull():
            return
        face = sheet.Shape.Faces[0]
        for p in edge.discretize(RIBBON_TICKS):
            u, v = face.Surface.parameter(p)
            _line(self.root, [p, p + face.normalAt(u, v) * (2 * size)], RIBBON, 2.0)

    def _pin(self, target, size):
        self.scale = size
        self.dragger = add_pin(self.root, target, size, self.begin_drag,
                               lambda t: self.drag_to(t), lambda t: self.end_drag(t))

    def dragger_target(self):
        return pin_position(self.dragger, self.scale)

    # -- dragging --
    def begin_drag(self):
        sheet = sheet_of(self.constraint)
        try:
            if sheet is None:
                raise drag.DragError(f"{self.constraint.Label} is in no Sheet")
            self._settle_now()  # a surface still settling from the last release is put in place first
            try:  # a PdeSurface with DragMode Dynamic: pulled by a spring, with mass and damping
                self.session = dynamic_drag.DynamicDrag(sheet, self.constraint)
            except drag.NotQuadratic:
                try:
                    self.session = drag.PointDrag(sheet, self.constraint)
                except drag.NotQuadratic:  # iterated terms: recompute as often as that takes
                    self.session = drag.TargetDrag(sheet, self.constraint)
        except drag.DragError as error:
            self._refuse(error)
            return False
        # The preview draws the whole surface: a trimmed sheet (a hole, a disc) shows its Shape.
        self.preview = (DragPreview(sheet.ViewObject, self.session.space)
                        if sheet.ViewObject and isinstance(self.session, (drag.PointDrag, dynamic_drag.DynamicDrag))
                        and self.session.natural else None)
        if isinstance(self.session, dynamic_drag.DynamicDrag):
            # The surface moves on while the pointer rests: a frame's steps every 1/60 s.
            self.target = None
            self.timer = QtCore.QTimer()
            self.timer.setInterval(int(1000 * dynamic_drag.TIME_STEP))
            self.timer.timeout.connect(self._tick)
            self.timer.start()
        _dragging.append(self)
        return True

    def _tick(self):
        """A frame of a dynamic drag: toward the pointer while held, settling once released (then
        the release is written)."""
        session = self.session
        if not isinstance(session, dynamic_drag.DynamicDrag):
            return
        try:
            if session.released:
                surface = session.settle()
                if session.settled or self.settle_frames > SETTLE_FRAMES:
                    self._finish_dynamic()
                    return
                self.settle_frames += 1
            elif self.target is not None:
                surface = session.move(self.target, update_shape=self.preview is None)
            else:
                return
        except Exception as error:  # a timer's slot: nothing may escape it (the document closed...)
            self.timer.stop()
            self.session = None
            if self in _dragging:
                _dragging.remove(self)
            self._close_preview()
            self._refuse(error)
            return
        if self.preview is not None:
            self.preview.show(surface)

    def _finish_dynamic(self):
        session, self.session = self.session, None
        self.timer.stop()
        if self in _dragging:
            _dragging.remove(self)
        self._close_preview()
        try:
            session.finish(self.released_at, do_command=Gui.doCommand)
        except Exception as error:
            self._refuse(error)
        self.rebuild(self.constraint)

    def _settle_now(self):
        if isinstance(self.session, dynamic_drag.DynamicDrag) and self.session.released:
            self._finish_dynamic()

    def begin_origin_drag(self):
        try:
            self.session = drag.OriginDrag(self.constraint)
        except drag.DragError as error:
            self._refuse(error)
            return False
        _dragging.append(self)
        return True

    def drag_to(self, target):
        """Re-solve for the target and draw the result (the Sheet's Shape waits for the release)."""
        if self.session is None:
            return None
        if isinstance(self.session, dynamic_drag.DynamicDrag):  # the timer's frames move it
            self.target = target
            self._tick()
            return None
        if isinstance(self.session, drag.RecomputeDrag):
            try:
                self.session.move(target)
            except drag.DragError as error:
                self._refuse(error)
            return None
        try:
            surface = self.session.move(target, update_shape=self.preview is None)
        except drag.DragError as error:
            self._refuse(error)
            return None
        if self.preview is not None:
            self.preview.show(surface)
        return surface

    def _close_preview(self):
        preview, self.preview = getattr(self, "preview", None), None
        if preview is not None:
            preview.close()

    def end_drag(self, target):
        if isinstance(self.session, dynamic_drag.DynamicDrag):  # settles in the timer's frames
            self.session.release(target)
            self.released_at, self.settle_frames = target, 0
            return
        session, self.session = self.session, None
        if self in _dragging:
            _dragging.remove(self)
        self._close_preview()
        if session is None:
            return
        try:
            session.finish(target, do_command=Gui.doCommand)
        except Exception as error:
            self._refuse(error)
        self.rebuild(self.constraint)

    def cancel_drag(self):
        if isinstance(self.session, dynamic_drag.DynamicDrag):
            self.timer.stop()
        session, self.session = self.session, None
        if self in _dragging:
            _dragging.remove(self)
        self._close_preview()
        if session is not None:
            session.cancel()
        self.rebuild(self.constraint)

    def _refuse(self, error):
        self.errors.append(str(error))
        App.Console.PrintError(f"VarSurf: {error}\n")


def refresh_sheet_handles(sheet):
    """Redraw the handles of a Sheet's constraints (their places follow the solved sheet)."""
    for c in getattr(sheet, "Constraints", None) or []:
        proxy = getattr(getattr(c, "ViewObject", None), "Proxy", None)
        handles = getattr(proxy, "handles", None)
        if handles is not None and handles not in _dragging:
            handles.rebuild(c)


def is_dragging():
    return bool(_dragging)


class CurveHandles:
    """The handles of a variational SpaceCurve, each a pin: dragging one moves the curve and, as
    fast as their joint solve allows, every sheet joined to it (Welch & Witkin Figure 2)."""

    def __init__(self, vobj):
        self.root = own_root(vobj, "VarSurfCurveHandles")
        self.curve = None
        self.draggers = []
        self.scale = 1.0
        self.session = None
        self.errors = []

    def rebuild(self, curve):
        if self in _dragging:
            return
        self.curve = curve
        self.root.removeAllChildren()
        self.draggers = []
        shape = curve.Shape
        size = HANDLE_SIZE * max(shape.BoundBox.DiagonalLength if not shape.isNull() else 100.0, 1.0)
        self.scale = size
        for i, target in enumerate(curve.Handles):
            self.draggers.append(add_pin(self.root, V(target), size, lambda i=i: self.begin_drag(i),
                                         lambda t: self.drag_to(t), lambda t: self.end_drag(t)))

    def handle_position(self, index):
        return pin_position(self.draggers[index], self.scale)

    def begin_drag(self, index):
        try:
            self.session = drag.HandleDrag(self.curve, index)
        except drag.DragError as error:
            self.errors.append(str(error))
            App.Console.PrintError(f"VarSurf: {error}\n")
            return False
        _dragging.append(self)
        return True

    def drag_to(self, target):
        if self.session is not None:
            self.session.move(target)

    def end_drag(self, target):
        if isinstance(self.session, dynamic_drag.DynamicDrag):  # settles in the timer's frames
            self.session.release(target)
            self.released_at, self.settle_frames = target, 0
            return
        session, self.session = self.session, None
        if self in _dragging:
            _dragging.remove(self)
        if session is not None:
            try:
                session.finish(target, do_command=Gui.doCommand)
            except Exception as error:
                self.errors.append(str(error))
                App.Console.PrintError(f"VarSurf: {error}\n")
        self.rebuild(self.curve)
