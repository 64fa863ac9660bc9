# SPDX-License-Identifier: LGPL-2.1-or-later
"""The PdeSurface task panel in the real FreeCAD GUI (under Xvfb):

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/pde_panel_gui.py

A PdeSurface between two edges with their derivative curves; a double click opens its panel; a
new a and a painted region previewed with Update, then OK (one undoable step); opened again and
cancelled after a change (the change is undone); a screenshot of the window with the panel open.
Writes $VARSURF_GUI_OUT/pde_panel.json and quits.
"""

import json
import os
import traceback

import FreeCAD as App
import FreeCADGui as Gui
import Part
from PySide import QtCore, QtGui

OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-pde-panel")
os.makedirs(OUT, exist_ok=True)


def widgets():
    forms = [w for w in QtGui.QApplication.allWidgets() if w.objectName() == "VarSurfPdeSurface" and w.isVisible()]
    if not forms:
        raise RuntimeError("no visible PDE surface panel")
    return {w.objectName(): w for w in forms[-1].findChildren(QtGui.QWidget) if w.objectName()}


def press(which):
    for widget in QtGui.QApplication.allWidgets():
        if isinstance(widget, QtGui.QDialogButtonBox):
            button = widget.button(which)
            if button is not None and button.isVisible():
                button.click()
                break
    Gui.updateGui()


def clipped():
    """Named widgets of the panel reaching beyond the task view's visible width."""
    forms = [w for w in QtGui.QApplication.allWidgets() if w.objectName() == "VarSurfPdeSurface" and w.isVisible()]
    scroll = forms[-1].parentWidget()
    while scroll is not None and not isinstance(scroll, QtGui.QScrollArea):
        scroll = scroll.parentWidget()
    viewport = scroll.viewport()
    return sorted(w.objectName() for w in forms[-1].findChildren(QtGui.QWidget)
                  if w.isVisible() and w.objectName() and not w.objectName().startswith("qt_")
                  and w.mapTo(viewport, QtCore.QPoint(w.width(), 0)).x() > viewport.width() + 1)


def window_shot(path):
    """The main window with its 3D view: Qt's grab() leaves the OpenGL view blank under Xvfb, so
    the view is rendered offscreen (saveImage) and painted over it."""
    Gui.updateGui()
    window = Gui.getMainWindow()
    picture = window.grab()
    area = window.findChild(QtGui.QMdiArea)
    sub = area.activeSubWindow() if area is not None else None
    views = [w for w in sub.widget().findChildren(QtGui.QWidget)
             if w.metaObject().className() == "QOpenGLWidget" and w.isVisible()] if sub is not None else []
    if views:
        rendered = path + ".view.png"
        Gui.ActiveDocument.ActiveView.saveImage(rendered, views[0].width(), views[0].height(), "Current")
        painter = QtGui.QPainter(picture)
        painter.drawImage(views[0].mapTo(window, QtCore.QPoint(0, 0)), QtGui.QImage(rendered))
        painter.end()
        os.remove(rendered)
    picture.save(path)


def run(result):
    Gui.activateWorkbench("VarSurfWorkbench")
    import varsurf

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
    w = widgets()
    result["shown"] = [w["kindValue"].text(), w["aSpin"].value(), w["regionTable"].rowCount()]
    w["aSpin"].setValue(2.5)
    w["addRegionButton"].click()
    w["updateButton"].click()
    Gui.updateGui()
    result["previewed"] = [round(float(pde.PdeA), 4), list(pde.PdeRegions), pde.isValid()]
    result["clipped"] = clipped()
    shot = os.path.join(OUT, "pde_panel.png")
    window_shot(shot)
    result["shot"] = shot
    press(QtGui.QDialogButtonBox.Ok)
    after = [p for row in pde.Shape.Faces[0].Surface.getPoles() for p in row]
    result["ok"] = [round(float(pde.PdeA), 4), len(pde.PdeRegions), pde.isValid(), doc.UndoNames[:1],
                    max((p - q).Length for p, q in zip(before, after)) > 1e-3]
    # Opened again, changed, cancelled: the change is undone.
    pde.ViewObject.Proxy.doubleClicked(pde.ViewObject)
    Gui.updateGui()
    w = widgets()
    result["reloaded"] = [round(w["aSpin"].value(), 4), w["regionTable"].rowCount()]
    w["aSpin"].setValue(7.0)
    w["removeRegionButton"].click()
    w["updateButton"].click()
    Gui.updateGui()
    press(QtGui.QDialogButtonBox.Cancel)
    result["cancelled"] = [round(float(pde.PdeA), 4), len(pde.PdeRegions), pde.isValid()]


def main():
    result = {}
    try:
        run(result)
    except Exception:
        result["error"] = traceback.format_exc()
    with open(os.path.join(OUT, "pde_panel.json"), "w") as out:
        json.dump(result, out, indent=1)
    os._exit(0)


QtCore.QTimer.singleShot(0, main)
