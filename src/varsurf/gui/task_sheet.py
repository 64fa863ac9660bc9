"""Task panel to edit a Sheet's weights and see its results."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtCore, QtGui

from varsurf.gui import resources

TRANSACTION_EDIT = "Edit VarSurf sheet"
_EDITABLE = ("Stretch", "Bend", "FixBoundary", "Tolerance")


class TaskPanelSheet:
    """Stretch, Bend, FixBoundary, Tolerance; results per curve. OK commits, Cancel undoes."""

    def __init__(self, obj):
        self.obj = obj
        self.doc = obj.Document
        self.form = Gui.PySideUic.loadUi(resources.ui("sheet.ui"))
        self.form.setWindowIcon(QtGui.QIcon(resources.icon("VarSurf_Sheet.svg")))
        self.stretch = self._child(QtGui.QDoubleSpinBox, "stretchSpin")
        self.bend = self._child(QtGui.QDoubleSpinBox, "bendSpin")
        self.fix_boundary = self._child(QtGui.QCheckBox, "fixBoundaryCheck")
        self.tolerance = self._child(QtGui.QLineEdit, "toleranceEdit")
        self.update_button = self._child(QtGui.QPushButton, "updateButton")
        self.table = self._child(QtGui.QTableWidget, "deviationTable")
        self.poles_label = self._child(QtGui.QLabel, "polesValue")
        self.time_label = self._child(QtGui.QLabel, "solveTimeValue")
        self.rank_label = self._child(QtGui.QLabel, "rankValue")
        self.status_label = self._child(QtGui.QLabel, "statusValue")

        header = self.table.horizontalHeader()
        header.setSectionResizeMode(0, QtGui.QHeaderView.Stretch)
        header.setSectionResizeMode(1, QtGui.QHeaderView.ResizeToContents)
        self.table.setSizeAdjustPolicy(QtGui.QAbstractScrollArea.AdjustIgnored)
        self.table.setMinimumWidth(0)

        validator = QtGui.QDoubleValidator(0.0, 1.0e6, 20, self.tolerance)
        validator.setNotation(QtGui.QDoubleValidator.ScientificNotation)
        self.tolerance.setValidator(validator)

        self._original = {name: getattr(obj, name) for name in _EDITABLE}
        self.doc.openTransaction(TRANSACTION_EDIT)
        self._load_values()
        self.show_results()
        self.update_button.clicked.connect(self.update)

    def _child(self, kind, name):
        widget = self.form.findChild(kind, name)
        if widget is None:
            raise RuntimeError(f"sheet.ui has no {kind.__name__} named {name}")
        return widget

    # -- values --
    def _load_values(self):
        self.stretch.setValue(float(self.obj.Stretch))
        self.bend.setValue(float(self.obj.Bend))
        self.fix_boundary.setChecked(bool(self.obj.FixBoundary))
        self.tolerance.setText(f"{float(self.obj.Tolerance):g}")

    def _store_values(self):
        self.obj.Stretch = float(self.stretch.value())
        self.obj.Bend = float(self.bend.value())
        self.obj.FixBoundary = bool(self.fix_boundary.isChecked())
        try:
            tolerance = float(self.tolerance.text())
        except ValueError:
            tolerance = float(self.obj.Tolerance)
        if tolerance > 0.0:
            self.obj.Tolerance = tolerance

    def show_results(self):
        obj = self.obj
        names = list(obj.CurveNames)
        deviations = list(obj.MaxDeviations)
        self.table.setRowCount(len(names))
        for row, (name, dev) in enumerate(zip(names, deviations)):
            self.table.setItem(row, 0, QtGui.QTableWidgetItem(name))
            item = QtGui.QTableWidgetItem(f"{dev:.3g}")
            item.setTextAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
            self.table.setItem(row, 1, item)
        self.poles_label.setText(
            f"{obj.PoleCountU} × {obj.PoleCountV}, degree {obj.DegreeU} × {obj.DegreeV}"
        )
        self.time_label.setText(f"{obj.SolveTime * 1000.0:.1f} ms")
        self.rank_label.setText(str(obj.ConstraintRank))
        self.status_label.setText(obj.Status)

    def update(self):
        """Apply the values and recompute, keeping the transaction open (a preview)."""
        self._store_values()
        self.doc.recompute()
        self.show_results()

    # -- task dialog protocol --
    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        self._store_values()
        self.doc.recompute()
        self.doc.commitTransaction()
        Gui.ActiveDocument.resetEdit()
        return True

    def reject(self):
        self.doc.abortTransaction()
        # With undo off the abort restores nothing: put the original values back by hand.
        for name, value in self._original.items():
            if getattr(self.obj, name) != value:
                setattr(self.obj, name, value)
        if self.obj.isTouched() or "Touched" in self.obj.State:
            self.doc.recompute()
        Gui.ActiveDocument.resetEdit()
        return True
