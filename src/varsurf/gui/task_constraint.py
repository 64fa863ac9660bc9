# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a Constraint: kind, enabled, weight, where it acts (a vertex picked in the 3D
view or (u, v)), its vector and origin, region, curve and reference links, angle; its residual
on the solved sheet. Fields the kind does not use are disabled."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtGui

from varsurf.gui.handles import sheet_of
from varsurf.gui.task_base import PropertyTaskPanel, message, translate
from varsurf.solve import constraints

_LINKS = {"location": ("Location", ("Vertex",)), "curve": ("Curve", ("Edge",)),
          "reference": ("Reference", ("Face", "Edge"))}
_VECTOR_KINDS = ("TangentU", "TangentV", "Normal", "PointInPlane", "PointOnLine", "Curvature", "PlaneAttractor",
                 "LineAttractor", "Director")
_ORIGIN_KINDS = ("Point", "PointInPlane", "PointOnLine", "PointAttractor", "PlaneAttractor",
                 "LineAttractor", "Repeller")


def _link_text(link):
    if link is None:
        return ""
    obj, subs = link
    subs = [s for s in subs if s]
    return f"{obj.Label}:{subs[0]}" if subs else obj.Label


class TaskPanelConstraint(PropertyTaskPanel):
    UI = "constraint.ui"
    ICON = "VarSurf_Constraint.svg"
    TRANSACTION = "Edit VarSurf constraint"
    EDITABLE = ("Kind", "Enabled", "Weight", "Location", "U", "V", "Vector", "Origin", "UseOrigin",
                "RegionU0", "RegionU1", "RegionV0", "RegionV1", "Curve", "Reference", "Angle", "CurvatureU",
                "CurvatureV", "CurvatureDirections")

    def __init__(self, obj):
        super().__init__(obj)
        c = self.child
        self.kind = c(QtGui.QComboBox, "kindCombo")
        self.kind.addItems(list(constraints.KINDS))
        self.help = c(QtGui.QLabel, "kindHelp")
        self.enabled = c(QtGui.QCheckBox, "enabledCheck")
        self.weight = c(QtGui.QDoubleSpinBox, "weightSpin")
        self.u, self.v = c(QtGui.QDoubleSpinBox, "uSpin"), c(QtGui.QDoubleSpinBox, "vSpin")
        self.vector = [c(QtGui.QDoubleSpinBox, f"vector{a}") for a in "XYZ"]
        self.origin = [c(QtGui.QDoubleSpinBox, f"origin{a}") for a in "XYZ"]
        self.use_origin = c(QtGui.QCheckBox, "useOriginCheck")
        self.region = [c(QtGui.QDoubleSpinBox, f"region{n}Spin") for n in ("U0", "U1", "V0", "V1")]
        self.angle = c(QtGui.QDoubleSpinBox, "angleSpin")
        self.curvature = [c(QtGui.QDoubleSpinBox, "curvatureUSpin"), c(QtGui.QDoubleSpinBox, "curvatureVSpin")]
        self.curvature_directions = c(QtGui.QComboBox, "curvatureDirectionsCombo")
        self.curvature_directions.addItems(list(constraints.CURVATURE_DIRECTIONS))
        self.residual = c(QtGui.QLabel, "residualValue")
        self.links = {}  # prefix -> (property, kinds, line edit, value)
        for prefix, (prop, kinds) in _LINKS.items():
            edit = c(QtGui.QLineEdit, prefix + "Edit")
            self.links[prefix] = [prop, kinds, edit, getattr(obj, prop)]
            c(QtGui.QPushButton, prefix + "Pick").clicked.connect(lambda _=False, p=prefix: self.pick(p))
            c(QtGui.QPushButton, prefix + "Clear").clicked.connect(lambda _=False, p=prefix: self.set_link(p, None))
        c(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.kind.currentTextChanged.connect(self.enable_fields)
        self.load()
        self.show_results()

    # -- links picked from the 3D view --
    def set_link(self, prefix, link):
        entry = self.links[prefix]
        entry[3] = link
        entry[2].setText(_link_text(link))

    def pick(self, prefix):
        """The element selected in the 3D view, if it is of the kind the link takes."""
        _prop, kinds, _edit, _value = self.links[prefix]
        for sel in Gui.Selection.getSelectionEx():
            for name in sel.SubElementNames:
                if name.startswith(kinds):
                    self.set_link(prefix, (sel.Object, name))
                    return True
        message(translate("VarSurf", "{}: select a {} in the 3D view first").format(
            self.obj.Label, " or ".join(k.lower() for k in kinds)))
        return False

    # -- values --
    def enable_fields(self, kind=None):
        kind = kind or self.kind.currentText()
        self.help.setText(constraints.KINDS.get(kind, ("", ""))[0])
        point = kind in constraints.POINT_KINDS
        for w in (self.u, self.v):
            w.setEnabled(point)
        self.child(QtGui.QPushButton, "locationPick").setEnabled(point)
        for w in self.vector:
            w.setEnabled(kind in _VECTOR_KINDS)
        for w in self.origin:
            w.setEnabled(kind in _ORIGIN_KINDS)
        self.use_origin.setEnabled(kind == "Point")
        for w in self.region:
            w.setEnabled(kind in constraints.REGION_KINDS or kind == "RegionMap")
        curve_kind = kind in constraints.CURVE_KINDS or kind in ("G0", "CurveAttractor", "CurveMap")
        self.child(QtGui.QPushButton, "curvePick").setEnabled(curve_kind)
        references = ("Ribbon", "G1", "G2", "SurfaceAttractor", "CurveMap", "RegionMap")
        self.child(QtGui.QPushButton, "referencePick").setEnabled(kind in references)
        self.angle.setEnabled(kind == "Ribbon")
        for w in self.curvature + [self.curvature_directions]:
            w.setEnabled(kind == "Curvature")

    def load(self):
        o = self.obj
        self.kind.setCurrentText(str(o.Kind))
        self.enabled.setChecked(bool(o.Enabled))
        self.weight.setValue(float(o.Weight))
        self.u.setValue(float(o.U))
        self.v.setValue(float(o.V))
        for w, value in zip(self.vector + self.origin, list(o.Vector) + list(o.Origin)):
            w.setValue(value)
        # What the spin boxes show (rounded): unchanged fields keep the exact values on store.
        self.shown = {"Vector": [w.value() for w in self.vector], "Origin": [w.value() for w in self.origin]}
        self.use_origin.setChecked(bool(o.UseOrigin))
        for w, name in zip(self.region, ("RegionU0", "RegionU1", "RegionV0", "RegionV1")):
            w.setValue(float(getattr(o, name)))
        self.angle.setValue(float(o.Angle.Value if hasattr(o.Angle, "Value") else o.Angle))
        for w, name in zip(self.curvature, ("CurvatureU", "CurvatureV")):
            w.setValue(float(getattr(o, name)))
        self.shown["Curvature"] = [w.value() for w in self.curvature]
        self.curvature_directions.setCurrentText(str(o.CurvatureDirections))
        for prefix, (prop, _kinds, _edit, _value) in self.links.items():
            self.set_link(prefix, getattr(o, prop))
        self.enable_fields()

    def store(self):
        o = self.obj
        o.Kind = self.kind.currentText()
        o.Enabled = self.enabled.isChecked()
        o.Weight = self.weight.value()
        o.U, o.V = self.u.value(), self.v.value()
        for prop, widgets in (("Vector", self.vector), ("Origin", self.origin)):
            values = [w.value() for w in widgets]
            if values != self.shown[prop]:
                setattr(o, prop, App.Vector(*values))
                self.shown[prop] = values
        o.UseOrigin = self.use_origin.isChecked()
        for w, name in zip(self.region, ("RegionU0", "RegionU1", "RegionV0", "RegionV1")):
            setattr(o, name, w.value())
        o.Angle = self.angle.value()
        values = [w.value() for w in self.curvature]
        if values != self.shown["Curvature"]:  # shown rounded to 6 decimals: unchanged keeps the exact values
            o.CurvatureU, o.CurvatureV = values
            self.shown["Curvature"] = values
        o.CurvatureDirections = self.curvature_directions.currentText()
        for prefix, (prop, _kinds, _edit, value) in self.links.items():
            if getattr(o, prop) != value:
                setattr(o, prop, value)

    def show_results(self):
        sheet = sheet_of(self.obj)
        text = "—"
        if sheet is not None:
            if not sheet.isValid():
                text = translate("VarSurf", "{} is in error: {}").format(sheet.Label, sheet.Status)
            elif self.obj.Label in list(sheet.ConstraintNames):
                k = list(sheet.ConstraintNames).index(self.obj.Label)
                unit = sheet.ConstraintUnits[k]
                text = f"{sheet.ConstraintResiduals[k]:.3g} {'°' if unit == 'deg' else unit}"
        self.residual.setText(text)
