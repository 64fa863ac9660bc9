# SPDX-License-Identifier: LGPL-2.1-or-later
"""Triangular surfaces in the real FreeCAD GUI (under Xvfb):

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/triangular_gui.py

A coarse Mesh of a handle selected, the command "Triangular surface from a mesh" makes a
TriangularSurface (its view provider, the mesh hidden, one undo step); a screenshot of the
window; its panel (double click) raises the degree with Update and OK as one undoable step, and
Cancel after a change puts it back; a document written without the GUI ($VARSURF_TRI_DOC) opened
gets its view providers. Writes $VARSURF_GUI_OUT/triangular.json and quits.
"""

import math
import os
import sys

import FreeCAD as App
import FreeCADGui as Gui
import Mesh
from PySide import QtGui

import varsurf  # the Mod link puts VarSurf on the path

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__)))),
                                "tests", "gui"))
from gui_helpers import clipped_widgets, press_task_button, report_view_text, run_when_up, task_widgets  # noqa: E402
from gui_helpers import open_written_without_gui, proxy_name, window_shot  # noqa: E402

OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-triangular")
os.makedirs(OUT, exist_ok=True)
FORM = "VarSurfTriangularSurface"


def handle_mesh(nu=8, nv=6, big=20.0, small=7.0):
    points, facets = [], []
    for i in range(nu):
        for j in range(nv):
            u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            points.append(App.Vector((big + small * math.cos(v)) * math.cos(u),
                                     (big + small * math.cos(v)) * math.sin(u), small * math.sin(v)))
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = i * nv + (j + 1) % nv, ((i + 1) % nu) * nv + (j + 1) % nv
            facets += [[points[a], points[b], points[d]], [points[a], points[d], points[c]]]
    return Mesh.Mesh(facets)


def run(result):
    Gui.activateWorkbench("VarSurfWorkbench")
    doc = App.newDocument("Triangular")
    doc.UndoMode = 1
    mesh = doc.addObject("Mesh::Feature", "Handle")
    mesh.Mesh = handle_mesh()
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(mesh)
    Gui.runCommand("VarSurf_TriangularSurface")
    Gui.updateGui()
    surface = next(o for o in doc.Objects if varsurf.is_triangular_surface(o))
    result["made"] = [surface.isValid(), surface.Status, proxy_name(surface), mesh.ViewObject.Visibility,
                      surface.ViewObject.Visibility, surface.Closed, surface.WorstAngle]
    result["undo_names"] = list(doc.UndoNames[:1])
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    result["shot"] = window_shot(os.path.join(OUT, "triangular.png"))
    # The panel: degree 4 with Update, then OK.
    Gui.ActiveDocument.setEdit(surface.Name, 0)
    Gui.updateGui()
    widgets = task_widgets(FORM)
    widgets["degreeSpin"].setValue(4)
    widgets["updateButton"].click()
    Gui.updateGui()
    result["updated"] = [int(surface.Degree), widgets["patchesValue"].text(), widgets["worstValue"].text()]
    result["panel_shot"] = window_shot(os.path.join(OUT, "triangular_panel.png"))
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["panel_ok"] = [int(surface.Degree), list(doc.UndoNames[:1]), surface.isValid()]
    # Cancel after a change puts it back.
    Gui.ActiveDocument.setEdit(surface.Name, 0)
    Gui.updateGui()
    task_widgets(FORM)["g1Check"].setChecked(False)
    task_widgets(FORM)["updateButton"].click()
    Gui.updateGui()
    changed = bool(surface.G1)
    # Checked here, not before an OK: see clipped_widgets.
    result["clipped"] = clipped_widgets(FORM)
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["panel_cancel"] = [changed, bool(surface.G1), surface.isValid()]
    doc.undo()
    doc.undo()
    Gui.updateGui()
    result["after_undo"] = sorted(o.Name for o in doc.Objects)
    built = os.environ.get("VARSURF_TRI_DOC")
    if built:
        open_written_without_gui(result, built, os.path.join(OUT, "triangular_restored.png"))
    result["report"] = report_view_text()


run_when_up([run], os.path.join(OUT, "triangular.json"))
