# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a Solid: its Sheets and tolerance; the curves they are joined along with the
gap measured at each, its hinges with the angles reached, and its status."""

from __future__ import annotations

from PySide import QtGui

from varsurf.gui import table_fit
from varsurf.gui.task_base import PropertyTaskPanel


class TaskPanelSolid(PropertyTaskPanel):
    UI = "solid.ui"
    ICON = "VarSurf_Solid.svg"
    TRANSACTION = "Edit VarSurf solid"
    EDITABLE = ("Tolerance",)

    def __init__(self, obj):
        super().__init__(obj)
        self.tolerance = self.child(QtGui.QDoubleSpinBox, "toleranceSpin")
        self.status = self.child(QtGui.QLabel, "statusValue")
        self.seams = self.child(QtGui.QTableWidget, "seamTable")
        self.hinges = self.child(QtGui.QTableWidget, "hingeTable")
        self.child(QtGui.QLabel, "sheetsValue").setText(", ".join(s.Label for s in obj.Sheets or []))
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.load()
        self.show_results()

    def load(self):
        self.tolerance.setValue(float(self.obj.Tolerance))

    def store(self):
        if abs(self.tolerance.value() - float(self.obj.Tolerance)) > 0.5e-6:  # 6 decimals shown
            self.obj.Tolerance = self.tolerance.value()

    def show_results(self):
        obj = self.obj
        self.status.setText(obj.Status)
        doc = obj.Document

        def label(key):
            name, _, sub = key.partition(":")
            found = doc.getObject(name)
            return f"{found.Label}:{sub}" if found is not None and sub else key

        table_fit.fill(self.seams, [(label(k), f"{g:.3g}") for k, g in zip(obj.SeamCurves, obj.SeamGaps)])
        enabled = [h for h in obj.Hinges or [] if h.Enabled]
        rows = []
        for k, h in enumerate(enabled):
            angle = float(h.Angle.Value if hasattr(h.Angle, "Value") else h.Angle)
            reached = (f"{obj.HingeAngles[2 * k]:.3f}° … {obj.HingeAngles[2 * k + 1]:.3f}°"
                       if len(obj.HingeAngles) >= 2 * k + 2 else "—")
            rows.append((h.Label, f"{angle:g}°", reached))
        table_fit.fill(self.hinges, rows)
