# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the GUI test scripts (run inside the real FreeCAD under Xvfb) do to the window: press a
task panel's buttons, read its widgets, find what the task view cuts off, read the report view,
take a picture of the whole main window."""

import json
import os
import sys
import traceback

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore, QtGui


def report_view_text():
    """Everything the report view shows."""
    widget = Gui.getMainWindow().findChild(QtGui.QTextEdit, "Report view")
    return widget.toPlainText() if widget is not None else ""


def window_shot(path):
    """The whole main window as the user sees it, saved to ``path``; the path. Qt's grab() leaves
    the OpenGL 3D view blank under Xvfb, so the active view is rendered offscreen (saveImage) and
    painted over it."""
    Gui.updateGui()
    window = Gui.getMainWindow()
    picture = window.grab()
    area = window.findChild(QtGui.QMdiArea)
    sub = area.activeSubWindow() if area is not None else None
    views = [w for w in sub.widget().findChildren(QtGui.QWidget)
             if w.metaObject().className() == "QOpenGLWidget" and w.isVisible()] if sub is not None else []
    if views and Gui.ActiveDocument is not None:
        view = views[0]
        rendered = path + ".view.png"
        Gui.ActiveDocument.ActiveView.saveImage(rendered, view.width(), view.height(), "Current")
        painter = QtGui.QPainter(picture)
        painter.drawImage(view.mapTo(window, QtCore.QPoint(0, 0)), QtGui.QImage(rendered))
        painter.end()
        os.remove(rendered)
    picture.save(path)
    return path


def panel_in_view(form_name):
    """The open panel's form and the task view's scroll area around it, or a string saying which
    is missing."""
    forms = [w for w in QtGui.QApplication.allWidgets() if w.objectName() == form_name and w.isVisible()]
    if not forms:
        return "no visible " + form_name
    scroll = forms[-1].parentWidget()
    while scroll is not None and not isinstance(scroll, QtGui.QScrollArea):
        scroll = scroll.parentWidget()
    return (forms[-1], scroll) if scroll is not None else "no scroll area"


def clipped_widgets(form_name):
    """The named widgets of the open panel that reach beyond the right edge of the task view's
    visible area (cut off, or only seen by scrolling sideways). After it, an OK pressed by
    press_task_button finds the panel's form deleted (the report view shows the panel's store()
    failing; a user's OK, after Update, after a region added or after window_shot, does not):
    check what OK stored through Update or the object."""
    found = panel_in_view(form_name)
    if isinstance(found, str):
        return [found]
    form, scroll = found
    viewport = scroll.viewport()
    return sorted(w.objectName() for w in form.findChildren(QtGui.QWidget)
                  if w.isVisible() and w.objectName() and not w.objectName().startswith("qt_")
                  and w.mapTo(viewport, QtCore.QPoint(w.width(), 0)).x() > viewport.width() + 1)


def press_task_button(which):
    """Click OK or Cancel of the open task panel, as the user would."""
    for widget in QtGui.QApplication.allWidgets():
        if isinstance(widget, QtGui.QDialogButtonBox):
            button = widget.button(which)
            if button is not None and button.isVisible():
                button.click()
                break
    Gui.updateGui()


def alive(widgets):
    """The widgets whose C++ side still exists (Qt lists widgets deleted later in the same pass)."""
    out = []
    for w in widgets:
        try:
            w.objectName()
        except RuntimeError:
            continue
        out.append(w)
    return out


def task_widgets(form="VarSurfSheet"):
    """The named widgets of the open task panel's form (not of other forms with the same names)."""
    forms = [w for w in alive(QtGui.QApplication.allWidgets()) if w.objectName() == form and w.isVisible()]
    if not forms:
        raise RuntimeError(f"no visible {form} panel")
    return {w.objectName(): w for w in forms[-1].findChildren(QtGui.QWidget) if w.objectName()}


def run_when_up(steps, path, mark_ok=False):
    """Once the event loop is up (commands, task panels and the recorder need it): run each of
    `steps` on one result dict, the first failure's traceback kept as its "error" (and "ok" set
    when all ran, with `mark_ok`); write the result as JSON to `path` and end FreeCAD."""
    def main():
        result = {"ok": False} if mark_ok else {}
        try:
            for step in steps:
                step(result)
            if mark_ok:
                result["ok"] = True
        except Exception:
            result["error"] = traceback.format_exc()
        with open(path, "w") as handle:
            json.dump(result, handle, indent=1, default=str)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(0)

    QtCore.QTimer.singleShot(0, main)


def proxy_name(obj):
    """The class name of an object's view-provider proxy ('NoneType' without one)."""
    return type(getattr(obj.ViewObject, "Proxy", None)).__name__


def open_written_without_gui(result, path, shot):
    """Open the document at `path` (written by a script without the GUI): the sorted view-provider
    classes its VarSurf objects got as result["restored"], whether all are valid as
    result["restored_valid"], and a screenshot of the window at `shot` as result["shot_restored"]."""
    again = App.openDocument(path)
    Gui.updateGui()
    result["restored"] = sorted(proxy_name(o) for o in again.Objects
                                if getattr(getattr(o, "Proxy", None), "Type", "").startswith("VarSurf::"))
    result["restored_valid"] = all(o.isValid() for o in again.Objects)
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    result["shot_restored"] = window_shot(shot)
