# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI smoke test, run inside the real FreeCAD GUI (under Xvfb):

    xvfb-run -a -s "-screen 0 1280x1024x24" freecad tests/gui/smoke_gui.py

Activates the VarSurf workbench, tries the command with a bad selection (nothing may be created),
selects a B-spline face and sketch edges, runs VarSurf_Sheet, recomputes, opens and cancels the
task panel, saves a screenshot and checks that it is not blank. Writes the outcome as JSON to
$VARSURF_GUI_OUT/smoke.json (default: a folder next to this file's repository's out/) and quits.
"""

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
import gui_helpers  # noqa: E402
from gui_helpers import (clipped_widgets, panel_in_view, press_task_button, report_view_text, run_when_up,  # noqa: E402
                         task_widgets)

OUT = os.environ.get("VARSURF_GUI_OUT") or os.path.join(os.getcwd(), "out", "gui-smoke")
os.makedirs(OUT, exist_ok=True)
RESULT = os.path.join(OUT, "smoke.json")


def image_stats(path):
    image = QtGui.QImage(path)
    if image.isNull():
        return {"width": 0, "height": 0, "variance": 0.0, "non_white": 0.0}
    w, h = image.width(), image.height()
    values = []
    non_white = 0
    step = 4
    for y in range(0, h, step):
        for x in range(0, w, step):
            c = QtGui.QColor(image.pixel(x, y))
            gray = 0.299 * c.red() + 0.587 * c.green() + 0.114 * c.blue()
            values.append(gray)
            if gray < 245:
                non_white += 1
    mean = sum(values) / len(values)
    variance = sum((v - mean) ** 2 for v in values) / len(values)
    return {"width": w, "height": h, "variance": variance, "non_white": non_white / len(values)}


def image_difference(a, b):
    """Fraction of sampled pixels that differ (by more than a little) between two pictures."""
    ia, ib = QtGui.QImage(a), QtGui.QImage(b)
    if ia.isNull() or ib.isNull() or ia.size() != ib.size():
        return 1.0
    changed = total = 0
    for y in range(0, ia.height(), 4):
        for x in range(0, ia.width(), 4):
            ca, cb = QtGui.QColor(ia.pixel(x, y)), QtGui.QColor(ib.pixel(x, y))
            total += 1
            if abs(ca.red() - cb.red()) + abs(ca.green() - cb.green()) + abs(ca.blue() - cb.blue()) > 30:
                changed += 1
    return changed / total


def tones(path):
    """Of a picture's pixels that are not white (the background): the fraction that are grey
    (neither near black nor near white). Crisp zebra stripes leave grey only along their edges."""
    image = QtGui.QImage(path)
    grey = dark = 0
    for y in range(0, image.height(), 2):
        for x in range(0, image.width(), 2):
            c = QtGui.QColor(image.pixel(x, y))
            level = 0.299 * c.red() + 0.587 * c.green() + 0.114 * c.blue()
            if level < 40:
                dark += 1
            elif level < 215:
                grey += 1
    return grey / max(1, grey + dark)


def snapshot(name):
    """An isometric, fitted 800 x 600 picture of the active view, nothing selected; its path."""
    Gui.Selection.clearSelection()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.updateGui()
    path = os.path.join(OUT, name)
    view.saveImage(path, 800, 600, "White")
    return path


def window_shot(name):
    """The whole main window as the user sees it, saved as OUT/name; its path."""
    return gui_helpers.window_shot(os.path.join(OUT, name))


def cut_table_cells(form_name, table_name, rows=None):
    """Cells of a table in the open panel whose text does not fit the visible part of their
    column (cut off, elided or only seen by scrolling sideways) and is not whole in the cell's
    tooltip either: (row, column, text). With `rows`, the table is first filled with them as the
    panels fill theirs. (One look-up for all: PySide drops the wrappers of an earlier one.)"""
    from varsurf.gui import table_fit

    found = panel_in_view(form_name)
    if isinstance(found, str):
        return [found]
    table = found[0].findChild(QtGui.QTableWidget, table_name)
    if rows is not None:
        table_fit.fill(table, rows)
        Gui.updateGui()
    viewport = table.viewport().width()
    metrics = table.fontMetrics()
    margin = 2 * (table.style().pixelMetric(QtGui.QStyle.PM_FocusFrameHMargin) + 1)  # Qt's text margins
    out = []
    for row in range(table.rowCount()):
        for column in range(table.columnCount()):
            item = table.item(row, column)
            if table.isColumnHidden(column):  # a measure no row has: cut unless it is one
                if item.text() != table_fit.EMPTY:
                    out.append((row, column, item.text()))
                continue
            rect = table.visualRect(table.model().index(row, column))
            needed = metrics.horizontalAdvance(item.text()) + margin
            cut = rect.x() < 0 or rect.x() + rect.width() > viewport or rect.width() < needed
            if cut and item.toolTip() != item.text():
                out.append((row, column, item.text()))
    return out


def unseen_widgets(form_name, names):
    """Of the named widgets of the open panel, those not wholly inside the task view's visible
    area when it is scrolled to the top (as the panel opens)."""
    found = panel_in_view(form_name)
    if isinstance(found, str):
        return [found]
    form, scroll = found
    scroll.verticalScrollBar().setValue(0)
    Gui.updateGui()
    viewport = scroll.viewport()
    out = []
    for name in names:
        widget = form.findChild(QtGui.QWidget, name)
        if widget is None or widget.mapTo(viewport, QtCore.QPoint(0, widget.height())).y() > viewport.height():
            out.append(name)
    return out


def report_view_lines():
    """The report view's non-empty lines (FreeCAD 0.20 keeps no error/warning kind per line that
    can be read back, so the test judges them by what they say)."""
    return [line.strip() for line in report_view_text().splitlines() if line.strip()]


def toolbars(result):
    """At 1600 px wide no toolbar overflows (no visible extension arrow); the constraint kinds
    sit in one drop-down button per family."""
    import varsurf.gui.commands as commands

    window = Gui.getMainWindow()
    before = window.size()
    window.resize(1600, before.height())
    Gui.updateGui()
    QtCore.QCoreApplication.processEvents()
    result["toolbar_window_width"] = window.width()
    result["toolbars_overflowing"] = sorted(
        bar.windowTitle() for bar in window.findChildren(QtGui.QToolBar)
        if bar.isVisible() and any(b.isVisible() for b in bar.findChildren(QtGui.QToolButton, "qt_toolbar_ext_button")))
    bar = [b for b in window.findChildren(QtGui.QToolBar) if b.windowTitle() == "VarSurf constraints"]
    result["constraint_toolbar_buttons"] = [
        [a.text() for a in (button.menu().actions() if button.menu() is not None else [])]
        for button in (bar[0].findChildren(QtGui.QToolButton) if bar else []) if button.isVisible()
        and button.objectName() != "qt_toolbar_ext_button"]
    result["constraint_groups"] = [list(members) for _name, _menu, _tip, members in commands.CONSTRAINT_GROUPS]
    result["constraint_toolbar_items"] = Gui.activeWorkbench().getToolbarItems().get("VarSurf constraints")
    window_shot("window_toolbars.png")
    window.resize(before)
    Gui.updateGui()


def preferences_dialog(result):
    """Edit > Preferences opens with a VarSurf group (FreeCAD looks its icon up by name, and says
    'Cannot find icon' in its log when it is missing); closed again from a timer (it is modal)."""
    groups = []

    def look():
        for widget in QtGui.QApplication.topLevelWidgets():
            if widget.metaObject().className() == "Gui::Dialog::DlgPreferencesImp" and widget.isVisible():
                for box in widget.findChildren(QtGui.QListWidget):
                    groups.extend(box.item(i).text() for i in range(box.count()))
                widget.reject()

    QtCore.QTimer.singleShot(500, look)
    Gui.runCommand("Std_DlgPreferences")
    result["preference_groups"] = groups


def run(result):
    Gui.activateWorkbench("VarSurfWorkbench")
    result["workbench"] = Gui.activeWorkbench().name()
    result["command_registered"] = "VarSurf_Sheet" in Gui.listCommands()
    toolbars(result)
    constraint_icons(result)
    preferences_dialog(result)

    import varsurf

    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__))))
    sys.path.insert(0, os.path.join(repo, "tests", "python"))
    import scenes

    doc = App.newDocument("Smoke")
    surface = scenes.add_face(doc, scenes.flat_face())  # a bicubic B-spline face, 11 x 11 poles
    rail = scenes.add_line_sketch(doc, "Rail", 14.0, (25.0, 20.0), (75.0, 60.0))
    arc = scenes.add_line_sketch(doc, "Side", 6.0, (60.0, 12.0), (88.0, 34.0))
    doc.recompute()
    Gui.updateGui()

    # 1. a bad selection (edges only): the command is inactive and creates nothing
    count = len(doc.Objects)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, rail.Name, "Edge1")
    result["active_with_edges_only"] = bool(Gui.Command.get("VarSurf_Sheet").isActive())
    Gui.runCommand("VarSurf_Sheet")  # if it runs at all, it must refuse
    Gui.updateGui()
    result["created_on_bad_selection"] = len(doc.Objects) - count

    # 2. the real thing: one face and edges of two sketches
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, surface.Name, "Face1")
    Gui.Selection.addSelection(doc.Name, rail.Name, "Edge1")
    Gui.Selection.addSelection(doc.Name, arc.Name, "Edge1")
    result["selection"] = [
        (s.ObjectName, list(s.SubElementNames)) for s in Gui.Selection.getSelectionEx()
    ]
    result["active_with_face_and_edges"] = bool(Gui.Command.get("VarSurf_Sheet").isActive())
    t0 = time.time()
    Gui.runCommand("VarSurf_Sheet")
    doc.recompute()
    Gui.updateGui()
    result["command_seconds"] = time.time() - t0
    sheets = [o for o in doc.Objects if varsurf.is_sheet(o)]
    result["sheets"] = len(sheets)
    if not sheets:
        result["report_view"] = report_view_text()[-2000:]
        raise RuntimeError("VarSurf_Sheet created no sheet")
    sheet = sheets[0]
    result["sheet_state"] = list(sheet.State)
    result["sheet_valid"] = sheet.isValid() and not sheet.Shape.isNull()
    result["max_deviations"] = list(sheet.MaxDeviations)
    result["tolerance"] = float(sheet.getPropertyByName("Tolerance"))
    result["curve_names"] = list(sheet.CurveNames)
    result["status"] = sheet.Status
    result["base_hidden"] = not surface.ViewObject.Visibility
    result["undo_names"] = list(doc.UndoNames)
    result["children"] = [o.Name for o in sheet.ViewObject.Proxy.claimChildren()]
    # A greyed-out command says why in its tooltip and status tip: one sheet is not a solid.
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, sheet.Name)
    solid_command = Gui.Command.get("VarSurf_Solid")
    result["solid_active_one_sheet"] = bool(solid_command.isActive())
    result["solid_tip_one_sheet"] = [solid_command.getAction()[0].toolTip(), solid_command.getAction()[0].statusTip()]
    Gui.Selection.clearSelection()
    result["icon"] = sheet.ViewObject.Proxy.getIcon()
    property_names(result, doc, sheet)

    # 2b. an error as the user sees it: the Sheet in error, one line in the report view
    sheet.Bend = 0.0  # with Stretch 0 (its default) there is no energy left to minimize
    doc.recompute()
    Gui.updateGui()
    result["error_status"] = sheet.Status
    result["error_valid"] = sheet.isValid()
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.Selection.addSelection(doc.Name, sheet.Name)  # its properties, Status in error, shown
    result["error_window"] = window_shot("window_error.png")
    Gui.Selection.clearSelection()
    sheet.Bend = 1.0
    doc.recompute()
    Gui.updateGui()
    result["repaired_status"] = sheet.Status

    # 3. the task panel: opens, shows the results, Cancel restores the values
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.ActiveDocument.setEdit(sheet.Name, 0)
    Gui.updateGui()
    result["task_panel_open"] = bool(Gui.Control.activeDialog())
    bend_before = sheet.Bend
    widgets = task_widgets()
    table_rows = widgets["deviationTable"].rowCount()
    widgets["bendSpin"].setValue(5.0)
    widgets["updateButton"].click()  # preview with the new value
    Gui.updateGui()
    result["task_panel_rows"] = table_rows
    result["task_panel_clipped"] = clipped_widgets("VarSurfSheet")
    result["deviation_cells_cut"] = cut_table_cells("VarSurfSheet", "deviationTable")
    result["task_panel_results_unseen"] = unseen_widgets(
        "VarSurfSheet", ("polesValue", "statusValue", "deviationTable"))
    result["task_panel_image"] = window_shot("task_panel.png")  # the whole window, panel included
    result["bend_during_edit"] = sheet.Bend
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["bend_after_cancel"] = sheet.Bend
    result["bend_restored"] = sheet.Bend == bend_before
    result["task_panel_closed"] = not Gui.Control.activeDialog()

    # 4. a constraint command in the real GUI: a Normal on the selected sheet
    import varsurf.gui.commands as commands

    result["constraint_commands"] = [c for c in commands.CONSTRAINTS if c in Gui.listCommands()]
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, sheet.Name)
    result["normal_active"] = bool(Gui.Command.get("VarSurf_Normal").isActive())
    Gui.runCommand("VarSurf_Normal")
    doc.recompute()
    result["constraint_kinds"] = [c.Kind for c in sheet.Constraints]
    result["constraint_residuals"] = list(sheet.ConstraintResiduals)
    result["sheet_valid_with_constraint"] = sheet.isValid()
    constraint = sheet.Constraints[0] if sheet.Constraints else None
    result["constraints_before_commands"] = len(sheet.Constraints)
    result["constraint_in_tree"] = constraint is not None and constraint in sheet.ViewObject.Proxy.claimChildren()
    result["constraint_icon"] = constraint.ViewObject.Proxy.getIcon() if constraint is not None else ""

    # 4b. drag a Point's pin in the view: live re-solves, then one undoable step
    import varsurf

    face = sheet.Shape.Faces[0]
    u0, u1, v0, v1 = face.ParameterRange
    start = face.valueAt(u0 + 0.6 * (u1 - u0), v0 + 0.5 * (v1 - v0))
    pin = varsurf.make_constraint(sheet, "Point", uv=(0.6, 0.5), origin=start, name="Pin")
    doc.recompute()
    handles = pin.ViewObject.Proxy.handles
    result["pin_has_dragger"] = handles.dragger is not None
    area_before = sheet.Shape.Area
    before = snapshot("drag_before.png")
    result["drag_began"] = handles.begin_drag()
    moves = 30
    t0 = time.perf_counter()
    for k in range(1, moves + 1):
        target = start + App.Vector(0, 0, 10.0 * k / moves)
        handles.dragger.translation.setValue(*(target / handles.scale))  # as the pointer would
        handles.drag_to(handles.dragger_target())
        Gui.updateGui()  # redraw: the sheet is tessellated again each move
    result["drag_moves_per_second"] = moves / (time.perf_counter() - t0)
    preview = handles.preview.points
    result["preview_through_pin"] = min(
        ((p[0] - target.x) ** 2 + (p[1] - target.y) ** 2 + (p[2] - target.z) ** 2) ** 0.5 for p in preview.tolist())
    result["preview_top"] = float(preview[:, 2].max())
    result["sheet_top_before"] = sheet.Shape.BoundBox.ZMax
    during = snapshot("drag_during.png")
    result["drag_image_change"] = image_difference(before, during)
    result["drag_image_stats"] = image_stats(during)
    handles.end_drag(handles.dragger_target())
    result["drag_errors"] = list(handles.errors)
    result["pin_origin_after"] = list(pin.Origin)
    result["drag_target"] = list(start + App.Vector(0, 0, 10.0))
    result["sheet_valid_after_drag"] = sheet.isValid()
    result["undo_after_drag"] = list(doc.UndoNames[:1])
    doc.undo()
    doc.recompute()
    result["area_before_drag"] = area_before
    result["area_after_undo"] = sheet.Shape.Area
    result["pin_origin_after_undo"] = list(pin.Origin)
    result["pin_start"] = list(start)

    # 4b'. the Pin's own panel: fields follow the kind, Update previews, Cancel restores
    Gui.ActiveDocument.setEdit(pin.Name, 0)
    Gui.updateGui()
    widgets = task_widgets("VarSurfConstraint")
    result["pin_panel_fields"] = {name: widgets[name].isEnabled()
                                  for name in ("uSpin", "originZ", "regionU0Spin", "angleSpin")}
    result["pin_panel_residual"] = widgets["residualValue"].text()
    origin_before = list(pin.Origin)
    widgets["originZ"].setValue(pin.Origin.z + 3.0)
    widgets["updateButton"].click()
    Gui.updateGui()
    result["pin_panel_preview"] = [pin.Origin.z - origin_before[2], sheet.isValid()]
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["pin_panel_restored"] = list(pin.Origin) == origin_before and sheet.isValid()
    result["pin_panel_image_stats"] = image_stats(snapshot("pin_panel.png"))
    Gui.ActiveDocument.setEdit(pin.Name, 0)
    Gui.updateGui()
    widgets = task_widgets("VarSurfConstraint")
    widgets["weightSpin"].setValue(2.0)
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["pin_panel_ok"] = [pin.Weight, list(pin.Origin) == origin_before, sheet.isValid(), doc.UndoNames[:1]]

    # 4c. color maps through the command (macro lines), and the L-curve plot
    from varsurf.gui import color_legend

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, sheet.Name)
    result["color_map_active"] = bool(Gui.Command.get("VarSurf_ColorMap").isActive())
    plain = snapshot("map_none.png")
    maps = {}
    for expected in ("Deviation", "CurveDeviation", "MeanCurvature", "GaussianCurvature", "Zebra"):
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(doc.Name, sheet.Name)
        Gui.runCommand("VarSurf_ColorMap")
        picture = snapshot(f"map_{expected}.png")
        overlay = sheet.ViewObject.Proxy.overlay
        maps[expected] = {
            "mode": sheet.ViewObject.Analysis,
            "range": sheet.ViewObject.AnalysisRange,
            "cells": len(overlay.grid.triangles) if overlay.grid is not None else 0,
            "curves": len(overlay.curves) if overlay.curves is not None else 0,
            "change": image_difference(plain, picture),
            "legend": list(color_legend.legend_texts(overlay.legend)) if overlay.legend is not None else [],
            "tones": tones(picture),
        }
        if expected in ("Deviation", "Zebra"):  # the whole window: the map with its legend, zebra
            window_shot(f"window_{expected.lower()}.png")
    result["color_maps"] = maps
    # zebra stripes follow their view properties: fewer stripes, another direction
    sheet.ViewObject.ZebraStripes = 4
    sheet.ViewObject.ZebraDirection = App.Vector(1, 0, 0)
    result["zebra_adjusted"] = [sheet.ViewObject.AnalysisRange, sheet.ViewObject.Proxy.overlay.grid.stripes,
                                image_difference(os.path.join(OUT, "map_Zebra.png"), snapshot("map_Zebra_4x.png"))]
    # a scale typed by the user replaces the data's range, in the map and its legend
    sheet.ViewObject.Analysis = "Deviation"
    sheet.ViewObject.AnalysisScale = 20.0
    overlay = sheet.ViewObject.Proxy.overlay
    result["scaled_legend"] = [sheet.ViewObject.AnalysisRange, list(color_legend.legend_texts(overlay.legend))]
    sheet.ViewObject.AnalysisScale = 0.0
    sheet.ViewObject.Analysis = "None"
    result["overlay_cleared"] = sheet.ViewObject.Proxy.overlay.root.getNumChildren() == 0
    sheet.SolveMode = "TSVD"
    doc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, sheet.Name)
    result["lcurve_active"] = bool(Gui.Command.get("VarSurf_LCurve").isActive())
    Gui.runCommand("VarSurf_LCurve")
    import tempfile

    lcurve = os.path.join(tempfile.gettempdir(), f"varsurf-lcurve-{doc.Name}-{sheet.Name}.png")
    result["lcurve_image_stats"] = image_stats(lcurve)
    if os.path.isfile(lcurve):
        import shutil

        shutil.copy(lcurve, os.path.join(OUT, "lcurve.png"))
    sheet.SolveMode = "Automatic"
    doc.recompute()

    # 4d. the preferences page loads in FreeCAD's own loader, its widgets bound to parameters
    from varsurf.gui import resources

    page = Gui.PySideUic.loadUi(resources.ui("preferences.ui"))
    entries = {}
    for kind, name in ((QtGui.QSpinBox, "degreeSpin"), (QtGui.QSpinBox, "minSpansSpin"),
                       (QtGui.QDoubleSpinBox, "bendSpin"), (QtGui.QDoubleSpinBox, "toleranceSpin"),
                       (QtGui.QComboBox, "solveModeCombo"), (QtGui.QDoubleSpinBox, "timeLimitSpin"),
                       (QtGui.QSpinBox, "memoryLimitSpin")):
        widget = page.findChild(kind, name)
        entries[name] = bytes(widget.property("prefEntry")).decode() if widget is not None else None
    result["preference_entries"] = entries
    tolerance = page.findChild(QtGui.QDoubleSpinBox, "toleranceSpin")
    result["preference_tolerance"] = [tolerance.value(), tolerance.text()]
    result["preference_modes"] = [page.findChild(QtGui.QComboBox, "solveModeCombo").itemText(i)
                                  for i in range(page.findChild(QtGui.QComboBox, "solveModeCombo").count())]

    # 4e. the sheet's panel again: space, solve mode and rest shape; constraints listed; OK commits
    Gui.ActiveDocument.setEdit(sheet.Name, 0)
    Gui.updateGui()
    widgets = task_widgets()
    result["panel_rows_with_constraints"] = [widgets["deviationTable"].item(r, 0).text()
                                             for r in range(widgets["deviationTable"].rowCount())]
    widgets["installButton"].click()  # install, then cancel: nothing kept
    Gui.updateGui()
    result["rest_during_edit"] = sheet.RestShape
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["rest_after_cancel"] = sheet.RestShape
    result["installed_after_cancel"] = not sheet.InstalledRest.isNull()
    Gui.ActiveDocument.setEdit(sheet.Name, 0)
    Gui.updateGui()
    widgets = task_widgets()
    widgets["degreeSpin"].setValue(4)
    widgets["solveModeCombo"].setCurrentText("Exact")
    widgets["refinementCombo"].setCurrentText("Local")
    widgets["updateButton"].click()
    Gui.updateGui()
    result["panel_local"] = [sheet.Refinement, widgets["polesValue"].text()]
    press_task_button(QtGui.QDialogButtonBox.Ok)
    result["panel_ok"] = [sheet.Degree, sheet.DegreeU, sheet.SolveMode, sheet.isValid(), doc.UndoNames[:1]]
    sheet.Refinement = "Uniform"
    doc.recompute()

    # 4e'. rest shape commands: install, then melt; each one undoable step with macro lines
    rest = {}
    for name in ("VarSurf_InstallRest", "VarSurf_Melt"):
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(doc.Name, sheet.Name)
        active = bool(Gui.Command.get(name).isActive())
        Gui.runCommand(name)
        rest[name] = [active, sheet.RestShape, doc.UndoNames[:1], sheet.isValid()]
    result["rest_commands"] = rest

    # 4f. FreeCAD's progress indicator during a solve (shown at once here: no delay)
    from varsurf.app import progress

    shown = []

    class Watch(progress.SolveProgress):
        def __call__(self):
            going = super().__call__()
            if self.indicator is not None:
                shown.append(self.asked)
            return going

    saved = progress.factory, progress.DELAY, progress.INTERVAL
    progress.factory, progress.DELAY, progress.INTERVAL = Watch, 0.0, 0.0
    try:
        sheet.SolveMode = "Penalty"
        doc.recompute()
    finally:
        progress.factory, progress.DELAY, progress.INTERVAL = saved
    result["progress_shown"] = len(shown)
    result["sheet_valid_with_progress"] = sheet.isValid()
    sheet.SolveMode = "Exact"
    doc.recompute()

    # 5. picture
    image = snapshot("smoke.png")
    result["image"] = image
    result["image_stats"] = image_stats(image)

    path = os.path.join(OUT, "smoke.FCStd")
    doc.saveAs(path)
    result["saved"] = os.path.isfile(path)
    cdoc = App.newDocument("Commands")
    csurface = scenes.add_face(cdoc, scenes.flat_face())
    crail = scenes.add_line_sketch(cdoc, "Rail", 5.0, (20.0, 15.0), (40.0, 20.0))
    cdoc.recompute()
    csheet = varsurf.make_sheet((csurface, "Face1"), [(crail, "Edge1")])
    cdoc.recompute()
    every_constraint_command(result, cdoc, csheet, csurface, crail)
    # local refinement shown on the sheet: the refined spans outlined by level
    csheet.Refinement, csheet.MinSpans, csheet.Tolerance = "Local", 2, 1e-3
    cdoc.recompute()
    for o in cdoc.Objects:  # the sheet alone in the picture
        if o.ViewObject is not None and o is not csheet:
            o.ViewObject.Visibility = False
    plain = snapshot("refinement_off.png")
    csheet.ViewObject.ShowRefinement = True
    shown = snapshot("refinement.png")
    result["refinement_view"] = [csheet.isValid(), csheet.RefinementDepth, csheet.ViewObject.Proxy.refinement.count,
                                 len(csheet.RefinedSpans) // 5, image_difference(plain, shown)]

    # 6. the Solid command on two selected Sheets (the pillow example's, built without it)
    sys.path.insert(0, os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__)))), "examples"))
    import pillow

    pdoc = App.newDocument("PillowSmoke")
    pillow.build(pdoc)
    pdoc.removeObject("Pillow")  # the example's own Solid: make it again through the command
    pdoc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(pdoc.Name, "Top")
    Gui.Selection.addSelection(pdoc.Name, "Bottom")
    result["solid_active"] = bool(Gui.Command.get("VarSurf_Solid").isActive())
    Gui.runCommand("VarSurf_Solid")
    pdoc.recompute()
    solids = [o for o in pdoc.Objects if getattr(getattr(o, "Proxy", None), "Type", "") == "VarSurf::Solid"]
    result["solids"] = len(solids)
    if solids:
        solid = solids[0]
        result["solid_closed"] = bool(solid.Closed) and solid.isValid()
        result["solid_icon"] = solid.ViewObject.Proxy.getIcon()
        result["solid_children"] = [o.Name for o in solid.ViewObject.Proxy.claimChildren()]
        result["sheets_hidden"] = not pdoc.getObject("Top").ViewObject.Visibility
    result["solid_image_stats"] = image_stats(snapshot("solid.png"))
    if solids:  # the Solid's panel: its joins listed; a tolerance edited, then cancelled
        Gui.ActiveDocument.setEdit(solid.Name, 0)
        Gui.updateGui()
        widgets = task_widgets("VarSurfSolid")
        result["solid_panel_seams"] = [widgets["seamTable"].item(r, 0).text()
                                       for r in range(widgets["seamTable"].rowCount())]
        tolerance = float(solid.Tolerance)
        widgets["toleranceSpin"].setValue(tolerance * 2)
        widgets["updateButton"].click()
        Gui.updateGui()
        result["solid_panel_preview"] = float(solid.Tolerance) / tolerance
        # (last: it looks the panel up among all widgets, after which PySide drops the ones above)
        result["solid_cells_cut"] = cut_table_cells("VarSurfSolid", "seamTable")
        press_task_button(QtGui.QDialogButtonBox.Cancel)
        result["solid_panel_restored"] = float(solid.Tolerance) == tolerance and solid.isValid()

    # 6b. a FillHole (the crowned lid example): its icon and child, its panel's joins; a tolerance
    # previewed with Update, then cancelled
    import crowned_lid

    ldoc = App.newDocument("LidSmoke")
    lid = crowned_lid.build(ldoc)
    result["fill_hole_icon"] = lid.ViewObject.Proxy.getIcon()
    result["fill_hole_children"] = [o.Name for o in lid.ViewObject.Proxy.claimChildren()]
    Gui.ActiveDocument.setEdit(lid.Name, 0)
    Gui.updateGui()
    widgets = task_widgets("VarSurfFillHole")
    table = widgets["joinTable"]
    result["fill_hole_panel_rows"] = [[table.item(r, c).text() for c in range(table.columnCount())]
                                      for r in range(table.rowCount())]
    result["fill_hole_panel_continuity"] = widgets["continuityCombo"].currentText()
    tolerance = float(lid.Tolerance)
    widgets["toleranceSpin"].setValue(tolerance * 2)
    widgets["updateButton"].click()
    Gui.updateGui()
    result["fill_hole_panel_preview"] = [float(lid.Tolerance) / tolerance, lid.isValid()]
    result["fill_hole_image_stats"] = image_stats(snapshot("fill_hole.png"))
    result["fill_hole_cells_cut"] = cut_table_cells("VarSurfFillHole", "joinTable")
    # A G2 fill's three measures a join (the lid's walls admit only G0): the figures of a 5-sided
    # hole's G2 joins (benchmark 7), through the panel's own table filling
    result["fill_hole_g2_cells_cut"] = cut_table_cells(
        "VarSurfFillHole", "joinTable", [(f"hole edge {k + 1}", "4.6e-05", "0.00597", "0.334") for k in range(5)])
    result["fill_hole_window"] = window_shot("window_fill_hole.png")
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["fill_hole_panel_restored"] = float(lid.Tolerance) == tolerance and lid.isValid()

    # 6c. the Tube command on the duct example's sections: a sketch and a circle picked whole, the
    # bulge by its edge; a picture of the view and of the whole window
    import duct

    tdoc = App.newDocument("TubeSmoke")
    duct.rounded_rectangle(tdoc, "Port", 60.0, 30.0, 6.0)
    round_port = tdoc.addObject("Part::Circle", "Round")
    round_port.Radius = 12.0
    round_port.Placement.Base = App.Vector(0, 0, 50)
    duct.bulge(tdoc)
    tdoc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(tdoc.Name, "Port")
    result["tube_active_one_section"] = bool(Gui.Command.get("VarSurf_Tube").isActive())
    Gui.Selection.addSelection(tdoc.Name, "Round")
    Gui.Selection.addSelection(tdoc.Name, "Bulge", "Edge1")
    result["tube_active"] = bool(Gui.Command.get("VarSurf_Tube").isActive())
    Gui.runCommand("VarSurf_Tube")
    tdoc.recompute()
    tubes = [o for o in tdoc.Objects if o.Name.startswith("Tube") and "Sections" not in o.PropertiesList]
    result["tube"] = [[o.Name, o.isValid(), o.Status] for o in tubes]
    result["tube_base"] = tubes[0].Base[0].Proxy.Type if tubes and tubes[0].Base else ""
    result["tube_image_stats"] = image_stats(snapshot("tube.png"))
    window_shot("tube_window.png")

    # 7. the Hinge and SpaceCurve commands on the hinge-pair example (built without its hinge)
    import hinge_pair

    hdoc = App.newDocument("HingeSmoke")
    hsolid = hinge_pair.build(hdoc, 180.0)
    for h in list(hsolid.Hinges):
        hsolid.Hinges = []
        hdoc.removeObject(h.Name)
    hdoc.recompute()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(hdoc.Name, "Left")
    Gui.Selection.addSelection(hdoc.Name, "Right")
    Gui.Selection.addSelection(hdoc.Name, "Seam", "Edge1")
    result["hinge_active"] = bool(Gui.Command.get("VarSurf_Hinge").isActive())
    Gui.runCommand("VarSurf_Hinge")
    hdoc.recompute()
    result["hinges"] = [h.Name for h in hsolid.Hinges]
    result["hinge_errors"] = list(hsolid.HingeErrors)
    result["hinge_icon"] = hsolid.Hinges[0].ViewObject.Proxy.getIcon() if hsolid.Hinges else ""
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(hdoc.Name, "Seam", "Edge1")
    result["space_curve_active"] = bool(Gui.Command.get("VarSurf_SpaceCurve").isActive())
    Gui.runCommand("VarSurf_SpaceCurve")
    curves = [o for o in hdoc.Objects if o.Name.startswith("SpaceCurve")]
    result["space_curve_ok"] = len(curves) == 1 and curves[0].isValid()
    result["space_curve_icon"] = curves[0].ViewObject.Proxy.getIcon() if curves else ""
    # a PDE surface between two sketch-like edges and their derivative curves, by its command
    for name, x, z in (("PdeU0", 0.0, 0.0), ("PdeU1", 60.0, 10.0), ("PdeD0", 15.0, 20.0), ("PdeD1", 75.0, 10.0)):
        edge = hdoc.addObject("Part::Feature", name)
        edge.Shape = Part.LineSegment(App.Vector(x, 100, z), App.Vector(x, 160, z)).toShape()
    hdoc.recompute()
    Gui.Selection.clearSelection()
    for name in ("PdeU0", "PdeU1", "PdeD0", "PdeD1"):
        Gui.Selection.addSelection(hdoc.Name, name, "Edge1")
    result["pde_active"] = bool(Gui.Command.get("VarSurf_PdeSurface").isActive())
    Gui.runCommand("VarSurf_PdeSurface")
    pdes = [o for o in hdoc.Objects if o.Name.startswith("PdeSurface")]
    result["pde_ok"] = [len(pdes) == 1 and pdes[0].isValid(), pdes[0].Kind if pdes else "",
                        hdoc.UndoNames[:1]]
    result["pde_icon"] = pdes[0].ViewObject.Proxy.getIcon() if pdes else ""
    result["hinge_image_stats"] = image_stats(snapshot("hinge.png"))
    # the Hinge's panel: a new angle, OK, one undoable step
    hinge = hsolid.Hinges[0]
    Gui.ActiveDocument.setEdit(hinge.Name, 0)
    Gui.updateGui()
    widgets = task_widgets("VarSurfHinge")
    result["hinge_panel_reached"] = widgets["reachedValue"].text()
    widgets["angleSpin"].setValue(90.0)
    widgets["updateButton"].click()
    Gui.updateGui()
    result["hinge_preview_angle"] = float(hinge.Angle.Value if hasattr(hinge.Angle, "Value") else hinge.Angle)
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    result["hinge_after_cancel"] = [float(hinge.Angle.Value if hasattr(hinge.Angle, "Value") else hinge.Angle),
                                    hsolid.isValid()]
    Gui.ActiveDocument.setEdit(hinge.Name, 0)
    Gui.updateGui()
    widgets = task_widgets("VarSurfHinge")
    widgets["angleSpin"].setValue(150.0)
    press_task_button(QtGui.QDialogButtonBox.Ok)
    # the pair's side curves open at 180 degrees: 150 contradicts them, and the Solid says so
    result["hinge_panel_ok"] = [float(hinge.Angle.Value if hasattr(hinge.Angle, "Value") else hinge.Angle),
                                hsolid.isValid(), hsolid.Status, hdoc.UndoNames[:1]]
    hdoc.undo()
    hdoc.recompute()
    result["hinge_after_undo"] = [float(hinge.Angle.Value if hasattr(hinge.Angle, "Value") else hinge.Angle),
                                  hsolid.isValid()]


def every_constraint_command(result, doc, sheet, surface, rail):
    """Each constraint command on a selection prepared for its kind: active, creates one
    constraint of that kind in one undoable step (undone again)."""
    import varsurf.gui.commands as commands
    from varsurf.solve import constraints

    vertex = doc.addObject("Part::Vertex", "PickedPoint")
    face = sheet.Shape.Faces[0]
    u0, u1, v0, v1 = face.ParameterRange
    p = face.valueAt(0.5 * (u0 + u1), 0.3 * (v0 + v1))
    vertex.X, vertex.Y, vertex.Z = p.x, p.y, p.z
    doc.recompute()
    outcome = {}
    result["constraints_before_every_command"] = len(sheet.Constraints)
    for name, kind, _menu, _tip in commands.CONSTRAINT_COMMANDS:
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(doc.Name, sheet.Name)
        if kind == "Point":
            Gui.Selection.addSelection(doc.Name, vertex.Name, "Vertex1")
        if kind in constraints.CURVE_KINDS or kind in ("G0", "CurveAttractor", "CurveMap"):
            Gui.Selection.addSelection(doc.Name, rail.Name, "Edge1")
        if kind == "CurveMap":  # the destination, picked after the source
            Gui.Selection.addSelection(doc.Name, surface.Name, "Edge1")
        if kind in ("G1", "G2", "SurfaceAttractor", "RegionMap"):
            Gui.Selection.addSelection(doc.Name, surface.Name, "Face1")
        active = bool(Gui.Command.get(name).isActive())
        began = time.perf_counter()
        before = list(sheet.Constraints)
        Gui.runCommand(name)
        Gui.updateGui()
        added = [c for c in sheet.Constraints if c not in before]
        outcome[kind] = [active, [c.Kind for c in added], list(doc.UndoNames[:1])]
        if added:
            doc.undo()
            doc.recompute()
        result.setdefault("constraint_command_seconds", {})[kind] = time.perf_counter() - began
    result["every_constraint_command"] = outcome
    result["constraints_after_undos"] = len(sheet.Constraints)  # each command undone again
    # a G0 join's measured continuity is listed in the Sheet's panel (then removed again)
    import varsurf

    join = varsurf.make_constraint(sheet, "G0", curve=(rail, "Edge1"), name="Join")
    doc.recompute()
    Gui.ActiveDocument.setEdit(sheet.Name, 0)
    Gui.updateGui()
    table = task_widgets()["deviationTable"]
    rows = [[table.item(r, c).text() for c in range(2)] for r in range(table.rowCount())]
    result["g0_panel"] = [sheet.isValid(), list(sheet.JoinNames), [r for r in rows if r[0].endswith(": join")]]
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    sheet.Constraints = [c for c in sheet.Constraints if c != join]
    doc.removeObject(join.Name)
    doc.recompute()
    # an attractor's origin is a pin too: dragged, the sheet follows; one undo step
    pull = varsurf.make_constraint(sheet, "PointAttractor", origin=(50.0, 40.0, 20.0),
                                   region=(0.3, 0.7, 0.3, 0.7), name="Pull")
    doc.recompute()
    handles = pull.ViewObject.Proxy.handles
    top = sheet.Shape.BoundBox.ZMax
    began = handles.begin_origin_drag() if handles.dragger is not None else False
    for z in (24.0, 28.0, 32.0):
        handles.dragger.translation.setValue(*(App.Vector(50.0, 40.0, z) / handles.scale))
        handles.drag_to(handles.dragger_target())
        Gui.updateGui()
    handles.end_drag(handles.dragger_target())
    result["origin_drag"] = [began, round(pull.Origin.z, 3), sheet.Shape.BoundBox.ZMax - top,
                             doc.UndoNames[:1], list(handles.errors)]
    result["constraint_icons"] = {name: Gui.Command.get(name).getInfo().get("pixmap", "")
                                  for name, *_rest in commands.CONSTRAINT_COMMANDS}
    window_shot("toolbars.png")


def _icon_pixels(icon, size, mode):
    """(red, green, blue, alpha) rows of ``icon`` drawn at size x size in QIcon ``mode``."""
    image = icon.pixmap(size, size, mode).toImage().convertToFormat(QtGui.QImage.Format_ARGB32)
    return [[QtGui.QColor.fromRgba(image.pixel(x, y)).getRgb() for x in range(image.width())]
            for y in range(image.height())]


def _saturation(pixels):
    """Mean HSV saturation (0..1) of the pixels that are not transparent."""
    seen = [p for row in pixels for p in row if p[3] > 64]
    return sum((max(p[:3]) - min(p[:3])) / max(1, max(p[:3])) for p in seen) / max(1, len(seen))


def _difference(a, b):
    """Mean per-pixel colour difference (0..1, alpha-weighted over white) of two renders."""
    def on_white(p):
        a = p[3] / 255.0
        return [a * c + (1 - a) * 255 for c in p[:3]]

    total = count = 0
    for row_a, row_b in zip(a, b):
        for pa, pb in zip(row_a, row_b):
            total += sum(abs(x - y) for x, y in zip(on_white(pa), on_white(pb))) / 765.0
            count += 1
    return total / max(1, count)


def constraint_icons(result):
    """Each constraint kind's icon at the toolbars' icon size: it covers its square (no speck),
    differs from every other kind's, and greys out when its command is disabled (as FreeCAD's own
    icons do); a contact sheet of them (normal row above, disabled row below, 4x) is saved."""
    import varsurf.gui.commands as commands

    window = Gui.getMainWindow()
    bars = [b for b in window.findChildren(QtGui.QToolBar) if b.windowTitle() == "VarSurf constraints"]
    size = (bars[0].iconSize() if bars else window.iconSize()).width()
    icons = {kind: QtGui.QIcon(Gui.Command.get(name).getInfo()["pixmap"])
             for name, kind, _menu, _tip in commands.CONSTRAINT_COMMANDS}
    normal = {k: _icon_pixels(i, size, QtGui.QIcon.Normal) for k, i in icons.items()}
    disabled = {k: _icon_pixels(i, size, QtGui.QIcon.Disabled) for k, i in icons.items()}
    kinds = list(icons)
    result["icon_size"] = size
    result["icon_coverage"] = {k: sum(p[3] > 64 for row in px for p in row) / float(size * size)
                               for k, px in normal.items()}
    pairs = [(_difference(normal[a], normal[b]), a, b) for i, a in enumerate(kinds) for b in kinds[i + 1:]]
    result["icon_closest_pair"] = list(min(pairs))
    result["icon_saturation"] = {k: [_saturation(normal[k]), _saturation(disabled[k])] for k in kinds}
    scale = 4
    sheet = QtGui.QImage(len(kinds) * (size + 4) * scale, 2 * (size + 4) * scale, QtGui.QImage.Format_ARGB32)
    sheet.fill(QtGui.QColor("white"))
    painter = QtGui.QPainter(sheet)
    for column, kind in enumerate(kinds):
        for row, mode in enumerate((QtGui.QIcon.Normal, QtGui.QIcon.Disabled)):
            picture = icons[kind].pixmap(size, size, mode).scaled(size * scale, size * scale)
            painter.drawPixmap(column * (size + 4) * scale, row * (size + 4) * scale, picture)
    painter.end()
    sheet.save(os.path.join(OUT, "constraint_icons.png"))


def property_names(result, doc, sheet):
    """With a Sheet selected, the property editor (Combo view, FreeCAD's default width) shows
    every property name whole: the names the name column cuts short."""
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, sheet.Name)
    end = time.time() + 1.0  # FreeCAD fills the editor from a timer after the selection
    while time.time() < end:
        QtCore.QCoreApplication.processEvents()
        time.sleep(0.02)
    window = Gui.getMainWindow()
    editors = [e for e in window.findChildren(QtGui.QTreeView)
               if e.metaObject().className() == "Gui::PropertyEditor::PropertyEditor" and e.isVisible()]
    result["property_editor"] = [[e.viewport().width(), e.columnWidth(0), e.header().length()] for e in editors]
    cut, names = [], 0
    for editor in editors:
        model, metrics = editor.model(), editor.fontMetrics()
        root = QtCore.QModelIndex()
        for group in range(model.rowCount(root)):
            parent = model.index(group, 0, root)
            editor.expand(parent)
            for row in range(model.rowCount(parent)):
                index = model.index(row, 0, parent)
                text = str(model.data(index))
                names += 1
                # the text starts a few pixels into its cell, after the group's indentation
                if editor.indentation() + metrics.horizontalAdvance(text) + 6 > editor.columnWidth(0):
                    cut.append(text)
    result["property_names_shown"] = names
    result["property_names_cut"] = cut
    window_shot("window_properties.png")
    Gui.Selection.clearSelection()


def drag_space_curve(result):
    """8. Welch & Witkin Figure 2 in the view: drag the middle handle of the moving-curve example's
    SpaceCurve; the curve and both joined sheets follow, one undo puts them back."""
    import moving_curve

    mdoc = App.newDocument("MovingSmoke")
    solid, curve = moving_curve.build(mdoc)
    Gui.updateGui()
    handles = curve.ViewObject.Proxy.handles
    result["curve_pins"] = [len(handles.draggers), len(curve.Handles)]
    volume = solid.Shape.Volume
    before = snapshot("curve_before.png")
    result["curve_drag_began"] = handles.begin_drag(1)
    start = handles.handle_position(1)
    moves = 12
    t0 = time.perf_counter()
    k = 0
    # A pointer moving at 30 events a second for 12 events, and on (ending where it is) while a
    # slow machine has not yet followed twice: what a user holding the mouse would see.
    while k < moves or (handles.session.live_solves < 2 and time.perf_counter() - t0 < 20.0):
        k += 1
        time.sleep(1.0 / 30.0)
        target = start + App.Vector(0, 0, 8.0 * min(k, moves) / moves)
        handles.draggers[1].translation.setValue(*(target / handles.scale))
        handles.drag_to(handles.handle_position(1))
        Gui.updateGui()
    moves = k
    result["curve_moves_per_second"] = moves / (time.perf_counter() - t0)
    result["curve_live_solves"] = handles.session.live_solves
    during = snapshot("curve_during.png")
    result["curve_image_change"] = image_difference(before, during)
    handles.end_drag(handles.handle_position(1))
    snapshot("curve_after.png")
    result["curve_drag_errors"] = list(handles.errors)
    result["curve_solid"] = [solid.isValid(), bool(solid.Closed), solid.Shape.Volume - volume]
    result["curve_undo_name"] = mdoc.UndoNames[:1]
    mdoc.undo()
    mdoc.recompute()
    result["curve_volume_after_undo"] = abs(solid.Shape.Volume - volume) / volume


#: Builds a document as `freecadcmd` or a test does (no GUI, so no view providers): the pillow
#: example (two sheets on flat helper faces, a rim, a Solid) and a sheet on a Part Box's top face
#: along an arc. Formatted with the examples folder and the file to write.
HEADLESS_SCRIPT = """
import sys
sys.path.append("/usr/lib/freecad-python3/lib")
import FreeCAD
import Part
sys.path.insert(0, {examples!r})
import pillow
import varsurf
doc = FreeCAD.newDocument("Headless")
pillow.build(doc)
box = doc.addObject("Part::Box", "Box")
box.Length, box.Width, box.Height = 60, 40, 20
box.Placement.Base = FreeCAD.Vector(100, 0, 0)
arc = doc.addObject("Part::Feature", "Arc")
arc.Shape = Part.Arc(FreeCAD.Vector(100, 20, 20), FreeCAD.Vector(130, 20, 26),
                     FreeCAD.Vector(160, 20, 20)).toShape()
doc.recompute()
top = next(i for i, f in enumerate(box.Shape.Faces) if abs(f.CenterOfMass.z - 20) < 1e-9)
varsurf.make_sheet((box, "Face%d" % (top + 1)), [(arc, "Edge1")], name="Lid")
rim0 = doc.addObject("Part::Feature", "Rim0")
rim0.Shape = Part.LineSegment(FreeCAD.Vector(0, 80, 0), FreeCAD.Vector(0, 140, 0)).toShape()
rim1 = doc.addObject("Part::Feature", "Rim1")
rim1.Shape = Part.LineSegment(FreeCAD.Vector(50, 80, 10), FreeCAD.Vector(50, 140, 10)).toShape()
doc.recompute()
varsurf.make_pde_surface((rim0, "Edge1"), (rim1, "Edge1"), a=2.0, name="Pde")
doc.recompute()
doc.saveAs({path!r})
"""


def _roots(vobj, name):
    """How many Coin roots called `name` hang under the view provider's root."""
    root = vobj.RootNode
    return sum(1 for i in range(root.getNumChildren()) if root.getChild(i).getName().getString() == name)


def headless_document(result, saved):
    """A document built without the GUI, opened in it: every VarSurf object has its view provider
    (icon, double click opens its panel), what a sheet replaces is hidden and nothing else; and a
    document saved with the GUI opens with one of each of its overlays."""
    import subprocess

    import varsurf

    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(varsurf.__file__))))
    path = os.path.join(OUT, "headless.FCStd")
    script = HEADLESS_SCRIPT.format(examples=os.path.join(repo, "examples"), path=path)
    run = subprocess.run(["/usr/bin/python3", "-c", script], capture_output=True, text=True, timeout=240)
    result["headless_build"] = [run.returncode, run.stderr[-2000:]]
    doc = App.openDocument(path)
    Gui.updateGui()
    varsurf_objects = [o for o in doc.Objects
                       if str(getattr(getattr(o, "Proxy", None), "Type", "")).startswith("VarSurf")]
    result["headless_view_providers"] = {o.Name: type(o.ViewObject.Proxy).__name__ for o in varsurf_objects}
    result["headless_icons"] = {o.Name: os.path.basename(o.ViewObject.Proxy.getIcon() or "")
                                for o in varsurf_objects if o.ViewObject.Proxy is not None}
    result["headless_visible"] = {o.Name: bool(o.ViewObject.Visibility) for o in doc.Objects}
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    lid = doc.getObject("Lid")
    lid.ViewObject.Proxy.doubleClicked(lid.ViewObject)  # what a double click in the tree runs
    Gui.updateGui()
    try:
        result["headless_panel"] = sorted(n for n in task_widgets() if n in ("deviationTable", "bendSpin"))
    except RuntimeError as error:
        result["headless_panel"] = str(error)
    result["headless_window"] = window_shot("headless_document.png")
    press_task_button(QtGui.QDialogButtonBox.Cancel)
    App.closeDocument(doc.Name)
    # The smoke document, saved with the GUI, opened again under another name.
    copy = os.path.join(OUT, "smoke_again.FCStd")
    with open(saved, "rb") as source, open(copy, "wb") as target:
        target.write(source.read())
    again = App.openDocument(copy)
    Gui.updateGui()
    sheets = [o for o in again.Objects if varsurf.is_sheet(o)]
    result["reopened_proxies"] = sorted({type(o.ViewObject.Proxy).__name__ for o in sheets})
    result["reopened_overlay_roots"] = [_roots(o.ViewObject, "VarSurfAnalysis") for o in sheets]
    App.closeDocument(again.Name)


def report_at_end(result):
    result["report_view_at_end"] = report_view_lines()


# Run once the event loop is up (commands and the task panel need it).
run_when_up([run, drag_space_curve, lambda result: headless_document(result, os.path.join(OUT, "smoke.FCStd")),
             report_at_end], RESULT, mark_ok=True)
