# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a Hinge: the sheets and curve it joins, its angle and Enabled; the angles its
Solid reached along the seam."""

from __future__ import annotations

from PySide import QtGui

from varsurf.gui.task_base import PropertyTaskPanel, translate


def solid_of(hinge):
    for obj in hinge.InList:
        if hinge in (getattr(obj, "Hinges", None) or []):
            return obj
    return None


class TaskPanelHinge(PropertyTaskPanel):
    UI = "hinge.ui"
    ICON = "VarSurf_Hinge.svg"
    TRANSACTION = "Edit VarSurf hinge"
    EDITABLE = ("Angle", "Enabled")

    def __init__(self, obj):
        super().__init__(obj)
        self.angle = self.child(QtGui.QDoubleSpinBox, "angleSpin")
        self.enabled = self.child(QtGui.QCheckBox, "enabledCheck")
        self.reached = self.child(QtGui.QLabel, "reachedValue")
        self.child(QtGui.QLabel, "sheetsValue").setText(" / ".join(s.Label for s in obj.Sheets or []))
        curve = obj.Curve
        self.child(QtGui.QLabel, "curveValue").setText(
            f"{curve[0].Label}:{[s for s in curve[1] if s][0]}" if curve else "")
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.load()
        self.show_results()

    def load(self):
        self.angle.setValue(float(self.obj.Angle.Value if hasattr(self.obj.Angle, "Value") else self.obj.Angle))
        self.enabled.setChecked(bool(self.obj.Enabled))

    def store(self):
        self.obj.Angle = self.angle.value()
        self.obj.Enabled = self.enabled.isChecked()

    def show_results(self):
        solid = solid_of(self.obj)
        if solid is None:
            self.reached.setText(translate("VarSurf", "not in a Solid"))
            return
        if not solid.isValid():
            self.reached.setText(translate("VarSurf", "{} is in error: {}").format(solid.Label, solid.Status))
            return
        enabled = [h for h in solid.Hinges if h.Enabled]
        if self.obj not in enabled:
            self.reached.setText(translate("VarSurf", "disabled"))
            return
        k = enabled.index(self.obj)
        lo, hi = solid.HingeAngles[2 * k], solid.HingeAngles[2 * k + 1]
        self.reached.setText(translate("VarSurf", "{:.3f}° … {:.3f}° (off by up to {:.3g}°)").format(
            lo, hi, solid.HingeErrors[k]))
