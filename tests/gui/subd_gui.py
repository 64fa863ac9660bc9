# SPDX-License-Identifier: LGPL-2.1-or-later
"""Subdivision surfaces in the real FreeCAD GUI (under Xvfb):

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/subd_gui.py

A Part Box and a Part Sphere selected, the command "Subdivision surface from a cage" makes a
SubdSurface capturing the sphere; selected, "Subdivision surface to B-rep" makes its SubdBRep;
screenshots of the window; undo removes the B-rep. The SubdSurface's panel (double click): the
level slider draws a level's mesh, a click on the surface (a real Qt mouse event) pins the
nearest vertex, the influence slider shrinks the region of influence drawn, the normal held;
OK is one undoable step; opened again, a pin removed and Cancel puts it back. Then a document
written without the GUI
($VARSURF_SUBD_DOC) opened: its objects get their view providers. Writes
$VARSURF_GUI_OUT/subd.json and quits.
"""

import math
import os
import sys
import time

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore, QtGui

import varsurf  # the Mod link puts VarSurf on the path

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__)))),
                                "tests", "gui"))
from gui_helpers import (clipped_widgets, press_task_button, report_view_text, run_when_up, task_widgets,  # noqa: E402
                         open_written_without_gui, proxy_name, window_shot)

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__))))
OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-subd")
os.makedirs(OUT, exist_ok=True)


def run(result):
    Gui.activateWorkbench("VarSurfWorkbench")
    doc = App.newDocument("Subd")
    doc.UndoMode = 1
    box = doc.addObject("Part::Box", "Cage")
    box.Length = box.Width = box.Height = 20.0
    box.Placement.Base = App.Vector(-10, -10, -10)
    sphere = doc.addObject("Part::Sphere", "Target")
    sphere.Radius = 13.0
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(box)
    Gui.Selection.addSelection(sphere)
    Gui.runCommand("VarSurf_SubdSurface")
    Gui.updateGui()
    subd = next(o for o in doc.Objects if varsurf.is_subd_surface(o))
    result["subd"] = [subd.isValid(), subd.Status, proxy_name(subd), box.ViewObject.Visibility,
                      sphere.ViewObject.Visibility, subd.ViewObject.Visibility]
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(subd)
    Gui.runCommand("VarSurf_SubdBRep")
    Gui.updateGui()
    brep = next(o for o in doc.Objects if o.TypeId == "Part::FeaturePython")
    result["brep"] = [brep.isValid(), brep.Status, proxy_name(brep), brep.Closed, subd.ViewObject.Visibility]
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    result["shot"] = window_shot(os.path.join(OUT, "subd_brep.png"))
    result["undo_names"] = list(doc.UndoNames[:2])
    doc.undo()
    Gui.updateGui()
    result["after_undo"] = sorted(o.Name for o in doc.Objects)
    panel(result, subd)
    turn_curves(result)
    loop_arcball(result)
    drag_vase(result)
    built = os.environ.get("VARSURF_SUBD_DOC")
    if built:
        open_written_without_gui(result, built, os.path.join(OUT, "subd_restored.png"))
    result["report"] = report_view_text()


def click_on(point):
    """A left click on the 3D view at a model point, as the pointer gives it (the GL widget's Qt
    events)."""
    from varsurf.gui.region_painter import gl_widget

    view = Gui.ActiveDocument.ActiveView
    gl = gl_widget(view)  # the active document's (other documents' views may count as visible)
    width, height = view.getSize()
    x, y = view.getPointOnScreen(point)
    at = QtCore.QPoint(round(x * gl.width() / width), round((height - 1 - y) * gl.height() / height))
    for kind, buttons in ((QtCore.QEvent.MouseButtonPress, QtCore.Qt.LeftButton),
                          (QtCore.QEvent.MouseButtonRelease, QtCore.Qt.NoButton)):
        QtGui.QApplication.sendEvent(gl, QtGui.QMouseEvent(kind, at, QtCore.Qt.LeftButton, buttons,
                                                           QtCore.Qt.NoModifier))
        Gui.updateGui()


def overlay_counts(subd):
    """Coordinates in the panel's overlay: the level mesh's and the region's."""
    from pivy import coin

    root = subd.ViewObject.RootNode
    found = [root.getChild(i) for i in range(root.getNumChildren())
             if root.getChild(i).getName().getString() == "VarSurfSubdOverlay"]
    if not found:
        return None
    counts = []
    for part in (found[0].getChild(0), found[0].getChild(1)):
        coords = [part.getChild(i) for i in range(part.getNumChildren())
                  if part.getChild(i).isOfType(coin.SoCoordinate3.getClassTypeId())]
        counts.append(coords[0].point.getNum() if coords else 0)
    return counts


def panel(result, subd):
    doc = subd.Document
    Gui.ActiveDocument.ActiveView.viewFront()  # the sphere's front (-y) toward the viewer
    Gui.SendMsgToActiveView("ViewFit")
    subd.ViewObject.doubleClicked()
    Gui.updateGui()
    w = task_widgets("VarSurfSubdSurface")
    w["showLevelSlider"].setValue(2)
    Gui.updateGui()
    result["panel_level"] = [w["showLevelLabel"].text(), overlay_counts(subd)]
    w["pickButton"].setChecked(True)
    click_on(App.Vector(0, -13.0, 2.0))
    level2 = subd.Proxy.outcome.levels[2]
    result["picked"] = [list(subd.PinLevels), list(subd.PinVertices), list(subd.PinInfluence),
                        min((App.Vector(*p) - App.Vector(0, -13, 2)).Length for p in level2),
                        (App.Vector(*level2[subd.PinVertices[0]]) - App.Vector(0, -13, 2)).Length
                        if len(subd.PinVertices) else None, w["pickButton"].isChecked()]
    regions = [(w["regionValue"].text(), overlay_counts(subd))]
    w["influenceSlider"].setValue(2)
    w["influenceSlider"].sliderReleased.emit()
    Gui.updateGui()
    regions.append((w["regionValue"].text(), overlay_counts(subd)))
    result["regions"] = regions
    w["normalButton"].click()
    Gui.updateGui()
    result["held"] = [len(subd.NormalDirections), w["pinTable"].item(0, 2).text() if w["pinTable"].rowCount() else ""]
    result["panel_shot"] = window_shot(os.path.join(OUT, "subd_panel.png"))
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["panel_ok"] = [doc.UndoNames[:1], list(subd.PinVertices), overlay_counts(subd), subd.isValid()]
    subd.ViewObject.doubleClicked()
    Gui.updateGui()
    w = task_widgets("VarSurfSubdSurface")
    w["pinTable"].selectRow(0)
    w["removeButton"].click()
    Gui.updateGui()
    removed = [list(subd.PinVertices), list(subd.NormalVertices)]
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["panel_cancel"] = [removed, list(subd.PinVertices), len(subd.NormalDirections), subd.isValid()]
    doc.undo()
    Gui.updateGui()
    result["panel_undo"] = [list(subd.PinVertices), subd.isValid()]
    # Last, in a panel closed by Cancel (which reads no widget): after clipped_widgets the form's
    # widgets may be gone (see gui_helpers).
    subd.ViewObject.doubleClicked()
    Gui.updateGui()
    result["panel_clipped"] = clipped_widgets("VarSurfSubdSurface")
    press_task_button(QtGui.QDialogButtonBox.Cancel)


def turn_curves(result):
    """A Part Circle on a plane's SubdSurface as its Curves: the arcball at its centre turned 20
    degrees about x in steps (each the approximate answer drawn), released: CurveMotion written in
    one undoable step. The circle becomes the Curves in the panel (selected, "Curves from
    selection")."""
    doc = App.newDocument("SubdCurves")
    doc.UndoMode = 1
    plane = doc.addObject("Part::Plane", "Cage")
    plane.Length = plane.Width = 100.0
    plane.Placement.Base = App.Vector(-50, -50, 0)
    circle = doc.addObject("Part::Circle", "Ring")
    circle.Radius = 25.0
    doc.recompute()
    subd = varsurf.make_subd_surface(plane, levels=4)
    subd.CurveMotion = App.Placement(App.Vector(0, 0, 10), App.Rotation())
    subd.CurveInfluence = 1
    doc.recompute()
    # The circle made its Curves in the panel: selected, then "Curves from selection", OK.
    subd.ViewObject.doubleClicked()
    Gui.updateGui()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(circle, "Edge1")
    w = task_widgets("VarSurfSubdSurface")
    w["curvesButton"].click()
    Gui.updateGui()
    result["curves_label"] = w["curvesValue"].text()
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["curves_set"] = [[(o.Name, list(subs)) for o, subs in subd.Curves], doc.UndoNames[:1], subd.isValid()]
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    handles = subd.ViewObject.Proxy.handles
    arcball = handles.arcball
    result["arcball"] = [arcball is not None, subd.CurvePins,
                         list(arcball.centre) if arcball is not None else None]
    if arcball is None:
        return
    result["turn_began"] = handles.begin_turn()
    from pivy import coin

    steps, t0 = 20, time.perf_counter()
    for k in range(1, steps + 1):
        q = App.Rotation(App.Vector(1, 0, 0), 20.0 * k / steps).Q
        arcball.dragger.rotation.setValue(coin.SbRotation(q[0], q[1], q[2], q[3]))  # as the pointer would
        handles.turn_to(arcball.placement())
        Gui.updateGui()
    result["turn_moves_per_second"] = steps / (time.perf_counter() - t0)
    result["turn_shot"] = window_shot(os.path.join(OUT, "subd_arcball.png"))
    handles.end_turn(arcball.placement())
    Gui.updateGui()
    motion = subd.CurveMotion
    result["turned"] = [subd.isValid(), doc.UndoNames[:1], math.degrees(motion.Rotation.Angle),
                        list(motion.Base), handles.errors, handles.preview is None]


def loop_arcball(result):
    """A sheet with a hole: in its panel, Move a loop and a click beside the hole, Hold a loop and
    a click beside the outer edge, OK (one undo step); then lifted 5 mm, the arcball stands at
    the lifted hole's centre."""
    sys.path.insert(0, os.path.join(REPO, "examples"))
    from subdivision_surfaces import grid_points, quad_cage

    doc = App.newDocument("SubdLoops")
    doc.UndoMode = 1
    cage = quad_cage(doc, "HoleCage", *grid_points(6, 60.0, hole=2))
    subd = varsurf.make_subd_surface(cage, levels=3, name="Holed")
    doc.recompute()
    cage.ViewObject.Visibility = False  # as the command leaves it: clicks land on the surface
    Gui.ActiveDocument.ActiveView.viewTop()
    Gui.SendMsgToActiveView("ViewFit")
    subd.ViewObject.doubleClicked()
    Gui.updateGui()
    w = task_widgets("VarSurfSubdSurface")
    w["moveLoopButton"].setChecked(True)
    click_on(App.Vector(30, 17, 0))  # beside the hole
    w["holdLoopButton"].setChecked(True)
    click_on(App.Vector(30, 3, 0))  # beside the outer edge
    picked = [list(subd.CurveLoops), list(subd.HeldLoops), w["curvesValue"].text(),
              w["moveLoopButton"].isChecked(), w["holdLoopButton"].isChecked()]
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["loops_picked"] = picked + [doc.UndoNames[:1], subd.BoundaryLoops]
    subd.CurveMotion = App.Placement(App.Vector(0, 0, 5), App.Rotation())
    doc.recompute()
    Gui.updateGui()
    arcball = subd.ViewObject.Proxy.handles.arcball
    result["loop_arcball"] = [subd.isValid(), subd.CurvePins, list(arcball.centre) if arcball is not None else None]
    Gui.ActiveDocument.ActiveView.viewIsometric()
    result["loop_shot"] = window_shot(os.path.join(OUT, "subd_loops.png"))


def drag_vase(result):
    """A scanned vase (10,240 faces) with one pin dragged 12 mm out in the view: each move the
    approximate answer drawn, the view redrawn; the release one undoable step."""
    sys.path.insert(0, os.path.join(REPO, "examples"))
    from subdivision_surfaces import quad_cage, vase_mesh, vase_cage_points

    doc = App.newDocument("SubdDrag")
    doc.UndoMode = 1
    cage = quad_cage(doc, "VaseCage", *vase_cage_points())
    vase = varsurf.make_subd_surface(cage, levels=4, target=vase_mesh(doc), name="Vase")
    doc.recompute()
    finest = vase.Proxy.outcome.levels[-1]
    pin = min(range(len(finest)), key=lambda k: (App.Vector(*finest[k]) - App.Vector(30, 0, 30)).Length)
    start = App.Vector(*finest[pin])
    varsurf.set_pins(vase, [(4, pin, start, 2)])
    doc.recompute()
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    handles = vase.ViewObject.Proxy.handles
    result["vase"] = [vase.isValid(), vase.FaceCount, len(handles.draggers)]
    result["drag_began"] = handles.begin_drag(0)
    view = Gui.ActiveDocument.ActiveView
    moves, t0, own = 60, time.perf_counter(), 0.0
    for k in range(1, moves + 1):
        target = start + App.Vector(12.0 * k / moves, 0, 0)
        handles.draggers[0].translation.setValue(*(target / handles.scale))  # as the pointer would
        t1 = time.perf_counter()
        handles.drag_to(handles.handle_position(0))
        own += time.perf_counter() - t1
        view.redraw()
        Gui.updateGui()
    result["drag_moves_per_second"] = moves / (time.perf_counter() - t0)
    result["drag_own_moves_per_second"] = moves / own  # VarSurf's share: the edit and the preview
    # What the window's redraw costs with nothing of VarSurf's changing (software OpenGL here).
    camera, t0 = view.getCameraNode(), time.perf_counter()
    for k in range(20):
        x, y, z = camera.position.getValue()
        camera.position.setValue(x + 1e-3, y, z)
        Gui.updateGui()
    result["redraw_seconds"] = (time.perf_counter() - t0) / 20
    result["drag_shot"] = window_shot(os.path.join(OUT, "subd_drag.png"))
    result["visible_while_dragging"] = vase.ViewObject.Visibility
    handles.end_drag(handles.handle_position(0))
    Gui.updateGui()
    result["released"] = [vase.isValid(), (App.Vector(vase.PinTargets[0]) - target).Length, doc.UndoNames[:1],
                          (App.Vector(*vase.Proxy.outcome.levels[-1][pin]) - target).Length, handles.errors]
    result["shown_after"] = [vase.ViewObject.Visibility, handles.preview is None]


run_when_up([run], os.path.join(OUT, "subd.json"))
