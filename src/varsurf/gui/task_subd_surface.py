# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a SubdSurface: its levels and solve; a level slider that draws that level's mesh
over the surface; pins added by picking a vertex of the shown level in the 3D view, each with an
influence slider (its region of influence, drawn as the finest vertices it moves) and its normal
held or not; pins removed; the selected edges made its Curves. Each edit is a line of varsurf.app.subd_pins run through
Gui.doCommand (a macro replays it) inside the panel's one transaction: OK keeps them, Cancel
undoes them."""

from __future__ import annotations

import FreeCADGui as Gui
from PySide import QtGui

from varsurf.app import subd_pins
from varsurf.app.feature import last_outcome, value
from varsurf.app.macro import ref
from varsurf.app.subd_surface import compute, normals_of, pins_of
from varsurf.gui import table_fit
from varsurf.gui.subd_overlay import SubdOverlay, VertexPicker
from varsurf.gui.task_base import PropertyTaskPanel, message, translate
from varsurf.solve.errors import SheetError


class TaskPanelSubdSurface(PropertyTaskPanel):
    UI = "subd_surface.ui"
    ICON = "VarSurf_SubdSurface.svg"
    TRANSACTION = "Edit VarSurf subdivision surface"
    EDITABLE = ("Levels", "Solve", "Rings", "PinVertices", "PinLevels", "PinInfluence", "PinTargets",
                "NormalVertices", "NormalLevels", "NormalInfluence", "NormalDirections", "Curves", "CurveMotion",
                "CurveLevel", "CurveInfluence")
    COLUMNS = ("Vertex", "Influence", "Normal")  # a vertex as "10 (2)": vertex 10 of level 2

    def __init__(self, obj):
        super().__init__(obj)
        self.levels = self.child(QtGui.QSpinBox, "levelsSpin")
        self.solve = self.child(QtGui.QComboBox, "solveCombo")
        self.solve.addItems(list(obj.getEnumerationsOfProperty("Solve")))
        self.rings = self.child(QtGui.QSpinBox, "ringsSpin")
        self.shown = self.child(QtGui.QSlider, "showLevelSlider")
        self.shown_label = self.child(QtGui.QLabel, "showLevelLabel")
        self.table = self.child(QtGui.QTableWidget, "pinTable")
        self.table.setColumnCount(len(self.COLUMNS))
        self.table.setHorizontalHeaderLabels([translate("VarSurf", c) for c in self.COLUMNS])
        self.table.setSelectionBehavior(QtGui.QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QtGui.QAbstractItemView.SingleSelection)
        self.table.setEditTriggers(QtGui.QAbstractItemView.NoEditTriggers)
        self.influence = self.child(QtGui.QSlider, "influenceSlider")
        self.influence_label = self.child(QtGui.QLabel, "influenceLabel")
        self.region_label = self.child(QtGui.QLabel, "regionValue")
        self.status = self.child(QtGui.QLabel, "statusValue")
        self.pick_button = self.child(QtGui.QPushButton, "pickButton")
        self.overlay = SubdOverlay(obj.ViewObject)
        self.picker = None
        self.region = []
        self.load()
        self.shown.valueChanged.connect(self.show_level)
        self.table.itemSelectionChanged.connect(self.pin_selected)
        self.influence.sliderReleased.connect(self.influence_set)
        self.influence.valueChanged.connect(self.influence_shown)
        self.pick_button.toggled.connect(self.pick_pin)
        self.child(QtGui.QPushButton, "normalButton").clicked.connect(self.hold_normal)
        self.child(QtGui.QPushButton, "removeButton").clicked.connect(self.remove)
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.child(QtGui.QPushButton, "curvesButton").clicked.connect(self.curves_from_selection)
        self.loop_buttons = {"moved": self.child(QtGui.QPushButton, "moveLoopButton"),
                             "held": self.child(QtGui.QPushButton, "holdLoopButton")}
        for mode, button in self.loop_buttons.items():
            button.toggled.connect(lambda on, mode=mode: self.pick_loop(mode, on))

    # -- object <-> widgets --
    def load(self):
        obj = self.obj
        self.levels.setValue(int(obj.Levels))
        self.solve.setCurrentIndex(max(self.solve.findText(str(obj.Solve)), 0))
        self.rings.setValue(int(obj.Rings))
        first = self.shown.maximum() == 99  # Qt's default: the panel just opened
        self.shown.setMaximum(int(obj.Levels))
        if first:
            self.shown.setValue(max(int(obj.Levels) - 1, 0))
        self.fill_table()
        self.show_results()

    def store(self):
        obj = self.obj
        if int(obj.Levels) != self.levels.value():
            obj.Levels = self.levels.value()
        if str(obj.Solve) != self.solve.currentText():
            obj.Solve = self.solve.currentText()
        if int(obj.Rings) != self.rings.value():
            obj.Rings = self.rings.value()

    def update(self):
        super().update()
        self.load()

    def show_results(self):
        obj = self.obj
        self.status.setText(obj.Status if obj.isValid() else obj.getStatusString())
        count = sum(len(subs) or 1 for _, subs in (obj.Curves or []))
        moved, held = len(obj.CurveLoops), len(obj.HeldLoops)
        parts = [translate("VarSurf", "Curves: {}").format(count)] if count else []
        if moved or held:
            parts.append(translate("VarSurf", "loops moved: {}, held: {}").format(moved, held))
        self.child(QtGui.QLabel, "curvesValue").setText(
            ", ".join(parts) + translate("VarSurf", "; pins along them: {}").format(obj.CurvePins) if parts
            else translate("VarSurf", "No curves or loops"))
        self.show_level(self.shown.value())
        self.pin_selected()

    def fill_table(self):
        try:
            pins, normals = pins_of(self.obj), normals_of(self.obj)
        except SheetError:  # lists of different lengths: the status says so
            pins, normals = [], []
        held = {(n.level, n.vertex) for n in normals}
        row = self.selected()
        rows = [(f"{p.vertex} ({p.level})", str(p.influence),
                 translate("VarSurf", "held") if (p.level, p.vertex) in held else "") for p in pins]
        table_fit.fill(self.table, rows)
        if rows:
            self.table.selectRow(min(row if row is not None else 0, len(rows) - 1))

    def selected(self):
        rows = self.table.selectionModel().selectedRows() if self.table.selectionModel() else []
        return rows[0].row() if rows else None

    # -- drawing --
    def outcome(self):
        try:
            return last_outcome(self.obj, compute) if self.obj.isValid() else None
        except SheetError:
            return None

    def show_level(self, level):
        self.shown_label.setText(translate("VarSurf", "Shown level {}").format(level))
        outcome = self.outcome()
        if outcome is not None and level < len(outcome.levels):
            self.overlay.show_level(outcome.levels[level], outcome.faces[level])

    def pin_selected(self):
        index = self.selected()
        pins = list(value(self.obj, "PinLevels"))
        if index is None or index >= len(pins):
            self.influence.setEnabled(False)
            self.region = []
            self.overlay.show_region([])
            self.region_label.setText(translate("VarSurf", "Pick a vertex to add a pin"))
            return
        self.influence.setEnabled(True)
        self.influence.blockSignals(True)
        self.influence.setMaximum(int(pins[index]))
        self.influence.setValue(int(self.obj.PinInfluence[index]))
        self.influence.blockSignals(False)
        self.influence_shown(self.influence.value())
        self.draw_region(index)

    def influence_shown(self, level):
        self.influence_label.setText(translate("VarSurf", "Influence {}").format(level))

    def draw_region(self, index):
        outcome = self.outcome()
        if outcome is None:
            self.overlay.show_region([])
            return
        try:
            self.region = subd_pins.region(self.obj, index)
        except SheetError as error:
            self.region_label.setText(str(error))
            return
        self.overlay.show_region(outcome.points[self.region])
        total = len(outcome.points)
        self.region_label.setText(translate("VarSurf", "Region of influence: {} of {} vertices ({:.1f} %)").format(
            len(self.region), total, 100.0 * len(self.region) / max(total, 1)))

    # -- pin edits: document lines --
    def run(self, call):
        """Run `call` (a subd_pins function call on this object) as recorded document lines."""
        lines = ["import varsurf.app.subd_pins", f"varsurf.app.subd_pins.{call}",
                 f"App.getDocument({self.doc.Name!r}).recompute()"]
        try:
            for line in lines:
                Gui.doCommand(line)
        except Exception as error:  # the line's own words (a SheetError), in the report view
            message(f"{self.obj.Label}: {error}")
        self.fill_table()
        self.show_results()

    def curves_from_selection(self):
        """The edges selected (in the view or the tree, the object itself excluded) as Curves."""
        refs = []
        for sel in Gui.Selection.getSelectionEx(self.doc.Name):
            if sel.Object is self.obj:
                continue
            edges = [name for name in sel.SubElementNames if name.startswith("Edge")]
            refs.append(f"(App.getDocument({self.doc.Name!r}).getObject({sel.Object.Name!r}), {edges!r})"
                        if edges else f"App.getDocument({self.doc.Name!r}).getObject({sel.Object.Name!r})")
        if not refs:
            message(f"{self.obj.Label}: select edges lying on the surface first, then press Curves from selection")
            return
        lines = ["import varsurf",
                 f"varsurf.set_curves({ref(self.obj)}, [{', '.join(refs)}], {ref(self.obj)}.CurveMotion, "
                 f"level={ref(self.obj)}.CurveLevel, influence={ref(self.obj)}.CurveInfluence)",
                 f"App.getDocument({self.doc.Name!r}).recompute()"]
        try:
            for line in lines:
                Gui.doCommand(line)
        except Exception as error:
            message(f"{self.obj.Label}: {error}")
        self.show_results()

    def pick(self, on, callback=None):
        """Clicks on the surface go to `callback` (a pinned vertex by default) while `on`."""
        if self.picker is not None:
            self.picker.stop()
            self.picker = None
        if on:
            self.picker = VertexPicker(self.obj, callback or self.picked)

    def pick_pin(self, on):
        """Pick vertex: the next click pins the shown level's vertex nearest to it."""
        if on:
            for button in self.loop_buttons.values():
                button.setChecked(False)
        self.pick(on)

    def pick_loop(self, mode, on):
        """Move a loop / Hold a loop: the next click names the boundary loop nearest to it."""
        if on:
            for other, button in list(self.loop_buttons.items()) + [("pin", self.pick_button)]:
                if other != mode and button.isChecked():
                    button.setChecked(False)
        self.pick(on, lambda point: self.loop_picked(mode, point))

    def loop_picked(self, mode, point):
        try:
            loop = subd_pins.loop_at(self.obj, point)
        except SheetError as error:
            message(f"{self.obj.Label}: {error}")
            return
        self.run(f"set_loop({ref(self.obj)}, {loop}, {mode!r})")
        self.loop_buttons[mode].setChecked(False)

    def picked(self, point):
        """A click on the surface: pin the shown level's vertex nearest to it."""
        level = self.shown.value()
        try:
            vertex = subd_pins.pick_vertex(self.obj, level, point)
        except SheetError as error:
            message(f"{self.obj.Label}: {error}")
            return
        self.run(f"add_pin({ref(self.obj)}, {level}, {vertex}, {min(self.influence.value(), level)})")
        self.table.selectRow(self.table.rowCount() - 1)
        self.pick_button.setChecked(False)

    def influence_set(self):
        index = self.selected()
        if index is not None and int(self.obj.PinInfluence[index]) != self.influence.value():
            self.run(f"set_influence({ref(self.obj)}, {index}, {self.influence.value()})")

    def hold_normal(self):
        index = self.selected()
        if index is not None:
            self.run(f"hold_normal({ref(self.obj)}, {index})")

    def remove(self):
        index = self.selected()
        if index is not None:
            self.run(f"remove_pin({ref(self.obj)}, {index})")

    # -- closing --
    def close(self):
        self.pick(False)
        self.overlay.close(self.obj.ViewObject)

    def accept(self):
        self.close()
        return super().accept()

    def reject(self):
        self.close()
        return super().reject()
