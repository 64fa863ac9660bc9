# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run inside the FreeCAD GUI (under Xvfb) by bench/run_bench.py: drags a Point's pin on a 64 x 64
pole Sheet through 10 curves with the 3D view redrawn after every move (the drag preview's grid
drawn each time), and writes as JSON to $VARSURF_BENCH_OUT the moves per second, those of the
move alone, the rate of the redraw alone (the same view, nothing moved) and an empty view's redraw
rate, all in the same process."""

import json
import math
import os
import sys
import time

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
OUT = os.environ.get("VARSURF_BENCH_OUT", "gui_drag.json")


def run():
    import run_bench

    Gui.activateWorkbench("VarSurfWorkbench")
    doc, sheet, pin = run_bench.drag_scene()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.updateGui()
    handles = pin.ViewObject.Proxy.handles
    start = handles.dragger_target()
    moves = 60
    result = {"poles": [sheet.PoleCountU, sheet.PoleCountV]}
    for redraw in (False, True):
        if not handles.begin_drag():
            raise RuntimeError(handles.errors)
        began = time.perf_counter()
        for k in range(moves):
            target = start + App.Vector(0, 0, 10.0 * math.sin(math.pi * k / moves))
            handles.dragger.translation.setValue(*(target / handles.scale))
            handles.drag_to(handles.dragger_target())
            if redraw:
                Gui.updateGui()
                Gui.ActiveDocument.ActiveView.redraw()
        result["redrawn" if redraw else "move_only"] = moves / (time.perf_counter() - began)
        handles.cancel_drag()
    # The renderer's own floor: the same view redrawn with the drag preview shown, nothing moved.
    if not handles.begin_drag():
        raise RuntimeError(handles.errors)
    handles.drag_to(handles.dragger_target())
    began = time.perf_counter()
    for k in range(moves):
        Gui.updateGui()
        Gui.ActiveDocument.ActiveView.redraw()
    result["redraw_only"] = moves / (time.perf_counter() - began)
    handles.cancel_drag()
    # And an empty view's: every object hidden.
    for obj in doc.Objects:
        obj.ViewObject.Visibility = False
    Gui.updateGui()
    began = time.perf_counter()
    for k in range(moves):
        Gui.updateGui()
        Gui.ActiveDocument.ActiveView.redraw()
    result["empty_view"] = moves / (time.perf_counter() - began)
    return result


def main():
    try:
        result = run()
    except Exception as error:  # reported, not hidden
        import traceback

        result = {"error": traceback.format_exc() or str(error)}
    with open(OUT, "w") as handle:
        json.dump(result, handle)
    os._exit(0)


QtCore.QTimer.singleShot(0, main)
