# SPDX-License-Identifier: LGPL-2.1-or-later
"""Render the demo document to a PNG inside the FreeCAD GUI (run by examples/demo.py):

    VARSURF_DEMO_FCSTD=out/demo/demo.FCStd VARSURF_DEMO_PNG=out/demo/demo.png \
        xvfb-run -a -s "-screen 0 1280x1024x24" freecad examples/render_demo.py
"""

import os
import sys
import traceback

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore


def render():
    fcstd = os.environ["VARSURF_DEMO_FCSTD"]
    png = os.environ["VARSURF_DEMO_PNG"]
    doc = App.openDocument(fcstd)
    Gui.activateWorkbench("VarSurfWorkbench")
    import varsurf
    from varsurf.gui.view_providers import ViewProviderPdeSurface, ViewProviderSheet

    for obj in doc.Objects:
        vobj = obj.ViewObject
        if varsurf.is_sheet(obj):
            if getattr(vobj, "Proxy", None) is None:
                ViewProviderSheet(vobj)
            vobj.ShapeColor = (0.30, 0.58, 0.86)
            vobj.LineColor = (0.05, 0.24, 0.40)
            vobj.Transparency = 0
            vobj.Visibility = True
        elif varsurf.is_pde_surface(obj):
            if getattr(vobj, "Proxy", None) is None:
                ViewProviderPdeSurface(vobj)
            vobj.ShapeColor = (0.36, 0.70, 0.45)
            vobj.LineColor = (0.05, 0.30, 0.15)
            vobj.Visibility = True
        elif obj.TypeId == "Part::Feature" and obj.Shape.Edges and not obj.Shape.Faces:  # input curves
            vobj.LineColor = (0.80, 0.15, 0.15) if "Deriv" not in obj.Name else (0.60, 0.20, 0.70)
            vobj.LineWidth = 4.0
            vobj.Visibility = True
        elif obj.TypeId == "Sketcher::SketchObject":
            vobj.LineColor = (0.91, 0.35, 0.05)
            vobj.LineWidth = 4.0
            vobj.PointSize = 6.0
            vobj.Visibility = True
        elif obj.Name == "Surface":  # the base face, faint, for comparison
            vobj.ShapeColor = (0.75, 0.75, 0.75)
            vobj.Transparency = 70
            vobj.Visibility = True
    Gui.Selection.clearSelection()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.updateGui()
    view.saveImage(png, 1200, 900, "White")


def main():
    code = 0
    try:
        render()
    except Exception:
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


QtCore.QTimer.singleShot(0, main)
