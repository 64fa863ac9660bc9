# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a TriangularSurface: the patches' degree, the energy's weights, the continuity
and the solver; what the surface reached (G1 angles, edges where continuity was overruled,
singular vertices) and its status."""

from __future__ import annotations

from PySide import QtGui

from varsurf.gui.task_base import PropertyTaskPanel
from varsurf.solve import triangular


class TaskPanelTriangularSurface(PropertyTaskPanel):
    UI = "triangular_surface.ui"
    ICON = "VarSurf_TriangularSurface.svg"
    TRANSACTION = "Edit VarSurf triangular surface"
    EDITABLE = ("Degree", "Stretch", "Bend", "G1", "ApproximateG1", "BorderAngle", "Solver")

    def __init__(self, obj):
        super().__init__(obj)
        self.degree = self.child(QtGui.QSpinBox, "degreeSpin")
        self.stretch = self.child(QtGui.QDoubleSpinBox, "stretchSpin")
        self.bend = self.child(QtGui.QDoubleSpinBox, "bendSpin")
        self.g1 = self.child(QtGui.QCheckBox, "g1Check")
        self.approximate = self.child(QtGui.QCheckBox, "approximateCheck")
        self.border_angle = self.child(QtGui.QDoubleSpinBox, "borderAngleSpin")
        self.solver = self.child(QtGui.QComboBox, "solverCombo")
        self.solver.addItems(list(triangular.SOLVERS))
        source = getattr(obj, "Source", None)
        self.child(QtGui.QLabel, "sourceValue").setText(source.Label if source is not None else "—")
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.load()
        self.show_results()

    def load(self):
        obj = self.obj
        self.degree.setValue(int(obj.Degree))
        self.stretch.setValue(float(obj.Stretch))
        self.bend.setValue(float(obj.Bend))
        self.g1.setChecked(bool(obj.G1))
        self.approximate.setChecked(bool(obj.ApproximateG1))
        self.border_angle.setValue(float(obj.getPropertyByName("BorderAngle")))
        self.solver.setCurrentIndex(max(0, self.solver.findText(str(obj.Solver))))

    def store(self):
        obj = self.obj
        changes = {
            "Degree": self.degree.value(), "Stretch": self.stretch.value(), "Bend": self.bend.value(),
            "G1": self.g1.isChecked(), "ApproximateG1": self.approximate.isChecked(),
            "Solver": self.solver.currentText(),
        }
        for name, new in changes.items():
            if getattr(obj, name) != new:
                setattr(obj, name, new)
        if abs(self.border_angle.value() - float(obj.getPropertyByName("BorderAngle"))) > 0.5e-2:
            obj.BorderAngle = self.border_angle.value()

    def show_results(self):
        obj = self.obj
        self.child(QtGui.QLabel, "statusValue").setText(obj.Status)
        values = {
            "patchesValue": f"{obj.PatchCount} ({obj.FaceCount} B-rep faces)",
            "unknownsValue": str(obj.Unknowns),
            "worstValue": f"{obj.WorstAngle:.3g}°",
            "seamValue": f"{obj.SeamAngle:.3g}°",
            "overruledValue": str(obj.OverruledEdges),
            "singularValue": ", ".join(str(v) for v in obj.SingularVertices) or "none",
            "timeValue": f"{obj.SolveTime * 1000.0:.1f} ms",
        }
        for name, text in values.items():
            self.child(QtGui.QLabel, name).setText(text)
