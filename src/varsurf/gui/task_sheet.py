# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel to edit a Sheet (energy, space, solve mode, rest shape) and see its results."""

from __future__ import annotations

import FreeCAD as App
from PySide import QtCore, QtGui

from varsurf.app import make
from varsurf.gui import table_fit
from varsurf.gui.task_base import PropertyTaskPanel

TRANSACTION_EDIT = "Edit VarSurf sheet"
_EDITABLE = ("Stretch", "Bend", "FixBoundary", "Tolerance", "Degree", "MinSpans", "MaxSpans", "SolveMode",
             "RestShape", "InstalledRest", "Refinement", "MaxDepth")


def _join_text(gap, angle, jump):
    """A join's gap, and for a G1 or G2 join the tangent-plane angle and the curvature jump."""
    if angle < 0.0:
        return f"gap {gap:.3g} mm"
    return f"gap {gap:.3g} mm, {angle:.3g}°, curvature {jump:.3g} %"


class TaskPanelSheet(PropertyTaskPanel):
    """Energy weights, tolerance, degree, spans, solve mode and rest shape (install / melt);
    results per curve and constraint. Update previews; OK commits, Cancel undoes."""

    UI = "sheet.ui"
    ICON = "VarSurf_Sheet.svg"
    TRANSACTION = TRANSACTION_EDIT
    EDITABLE = _EDITABLE

    def __init__(self, obj):
        super().__init__(obj)
        self.stretch = self.child(QtGui.QDoubleSpinBox, "stretchSpin")
        self.bend = self.child(QtGui.QDoubleSpinBox, "bendSpin")
        self.fix_boundary = self.child(QtGui.QCheckBox, "fixBoundaryCheck")
        self.tolerance = self.child(QtGui.QLineEdit, "toleranceEdit")
        self.update_button = self.child(QtGui.QPushButton, "updateButton")
        self.degree = self.child(QtGui.QSpinBox, "degreeSpin")
        self.min_spans = self.child(QtGui.QSpinBox, "minSpansSpin")
        self.max_spans = self.child(QtGui.QSpinBox, "maxSpansSpin")
        self.solve_mode = self.child(QtGui.QComboBox, "solveModeCombo")
        self.rest_shape = self.child(QtGui.QComboBox, "restShapeCombo")
        self.install_button = self.child(QtGui.QPushButton, "installButton")
        self.melt_button = self.child(QtGui.QPushButton, "meltButton")
        self.refinement = self.child(QtGui.QComboBox, "refinementCombo")
        self.max_depth = self.child(QtGui.QSpinBox, "maxDepthSpin")
        self.refinement.addItems(list(obj.getEnumerationsOfProperty("Refinement")))
        self.solve_mode.addItems(list(obj.getEnumerationsOfProperty("SolveMode")))
        self.rest_shape.addItems(list(obj.getEnumerationsOfProperty("RestShape")))
        self.table = self.child(QtGui.QTableWidget, "deviationTable")
        self.poles_label = self.child(QtGui.QLabel, "polesValue")
        self.time_label = self.child(QtGui.QLabel, "solveTimeValue")
        self.rank_label = self.child(QtGui.QLabel, "rankValue")
        self.status_label = self.child(QtGui.QLabel, "statusValue")

        self.table.setSizeAdjustPolicy(QtGui.QAbstractScrollArea.AdjustIgnored)
        self.table.setMinimumWidth(0)
        table_fit.keep_values_whole(self.table)

        validator = QtGui.QDoubleValidator(0.0, 1.0e6, 20, self.tolerance)
        validator.setNotation(QtGui.QDoubleValidator.ScientificNotation)
        self.tolerance.setValidator(validator)

        self.load()
        self.show_results()
        self.update_button.clicked.connect(self.update)
        self.install_button.clicked.connect(self.install_rest_shape)
        self.melt_button.clicked.connect(self.melt)

    # -- values --
    def load(self):
        self.stretch.setValue(float(self.obj.Stretch))
        self.bend.setValue(float(self.obj.Bend))
        self.fix_boundary.setChecked(bool(self.obj.FixBoundary))
        self.tolerance.setText(f"{float(self.obj.Tolerance):g}")
        self.degree.setValue(int(self.obj.Degree))
        self.min_spans.setValue(int(self.obj.MinSpans))
        self.max_spans.setValue(int(self.obj.MaxSpans))
        self.solve_mode.setCurrentText(str(self.obj.SolveMode))
        self.rest_shape.setCurrentText(str(self.obj.RestShape))
        self.refinement.setCurrentText(str(self.obj.Refinement))
        self.max_depth.setValue(int(self.obj.MaxDepth))

    def store(self):
        self.obj.Stretch = float(self.stretch.value())
        self.obj.Bend = float(self.bend.value())
        self.obj.FixBoundary = bool(self.fix_boundary.isChecked())
        try:
            tolerance = float(self.tolerance.text())
        except ValueError:
            tolerance = float(self.obj.Tolerance)
        if tolerance > 0.0:
            self.obj.Tolerance = tolerance
        self.obj.Degree = int(self.degree.value())
        self.obj.MinSpans = int(self.min_spans.value())
        self.obj.MaxSpans = max(int(self.max_spans.value()), int(self.min_spans.value()))
        self.obj.SolveMode = self.solve_mode.currentText()
        self.obj.Refinement = self.refinement.currentText()
        self.obj.MaxDepth = int(self.max_depth.value())
        if self.rest_shape.currentText() != "Installed" or not self.obj.InstalledRest.isNull():
            self.obj.RestShape = self.rest_shape.currentText()

    def show_results(self):
        obj = self.obj
        rows = [(name, f"{dev:.3g} mm") for name, dev in zip(obj.CurveNames, obj.MaxDeviations)]
        rows += [(name, f"{dev:.3g} {'°' if unit == 'deg' else unit}")
                 for name, dev, unit in zip(obj.ConstraintNames, obj.ConstraintResiduals, obj.ConstraintUnits)]
        rows += [(f"{name}: join", _join_text(gap, angle, jump)) for name, gap, angle, jump in
                 zip(*(getattr(obj, p, []) for p in ("JoinNames", "JoinGaps", "JoinAngles", "JoinCurvatureJumps")))]
        self.table.setRowCount(len(rows))
        for row, (name, text) in enumerate(rows):
            self.table.setItem(row, 0, table_fit.name_item(name))
            item = QtGui.QTableWidgetItem(text)
            item.setTextAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
            self.table.setItem(row, 1, item)
        # As tall as its rows (up to eight; more scroll), so the settings below stay close.
        rows_shown = self.table.verticalHeader()
        body = min(rows_shown.length(), 8 * rows_shown.defaultSectionSize()) if rows else \
            rows_shown.defaultSectionSize()
        self.table.setFixedHeight(self.table.horizontalHeader().sizeHint().height() + 2 * self.table.frameWidth()
                                  + body)
        table_fit.fit_columns(self.table)
        text = f"{obj.PoleCountU} × {obj.PoleCountV}, degree {obj.DegreeU} × {obj.DegreeV}"
        if str(getattr(obj, "Refinement", "Uniform")) == "Local":
            text += f"; local: {obj.RefinementDepth} levels, {obj.DegreesOfFreedom} poles solved"
        self.poles_label.setText(text)
        self.time_label.setText(f"{obj.SolveTime * 1000.0:.1f} ms")
        self.rank_label.setText(str(obj.ConstraintRank))
        self.status_label.setText(obj.Status)

    def install_rest_shape(self):
        """The current result becomes the rest shape (inside the panel's transaction)."""
        try:
            make.install_rest_shape(self.obj)
        except ValueError as error:
            App.Console.PrintError(f"VarSurf: {error}\n")
            return
        self.rest_shape.setCurrentText("Installed")
        self.update()

    def melt(self):
        make.melt(self.obj)
        self.rest_shape.setCurrentText("None")
        self.update()
