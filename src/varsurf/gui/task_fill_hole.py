# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a FillHole: its continuity and tolerance; how the sheet joins each face around
the hole (gap, angle, curvature jump, measured on the result), and its status."""

from __future__ import annotations

from PySide import QtGui

from varsurf.gui import table_fit
from varsurf.gui.task_base import PropertyTaskPanel


class TaskPanelFillHole(PropertyTaskPanel):
    UI = "fill_hole.ui"
    ICON = "VarSurf_FillHole.svg"
    TRANSACTION = "Edit VarSurf fill hole"
    EDITABLE = ("Continuity", "Tolerance")

    def __init__(self, obj):
        super().__init__(obj)
        self.continuity = self.child(QtGui.QComboBox, "continuityCombo")
        self.continuity.addItems(list(obj.getEnumerationsOfProperty("Continuity")))
        self.tolerance = self.child(QtGui.QDoubleSpinBox, "toleranceSpin")
        self.status = self.child(QtGui.QLabel, "statusValue")
        self.joins = self.child(QtGui.QTableWidget, "joinTable")
        base = obj.Base
        self.child(QtGui.QLabel, "baseValue").setText(
            f"{base[0].Label}: {', '.join(base[1])}" if base else "—")
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.load()
        self.show_results()

    def load(self):
        self.continuity.setCurrentText(str(self.obj.Continuity))
        self.tolerance.setValue(float(self.obj.Tolerance))

    def store(self):
        if self.continuity.currentText() != str(self.obj.Continuity):
            self.obj.Continuity = self.continuity.currentText()
        if abs(self.tolerance.value() - float(self.obj.Tolerance)) > 0.5e-6:  # 6 decimals shown
            self.obj.Tolerance = self.tolerance.value()

    def show_results(self):
        obj = self.obj
        self.status.setText(obj.Status)
        angles, jumps = list(obj.JoinAngles), list(obj.JoinCurvatureJumps)
        rows = []
        for k, (name, gap) in enumerate(zip(obj.JoinNames, obj.JoinGaps)):
            rows.append((name, f"{gap:.3g}", f"{angles[k]:.3g}" if k < len(angles) else table_fit.EMPTY,
                         f"{jumps[k]:.3g}" if k < len(jumps) else table_fit.EMPTY))
        table_fit.fill(self.joins, rows)
