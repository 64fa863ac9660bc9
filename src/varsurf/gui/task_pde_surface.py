# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a PdeSurface: the boundary conditions it has, the coefficient a and the regions
it is painted on, the derivative magnitudes and solver settings; the result's deviations."""

from __future__ import annotations

from PySide import QtCore, QtGui

from varsurf.gui import table_fit
from varsurf.gui.task_base import PropertyTaskPanel, translate

#: Columns of the painted regions' table: a, then the rectangle in 0..1.
REGION_COLUMNS = 5


class TaskPanelPdeSurface(PropertyTaskPanel):
    UI = "pde_surface.ui"
    ICON = "VarSurf_PdeSurface.svg"
    TRANSACTION = "Edit VarSurf PDE surface"
    EDITABLE = ("PdeA", "PdeBlend", "PdeRegions", "Magnitude0", "Magnitude1", "Tolerance", "MinSpans",
                "MaxSpans", "DragMode", "Mass", "Damping", "Spring")
    #: The dynamic drag's numbers: property, spin box.
    DYNAMICS = (("Mass", "massSpin"), ("Damping", "dampingSpin"), ("Spring", "springSpin"))

    def __init__(self, obj):
        super().__init__(obj)
        self.a = self.child(QtGui.QDoubleSpinBox, "aSpin")
        self.blend = self.child(QtGui.QDoubleSpinBox, "blendSpin")
        self.magnitudes = [self.child(QtGui.QDoubleSpinBox, f"magnitude{k}Spin") for k in (0, 1)]
        self.tolerance = self.child(QtGui.QDoubleSpinBox, "toleranceSpin")
        self.min_spans = self.child(QtGui.QSpinBox, "minSpansSpin")
        self.max_spans = self.child(QtGui.QSpinBox, "maxSpansSpin")
        self.regions = self.child(QtGui.QTableWidget, "regionTable")
        self.drag_mode = self.child(QtGui.QComboBox, "dragModeCombo")
        self.drag_mode.addItems(list(obj.getEnumerationsOfProperty("DragMode")))
        self.dynamics = [(name, self.child(QtGui.QDoubleSpinBox, spin)) for name, spin in self.DYNAMICS]
        # Five short numbers a row: the columns share the panel's width (no sideways scrolling),
        # without row numbers or cell padding, so "0.25" fits FreeCAD's default 250 px combo view.
        self.regions.horizontalHeader().setSectionResizeMode(QtGui.QHeaderView.Stretch)
        self.regions.horizontalHeader().setMinimumSectionSize(10)
        self.regions.verticalHeader().setVisible(False)
        self.regions.setTextElideMode(QtCore.Qt.ElideNone)
        self.regions.setStyleSheet("QTableWidget::item { padding: 0px; }")
        self.status = self.child(QtGui.QLabel, "statusValue")
        self.deviations = self.child(QtGui.QTableWidget, "deviationTable")
        self.child(QtGui.QLabel, "curvesValue").setText(self._curves_text())
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.child(QtGui.QPushButton, "addRegionButton").clicked.connect(self.add_region)
        self.child(QtGui.QPushButton, "removeRegionButton").clicked.connect(self.remove_region)
        self.load()
        self.show_results()

    def _curves_text(self):
        obj = self.obj
        parts = []
        for prop in ("U0", "U1", "Derivative0", "Derivative1", "Face0", "Face1", "V0", "V1"):
            link = getattr(obj, prop, None)
            if link is not None:
                parts.append(f"{prop}: {link[0].Label}:{', '.join(s for s in link[1] if s)}")
        for prop in ("UCurves", "VCurves"):
            count = sum(len([s for s in subs if s]) for _, subs in getattr(obj, prop))
            if count:
                parts.append(f"{prop}: {count}")
        return "\n".join(parts)

    def add_region(self):
        row = self.regions.rowCount()
        self.regions.insertRow(row)
        for column, value in enumerate((2.0 * float(self.a.value()), 0.25, 0.75, 0.25, 0.75)):
            self.regions.setItem(row, column, QtGui.QTableWidgetItem(f"{value:g}"))

    def remove_region(self):
        row = self.regions.currentRow()
        self.regions.removeRow(row if row >= 0 else self.regions.rowCount() - 1)

    def load(self):
        obj = self.obj
        self.a.setValue(float(obj.PdeA))
        self.blend.setValue(float(obj.PdeBlend))
        for spin, name in zip(self.magnitudes, ("Magnitude0", "Magnitude1")):
            spin.setValue(float(getattr(obj, name)))
        self.tolerance.setValue(float(obj.Tolerance))
        self.min_spans.setValue(int(obj.MinSpans))
        self.max_spans.setValue(int(obj.MaxSpans))
        self.drag_mode.setCurrentText(str(obj.DragMode))
        for name, spin in self.dynamics:
            spin.setValue(float(getattr(obj, name)))
        flat = list(obj.PdeRegions)
        self.regions.setRowCount(0)
        for start in range(0, len(flat) - len(flat) % REGION_COLUMNS, REGION_COLUMNS):
            row = self.regions.rowCount()
            self.regions.insertRow(row)
            for column in range(REGION_COLUMNS):
                self.regions.setItem(row, column, QtGui.QTableWidgetItem(f"{flat[start + column]:g}"))

    def _region_numbers(self):
        """The table's numbers row by row; an unreadable cell keeps the object's value and says so."""
        numbers = []
        for row in range(self.regions.rowCount()):
            for column in range(REGION_COLUMNS):
                item = self.regions.item(row, column)
                try:
                    numbers.append(float(item.text()))
                except (AttributeError, ValueError):
                    self.status.setText(translate("VarSurf", "Region {} has a cell that is not a number: "
                                                             "type a number").format(row + 1))
                    return None
        return numbers

    def store(self):
        obj = self.obj
        if abs(self.a.value() - float(obj.PdeA)) > 0.5e-4:  # 4 decimals shown
            obj.PdeA = self.a.value()
        if abs(self.blend.value() - float(obj.PdeBlend)) > 0.5e-4:
            obj.PdeBlend = self.blend.value()
        for spin, name in zip(self.magnitudes, ("Magnitude0", "Magnitude1")):
            if abs(spin.value() - float(getattr(obj, name))) > 0.5e-4:
                setattr(obj, name, spin.value())
        if abs(self.tolerance.value() - float(obj.Tolerance)) > 0.5e-6:
            obj.Tolerance = self.tolerance.value()
        if self.min_spans.value() != int(obj.MinSpans):
            obj.MinSpans = self.min_spans.value()
        if self.max_spans.value() != int(obj.MaxSpans):
            obj.MaxSpans = self.max_spans.value()
        if self.drag_mode.currentText() != str(obj.DragMode):
            obj.DragMode = self.drag_mode.currentText()
        for name, spin in self.dynamics:
            if abs(spin.value() - float(getattr(obj, name))) > 0.5 * 10 ** -spin.decimals():
                setattr(obj, name, spin.value())
        numbers = self._region_numbers()
        if numbers is not None and numbers != list(obj.PdeRegions):
            obj.PdeRegions = numbers

    def show_results(self):
        obj = self.obj
        self.child(QtGui.QLabel, "kindValue").setText(str(obj.Kind))
        self.status.setText(obj.Status if obj.isValid() else obj.getStatusString())
        table_fit.fill(self.deviations, [(name, f"{dev:.3g}") for name, dev in zip(obj.CurveNames,
                                                                                   obj.MaxDeviations)])
