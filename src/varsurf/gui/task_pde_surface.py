# SPDX-License-Identifier: LGPL-2.1-or-later
"""Task panel of a PdeSurface: the boundary conditions it has, the coefficient a and the regions
it is painted on, the derivative magnitudes and solver settings; the result's deviations."""

from __future__ import annotations

from PySide import QtGui

from varsurf.app import pde_surface as pde_feature
from varsurf.gui import table_fit
from varsurf.gui.region_painter import RegionPainter
from varsurf.gui.region_table import RegionTable
from varsurf.gui.task_base import PropertyTaskPanel, translate
from varsurf.solve import pde_surface as pde_solve
from varsurf.solve.errors import SheetError


class TaskPanelPdeSurface(PropertyTaskPanel):
    UI = "pde_surface.ui"
    ICON = "VarSurf_PdeSurface.svg"
    TRANSACTION = "Edit VarSurf PDE surface"
    EDITABLE = ("PdeA", "PdeBlend", "PdeRegions", "PdeLoops", "Magnitude0", "Magnitude1", "Tolerance", "MinSpans",
                "MaxSpans", "DragMode", "Mass", "Damping", "Spring", "MaterialRegions")
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
        self.status = self.child(QtGui.QLabel, "statusValue")
        # a painted (a, then the rectangle); mass and damping painted (the same, two values).
        self.regions = RegionTable(self.child(QtGui.QTableWidget, "regionTable"), "PdeRegions", 5,
                                   lambda: (2.0 * float(self.a.value()), 0.25, 0.75, 0.25, 0.75), self.status)
        self.materials = RegionTable(self.child(QtGui.QTableWidget, "materialTable"), "MaterialRegions", 6,
                                     lambda: (4.0 * float(self.dynamics[0][1].value()),
                                              float(self.dynamics[1][1].value()), 0.25, 0.75, 0.25, 0.75),
                                     self.status)
        self.drag_mode = self.child(QtGui.QComboBox, "dragModeCombo")
        self.drag_mode.addItems(list(obj.getEnumerationsOfProperty("DragMode")))
        self.dynamics = [(name, self.child(QtGui.QDoubleSpinBox, spin)) for name, spin in self.DYNAMICS]
        self.deviations = self.child(QtGui.QTableWidget, "deviationTable")
        self.child(QtGui.QLabel, "curvesValue").setText(self._curves_text())
        self.child(QtGui.QPushButton, "updateButton").clicked.connect(self.update)
        self.paint_value = self.child(QtGui.QDoubleSpinBox, "paintSpin")
        self.paint_button = self.child(QtGui.QPushButton, "paintButton")
        self.paint_button.toggled.connect(self.paint)
        self.paint_shape = self.child(QtGui.QComboBox, "paintShapeCombo")
        self.paint_shape.addItems([translate("VarSurf", "Rectangle"), translate("VarSurf", "Loop")])
        self.paint_shape.currentIndexChanged.connect(self._shape_changed)
        self.loops_label = self.child(QtGui.QLabel, "loopsValue")
        self.child(QtGui.QPushButton, "removeLoopButton").clicked.connect(self.remove_loop)
        self.loops = []
        self.painter = None
        for table, add, remove in ((self.regions, "addRegionButton", "removeRegionButton"),
                                   (self.materials, "addMaterialButton", "removeMaterialButton")):
            self.child(QtGui.QPushButton, add).clicked.connect(table.add)
            self.child(QtGui.QPushButton, remove).clicked.connect(table.remove)
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
        self.regions.load(obj)
        self.materials.load(obj)
        self.paint_value.setValue(2.0 * float(obj.PdeA))
        try:
            self.loops = list(pde_feature.loops_of([float(x) for x in obj.PdeLoops]))
        except SheetError:
            self.loops = []  # unreadable: the object says so; painting starts the list again
        self._show_loops()

    def paint(self, on):
        """Paint in view: a rectangle dragged over the surface (or a loop drawn on it) is added
        with the Paint a value and previewed at once; the painted ones are outlined meanwhile."""
        if on and self.painter is None:
            self.painter = RegionPainter(self.obj, self.painted, self.painted_loop)
            self._shape_changed()
            self._outline()
        elif not on and self.painter is not None:
            self.painter.stop()
            self.painter = None

    def _shape_changed(self, *_):
        if self.painter is not None:
            self.painter.loop = self.paint_shape.currentIndex() == 1

    def _outline(self):
        if self.painter is not None:
            numbers = self.regions.numbers() or []
            rects = [tuple(numbers[k + 1:k + 5]) for k in range(0, len(numbers) - len(numbers) % 5, 5)]
            self.painter.show(rects, [points for _a, points in self.loops])

    def _show_loops(self):
        self.loops_label.setText(translate("VarSurf", "{} loops").format(len(self.loops)))

    def painted(self, u0, u1, v0, v1):
        self.regions.append([float(self.paint_value.value())] + [round(x, 4) for x in (u0, u1, v0, v1)])
        self.update()
        self._outline()

    def painted_loop(self, points):
        """A loop drawn in the view: painted if it encloses an area without crossing itself."""
        loop = (float(self.paint_value.value()), tuple((round(u, 4), round(v, 4)) for u, v in points))
        try:
            pde_solve.check(pde_solve.PdeSurfaceSettings(loops=(loop,)))
        except SheetError as error:
            self.status.setText(str(error))
            return
        self.loops.append(loop)
        self._show_loops()
        self.update()
        self._outline()

    def remove_loop(self):
        if self.loops:
            self.loops.pop()
            self._show_loops()
            self._outline()

    def accept(self):
        self.paint(False)
        return super().accept()

    def reject(self):
        self.paint(False)
        return super().reject()

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
        self.regions.store(obj)
        self.materials.store(obj)
        flat = pde_feature.flat_loops(self.loops)
        if flat != [float(x) for x in obj.PdeLoops]:
            obj.PdeLoops = flat

    def show_results(self):
        obj = self.obj
        self.child(QtGui.QLabel, "kindValue").setText(str(obj.Kind))
        self.status.setText(obj.Status if obj.isValid() else obj.getStatusString())
        table_fit.fill(self.deviations, [(name, f"{dev:.3g}") for name, dev in zip(obj.CurveNames,
                                                                                   obj.MaxDeviations)])
