# SPDX-License-Identifier: LGPL-2.1-or-later
"""The PdeSurface task panel in the real FreeCAD GUI (under Xvfb):

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/pde_panel_gui.py

A PdeSurface between two edges with their derivative curves; a double click opens its panel; a
new a and a painted region previewed with Update, then OK (one undoable step); opened again and
cancelled after a change (the change is undone); a screenshot of the window with the panel open.
Then a Point's pin on the surface dragged in the view as the pointer would (each move an update
of the prepared solve, the preview drawn), a screenshot while it moves, and the release: one
undoable step; and dragged again with DragMode Dynamic and a heavier region painted around the
pin (both set in the panel): the surface follows
with inertia at the timer's frames, settles after the release, which is written. Writes
$VARSURF_GUI_OUT/pde_panel.json and quits.
"""

import math
import os
import sys
import time

import FreeCAD as App
import FreeCADGui as Gui
import Part
from PySide import QtCore, QtGui

import varsurf  # the Mod link puts VarSurf on the path

# The helpers the GUI scripts share live beside this one.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__)))),
                                "tests", "gui"))
from gui_helpers import (clipped_widgets, press_task_button, report_view_text, run_when_up, task_widgets,  # noqa: E402
                         window_shot)

OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-pde-panel")
os.makedirs(OUT, exist_ok=True)


def run(result):
    Gui.activateWorkbench("VarSurfWorkbench")

    doc = App.newDocument("PdePanel")
    doc.UndoMode = 1
    # An arched boundary beside a straight one: the surface depends on a (along v it bends).
    for name, x, z, rise in (("U0", 0.0, 0.0, 15.0), ("U1", 60.0, 10.0, 0.0), ("D0", 15.0, 20.0, 15.0),
                             ("D1", 75.0, 10.0, 0.0)):
        edge = doc.addObject("Part::Feature", name)
        ends = App.Vector(x, 0, z), App.Vector(x, 80, z)
        edge.Shape = (Part.Arc(ends[0], App.Vector(x, 40, z + rise), ends[1]) if rise
                      else Part.LineSegment(*ends)).toShape()
    doc.recompute()
    pde = varsurf.make_pde_surface((doc.U0, "Edge1"), (doc.U1, "Edge1"), derivative0=(doc.D0, "Edge1"),
                                   derivative1=(doc.D1, "Edge1"))
    doc.recompute()
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    before = [p for row in pde.Shape.Faces[0].Surface.getPoles() for p in row]
    pde.ViewObject.Proxy.doubleClicked(pde.ViewObject)
    Gui.updateGui()
    w = task_widgets("VarSurfPdeSurface")
    result["shown"] = [w["kindValue"].text(), w["aSpin"].value(), w["regionTable"].rowCount()]
    w["aSpin"].setValue(2.5)
    w["addRegionButton"].click()
    w["updateButton"].click()
    Gui.updateGui()
    result["previewed"] = [round(float(pde.PdeA), 4), list(pde.PdeRegions), pde.isValid()]
    result["clipped"] = clipped_widgets("VarSurfPdeSurface")
    shot = os.path.join(OUT, "pde_panel.png")
    window_shot(shot)
    result["shot"] = shot
    press_task_button(QtGui.QDialogButtonBox.Ok)
    Gui.updateGui()
    result["report_after_ok"] = report_view_text()
    after = [p for row in pde.Shape.Faces[0].Surface.getPoles() for p in row]
    result["ok"] = [round(float(pde.PdeA), 4), len(pde.PdeRegions), pde.isValid(), doc.UndoNames[:1],
                    max((p - q).Length for p, q in zip(before, after)) > 1e-3]
    # Opened again, changed, cancelled: the change is undone.
    pde.ViewObject.Proxy.doubleClicked(pde.ViewObject)
    Gui.updateGui()
    w = task_widgets("VarSurfPdeSurface")
    result["reloaded"] = [round(w["aSpin"].value(), 4), w["regionTable"].rowCount()]
    w["aSpin"].setValue(7.0)
    w["removeRegionButton"].click()
    w["updateButton"].click()
    Gui.updateGui()
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    Gui.updateGui()
    result["report_after_cancel"] = report_view_text()
    result["cancelled"] = [round(float(pde.PdeA), 4), len(pde.PdeRegions), pde.isValid()]

    # a painted in the view: Paint in view down, a rectangle dragged over the surface with the
    # mouse (Qt events on the 3D view's GL widget, as the pointer gives them), then OK.
    pde.ViewObject.Proxy.doubleClicked(pde.ViewObject)
    Gui.updateGui()
    w = task_widgets("VarSurfPdeSurface")
    w["paintSpin"].setValue(6.0)
    w["paintButton"].click()
    Gui.updateGui()
    result["painted"] = paint_rectangle(pde, (0.3, 0.3), (0.6, 0.7), os.path.join(OUT, "pde_paint.png"))
    result["painted_rows"] = w["regionTable"].rowCount()
    # A loop drawn around (0.5, 0.45): the Loop shape, a circular drag.
    w["paintShapeCombo"].setCurrentIndex(1)
    circle = [(0.5 + 0.15 * math.cos(2 * math.pi * k / 40), 0.45 + 0.15 * math.sin(2 * math.pi * k / 40))
              for k in range(40)]
    drag_over(pde, circle, os.path.join(OUT, "pde_paint_loop.png"))
    result["loops_label"] = w["loopsValue"].text()
    result["loop_status"] = w["statusValue"].text()
    loops = list(pde.PdeLoops)
    points = [(loops[2 + 2 * i], loops[3 + 2 * i]) for i in range(int(loops[1]))] if loops else []
    result["loop"] = [loops[:2], max((abs(math.hypot(u - 0.5, v - 0.45) - 0.15) for u, v in points), default=None),
                      pde.isValid()]
    # A drag that starts off the surface (beyond its u = 1 edge) paints nothing: the view has it;
    # and painting goes on after it.
    w["paintShapeCombo"].setCurrentIndex(0)
    result["painted_off"] = paint_rectangle(pde, (1.6, 0.5), (0.5, 0.8), None)["regions"]
    result["painted_after_off"] = paint_rectangle(pde, (0.1, 0.1), (0.2, 0.2), None)["regions"]
    press_task_button(QtGui.QDialogButtonBox.Ok)
    Gui.updateGui()
    result["paint_ok"] = [[round(float(x), 2) for x in pde.PdeRegions], len(pde.PdeLoops), pde.isValid(),
                          doc.UndoNames[:1],
                          report_view_text()[len(result["report_after_cancel"]):]]

    # A Point's pin dragged up 12 mm in the view.
    from varsurf.app import drag

    start = pde.Shape.Faces[0].Surface.value(0.5, 0.5)
    pin = varsurf.make_constraint(pde, "Point", uv=(0.5, 0.5), origin=start, name="Pin")
    doc.recompute()
    handles = pin.ViewObject.Proxy.handles
    result["drag_began"] = handles.begin_drag()
    result["drag_session"] = type(handles.session).__name__
    moves, t0 = 30, time.perf_counter()
    for k in range(1, moves + 1):
        target = start + App.Vector(0, 0, 12.0 * k / moves)
        handles.dragger.translation.setValue(*(target / handles.scale))  # as the pointer would
        handles.drag_to(handles.dragger_target())
        Gui.updateGui()
    result["drag_moves_per_second"] = moves / (time.perf_counter() - t0)
    preview = handles.preview.points if handles.preview is not None else None
    result["preview_through_pin"] = None if preview is None else min(
        ((p[0] - target.x) ** 2 + (p[1] - target.y) ** 2 + (p[2] - target.z) ** 2) ** 0.5 for p in preview.tolist())
    shot = os.path.join(OUT, "pde_drag.png")
    window_shot(shot)
    result["drag_shot"] = shot
    handles.end_drag(handles.dragger_target())
    result["drag_errors"] = list(handles.errors)
    result["after_drag"] = [pde.isValid(), doc.UndoNames[:1] == [drag.TRANSACTION],
                            pde.Shape.distToShape(Part.Vertex(target))[0]]

    # The same pin dragged dynamically (DragMode Dynamic, set in the panel): the pointer moves
    # down 12 mm over a second at 60 moves a second, the surface follows with inertia in the
    # timer's frames, and settles after the release, which is then written.
    pde.ViewObject.Proxy.doubleClicked(pde.ViewObject)
    Gui.updateGui()
    w = task_widgets("VarSurfPdeSurface")
    result["dynamics_shown"] = [w["dragModeCombo"].currentText(), w["massSpin"].value(), w["dampingSpin"].value(),
                                w["springSpin"].value()]
    w["dragModeCombo"].setCurrentText("Dynamic")
    w["dampingSpin"].setValue(0.3)
    w["addMaterialButton"].click()  # a heavier region around the pin (4 x Mass, the damping)
    Gui.updateGui()
    result["material_rows"] = w["materialTable"].rowCount()
    for area in Gui.getMainWindow().findChildren(QtGui.QScrollArea):  # the panel scrolled to the table
        if area.isAncestorOf(w["materialTable"]):
            area.ensureWidgetVisible(w["materialTable"])
    Gui.updateGui()
    shot = os.path.join(OUT, "pde_dynamics_panel.png")
    window_shot(shot)
    result["dynamics_shot"] = shot
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["dynamics_stored"] = [str(pde.DragMode), round(float(pde.Damping), 3),
                                 [round(float(x), 4) for x in pde.MaterialRegions]]
    high = target
    result["dynamic_began"] = handles.begin_drag()
    result["dynamic_session"] = type(handles.session).__name__
    shown = []
    original_show = handles.preview.show if handles.preview is not None else None
    if original_show is not None:
        def counting(surface):
            shown.append(surface.evaluate(0.5, 0.5)[2])
            return original_show(surface)
        handles.preview.show = counting
    t0 = time.perf_counter()
    moves = 60
    for k in range(1, moves + 1):
        target = high - App.Vector(0, 0, 12.0 * k / moves)
        handles.dragger.translation.setValue(*(target / handles.scale))
        handles.drag_to(handles.dragger_target())
        until = t0 + k / 60.0
        while time.perf_counter() < until:
            QtGui.QApplication.processEvents()
            Gui.updateGui()
    elapsed = time.perf_counter() - t0
    result["dynamic_frames_per_second"] = len(shown) / elapsed
    result["dynamic_lag"] = shown[-1] - target.z if shown else None  # still above the pointer: inertia
    shot = os.path.join(OUT, "pde_dynamic_drag.png")
    window_shot(shot)
    result["dynamic_shot"] = shot
    handles.end_drag(handles.dragger_target())
    t1 = time.perf_counter()
    while handles.session is not None and time.perf_counter() - t1 < 6.0:
        QtGui.QApplication.processEvents()
        Gui.updateGui()
    result["dynamic_settle_seconds"] = time.perf_counter() - t1
    result["dynamic_errors"] = list(handles.errors)
    result["after_dynamic"] = [handles.session is None, pde.isValid(), doc.UndoNames[:1] == [drag.TRANSACTION],
                               pde.Shape.distToShape(Part.Vertex(target))[0]]
    Gui.updateGui()
    result["report_at_end"] = report_view_text()


def drag_over(pde, path, shot):
    """Press the left button on the surface point at (u, v) path[0], move through the others and
    release at the last, as the pointer does (the GL widget's Qt events); a screenshot before the
    release. Points beyond u = 1 lie on the surface's tangent plane past its edge."""
    view = Gui.ActiveDocument.ActiveView
    gl = next(w for w in Gui.getMainWindow().findChildren(QtGui.QWidget)
              if w.metaObject().className() == "QOpenGLWidget" and w.isVisible())
    width, height = view.getSize()
    face = pde.Shape.Faces[0]

    def at(uv):  # Coin's pixels (from the bottom left) to the widget's (from the top left)
        u, v = uv
        beyond = face.Surface.getDN(1.0, v, 1, 0) * (u - min(u, 1.0))
        x, y = view.getPointOnScreen(face.Surface.value(min(u, 1.0), v) + beyond)
        return QtCore.QPoint(round(x * gl.width() / width), round((height - 1 - y) * gl.height() / height))

    def send(kind, point, buttons):
        event = QtGui.QMouseEvent(kind, point, QtCore.Qt.LeftButton if kind != QtCore.QEvent.MouseMove
                                  else QtCore.Qt.NoButton, buttons, QtCore.Qt.NoModifier)
        QtGui.QApplication.sendEvent(gl, event)
        Gui.updateGui()

    camera = view.getCameraOrientation().Q, view.getCameraNode().position.getValue().getValue()
    send(QtCore.QEvent.MouseButtonPress, at(path[0]), QtCore.Qt.LeftButton)
    for uv in path[1:]:
        send(QtCore.QEvent.MouseMove, at(uv), QtCore.Qt.LeftButton)
    if shot:
        window_shot(shot)
    send(QtCore.QEvent.MouseButtonRelease, at(path[-1]), QtCore.Qt.NoButton)
    after = view.getCameraOrientation().Q, view.getCameraNode().position.getValue().getValue()
    turned = max(abs(a - b) for a, b in zip(camera[0] + camera[1], after[0] + after[1]))
    return {"shot": shot, "view_moved": turned, "regions": [round(float(x), 3) for x in pde.PdeRegions]}


def paint_rectangle(pde, corner0, corner1, shot):
    """A drag from the surface point at (u, v) corner0 to the one at corner1."""
    path = [(corner0[0] + k / 10 * (corner1[0] - corner0[0]), corner0[1] + k / 10 * (corner1[1] - corner0[1]))
            for k in range(11)]
    return drag_over(pde, path, shot)


run_when_up([run], os.path.join(OUT, "pde_panel.json"))
