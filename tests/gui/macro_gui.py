# SPDX-License-Identifier: LGPL-2.1-or-later
"""Records a VarSurf session with FreeCAD's own macro recorder, in the real GUI (under Xvfb), then
replays the macro in a fresh document of the same GUI:

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/macro_gui.py

The session is what a user does: the scene typed into the Python console (a wavy closed rim and
two planes), then through the commands: two Sheets on the planes through the rim, property edits
(as the property editor records them), a Normal constraint, the Solid, a color map. Writes
$VARSURF_GUI_OUT/macro.json (the sheets' poles and the solid's volume, recorded and replayed, and
the view state after the replay) and keeps the macro there as varsurf_session.FCMacro; the test
(tests/python/test_gui_macro.py) replays it in freecadcmd too.
"""

import json
import os
import sys
import traceback

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore, QtGui

OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-macro")
os.makedirs(OUT, exist_ok=True)
RESULT = os.path.join(OUT, "macro.json")
MACRO = "varsurf_session"
DOC = "Recorded"

# The scene, as a user types it into the Python console (the recorder keeps console lines).
SCENE = [
    "import math",
    "import Part",
    f"doc = App.newDocument({DOC!r})",
    "rim = doc.addObject('Part::Feature', 'Rim')",
    "c = Part.BSplineCurve()",
    "c.interpolate([App.Vector(40 * math.cos(t), 25 * math.sin(t), 4 * math.sin(2 * t)) "
    "for t in (2 * math.pi * k / 48 for k in range(48))], PeriodicFlag=True)",
    "rim.Shape = c.toShape()",
    "top = doc.addObject('Part::Plane', 'TopBase')",
    "top.Length, top.Width = 120, 90",
    "top.Placement.Base = App.Vector(-60, -45, 0)",
    "bottom = doc.addObject('Part::Plane', 'BottomBase')",
    "bottom.Length, bottom.Width = 120, 90",
    "bottom.Placement.Base = App.Vector(-60, -45, 0)",
    "doc.recompute()",
]


def start_recording():
    """Macro > Macro recording...: a name, this folder, Record (the dialog is modal: filled from
    a timer once it is up)."""
    def fill():
        for widget in QtGui.QApplication.topLevelWidgets():
            if widget.metaObject().className() == "Gui::Dialog::DlgMacroRecordImp" and widget.isVisible():
                widget.findChild(QtGui.QLineEdit, "lineEditPath").setText(MACRO)
                widget.findChild(QtGui.QLineEdit, "lineEditMacroPath").setText(OUT + os.sep)
                widget.findChild(QtGui.QPushButton, "buttonStart").click()
    path = os.path.join(OUT, MACRO + ".FCMacro")
    if os.path.exists(path):
        os.remove(path)
    QtCore.QTimer.singleShot(300, fill)
    Gui.runCommand("Std_DlgMacroRecord")
    return path


def select(*items):
    Gui.Selection.clearSelection()
    for item in items:
        Gui.Selection.addSelection(DOC, *item)


def state(doc):
    """What the comparison needs: each sheet's poles, the solid's volume and validity."""
    import varsurf

    out = {"sheets": {}}
    for obj in doc.Objects:
        if varsurf.is_sheet(obj) and not obj.Shape.isNull():
            surface = obj.Shape.Faces[0].Surface
            out["sheets"][obj.Name] = [[tuple(p) for p in row] for row in surface.getPoles()]
        if getattr(getattr(obj, "Proxy", None), "Type", "") == "VarSurf::Solid":
            out["solid"] = [obj.Name, obj.isValid(), obj.Shape.Volume if not obj.Shape.isNull() else 0.0]
    out["invalid"] = sorted(o.Name for o in doc.Objects if not o.isValid())
    return out


def run(result):
    Gui.activateWorkbench("VarSurfWorkbench")
    path = start_recording()
    for line in SCENE:
        Gui.doCommand(line)  # what pressing Enter in the Python console does
    doc = App.getDocument(DOC)
    Gui.updateGui()
    select(("TopBase", "Face1"), ("Rim", "Edge1"))
    Gui.runCommand("VarSurf_Sheet")
    select(("BottomBase", "Face1"), ("Rim", "Edge1"))
    Gui.runCommand("VarSurf_Sheet")
    sheets = [o.Name for o in doc.Objects if o.Name.startswith("Sheet")]
    result["sheet_names"] = sheets
    # the property editor records an edit as this line
    for name, pressure in zip(sheets, (0.1, -0.1)):
        for prop, value in (("Stretch", 1.0), ("Tolerance", 0.001), ("Pressure", pressure), ("Trim", "Loop")):
            Gui.doCommand(f"App.getDocument({DOC!r}).getObject({name!r}).{prop} = {value!r}")
    Gui.doCommand(f"App.getDocument({DOC!r}).recompute()")
    select((sheets[0], ""))
    Gui.runCommand("VarSurf_Normal")
    select((sheets[0], ""), (sheets[1], ""))
    Gui.runCommand("VarSurf_Solid")
    select((sheets[0], ""))
    Gui.runCommand("VarSurf_ColorMap")
    Gui.Selection.clearSelection()
    Gui.runCommand("Std_MacroStopRecord")
    result["recorded"] = state(doc)
    result["analysis_recorded"] = str(doc.getObject(sheets[0]).ViewObject.Analysis)
    result["undo_names"] = list(doc.UndoNames)
    with open(path) as handle:
        result["macro"] = handle.read()

    # replay in a fresh GUI document: the recorded one is closed first (the macro makes its own)
    App.closeDocument(DOC)
    Gui.updateGui()
    # as Macro > Macros... > Execute runs it: in a copy of the console's namespace (App, Gui)
    namespace = dict(sys.modules["__main__"].__dict__, __file__=path)
    exec(compile(result["macro"], path, "exec"), namespace)
    Gui.updateGui()
    again = App.getDocument(DOC)
    result["replayed"] = state(again)
    replayed_sheet = again.getObject(sheets[0])
    result["replayed_view_provider"] = type(getattr(replayed_sheet.ViewObject, "Proxy", None)).__name__


def main():
    result = {"ok": False}
    try:
        run(result)
        result["ok"] = True
    except Exception:
        result["error"] = traceback.format_exc()
    with open(RESULT, "w") as handle:
        json.dump(result, handle, indent=1, default=str)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


# run once the event loop is up (the recorder's dialog and the commands need it)
QtCore.QTimer.singleShot(0, main)
