# SPDX-License-Identifier: LGPL-2.1-or-later
"""Subdivision surfaces in the real FreeCAD GUI (under Xvfb):

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/subd_gui.py

A Part Box and a Part Sphere selected, the command "Subdivision surface from a cage" makes a
SubdSurface capturing the sphere; selected, "Subdivision surface to B-rep" makes its SubdBRep;
screenshots of the window; undo removes the B-rep. Then a document written without the GUI
($VARSURF_SUBD_DOC) opened: its objects get their view providers. Writes
$VARSURF_GUI_OUT/subd.json and quits.
"""

import json
import os
import sys
import time
import traceback

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore

import varsurf  # the Mod link puts VarSurf on the path

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__)))),
                                "tests", "gui"))
from gui_helpers import report_view_text, window_shot  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__))))
OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-subd")
os.makedirs(OUT, exist_ok=True)


def proxy_name(obj):
    return type(getattr(obj.ViewObject, "Proxy", None)).__name__


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
    drag_vase(result)
    built = os.environ.get("VARSURF_SUBD_DOC")
    if built:
        again = App.openDocument(built)
        Gui.updateGui()
        result["restored"] = sorted(proxy_name(o) for o in again.Objects
                                    if getattr(getattr(o, "Proxy", None), "Type", "").startswith("VarSurf::"))
        result["restored_valid"] = all(o.isValid() for o in again.Objects)
        Gui.ActiveDocument.ActiveView.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        result["shot_restored"] = window_shot(os.path.join(OUT, "subd_restored.png"))
    result["report"] = report_view_text()


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


def main():
    result = {}
    try:
        run(result)
    except Exception:
        result["error"] = traceback.format_exc()
    with open(os.path.join(OUT, "subd.json"), "w") as out:
        json.dump(result, out, indent=1)
    os._exit(0)


QtCore.QTimer.singleShot(0, main)
