# SPDX-License-Identifier: LGPL-2.1-or-later
"""View providers of VarSurf objects."""

from __future__ import annotations

import importlib
import os

import FreeCADGui as Gui
from PySide import QtGui
from PySide.QtCore import QT_TRANSLATE_NOOP

from varsurf.app.persistence import VersionedState
from varsurf.gui import analysis_overlay, property_columns, refinement_overlay, resources
from varsurf.gui.handles import ConstraintHandles, CurveHandles, is_dragging, refresh_sheet_handles
from varsurf.gui.subd_handles import SubdHandles

TYPE = "VarSurf::ViewProviderSheet"


def _input_objects(obj):
    """The objects a Sheet links to: base first, then the curves' objects, without repeats."""
    found = []
    base = getattr(obj, "Base", None)
    if base:
        found.append(base[0])
    for link_obj, _subs in getattr(obj, "Curves", None) or []:
        found.append(link_obj)
    found.extend(getattr(obj, "Constraints", None) or [])
    unique = []
    for item in found:
        if item is not None and item is not obj and item not in unique:
            unique.append(item)
    return unique


class _ViewProvider(VersionedState):
    """What every VarSurf view provider does: remember its objects, show ICON in the tree."""

    ICON = "VarSurf.svg"

    def __init__(self, vobj):
        vobj.Proxy = self
        self.attach(vobj)

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object
        property_columns.install()  # also in documents opened outside the workbench

    def getIcon(self):
        return resources.icon(self.ICON)

    def updateData(self, obj, prop):
        pass

    def onChanged(self, vobj, prop):
        pass

    def onDelete(self, vobj, subelements):
        """What the object stood for in the view (its proxy's consumed(), hidden when it was
        made) is shown again."""
        proxy = getattr(vobj.Object, "Proxy", None)
        for obj in proxy.consumed(vobj.Object) if hasattr(proxy, "consumed") else []:
            if obj is not None and obj.ViewObject is not None:
                obj.ViewObject.Visibility = True
        return True


class _EditedInPanel:
    """Double click or the context menu opens the object's task panel (PANEL: module, class).

    The panel is named, not imported: panels use the make-functions, which import this module for
    the view providers of the objects they make."""

    PANEL = ("", "")
    EDIT_TEXT = "Edit"

    def doubleClicked(self, vobj):
        Gui.ActiveDocument.setEdit(vobj.Object.Name, 0)
        return True

    def setupContextMenu(self, vobj, menu):
        action = QtGui.QAction(QtGui.QIcon(self.getIcon()),
                               QtGui.QApplication.translate("VarSurf", self.EDIT_TEXT), menu)
        action.triggered.connect(lambda: Gui.ActiveDocument.setEdit(vobj.Object.Name, 0))
        menu.addAction(action)

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return False  # let FreeCAD handle Transform etc.
        module, name = self.PANEL
        Gui.Control.showDialog(getattr(importlib.import_module(module), name)(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        if mode != 0:
            return False
        Gui.Control.closeDialog()
        return True


class ViewProviderSheet(_EditedInPanel, _ViewProvider):
    """Tree icon, children (base, curves, constraints), double click to edit."""

    TYPE = TYPE
    ICON = "VarSurf_Sheet.svg"
    PANEL = ("varsurf.gui.task_sheet", "TaskPanelSheet")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit sheet")

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        return _input_objects(obj) if obj is not None else []

    def attach(self, vobj):
        super().attach(vobj)
        analysis_overlay.add_view_properties(vobj)
        refinement_overlay.add_view_property(vobj)
        if getattr(self, "overlay", None) is None:  # FreeCAD attaches again when Proxy is set
            self.overlay = analysis_overlay.AnalysisOverlay(vobj)
            self.refinement = refinement_overlay.RefinementOverlay(vobj)

    def updateData(self, obj, prop):
        if prop != "Shape":
            return
        refresh_sheet_handles(obj)  # the constraints' handles sit on the solved sheet
        overlay = getattr(self, "overlay", None)
        if overlay is None or obj.ViewObject is None:
            return
        if is_dragging():
            overlay.root.removeAllChildren()  # back when the drag is released and recomputed
        else:
            overlay.update(obj.ViewObject)
            self.refinement.update(obj.ViewObject)

    def onChanged(self, vobj, prop):
        overlay = getattr(self, "overlay", None)
        if prop in analysis_overlay.REDRAW and overlay is not None:
            overlay.update(vobj)
        if prop == "ShowRefinement" and getattr(self, "refinement", None) is not None:
            self.refinement.update(vobj)


class ViewProviderConstraint(_EditedInPanel, _ViewProvider):
    """Tree icon of a Constraint, and its handles in the 3D view (gui.handles): a Point's pin drags
    its target with the Sheet re-solved live."""

    TYPE = "VarSurf::ViewProviderConstraint"
    ICON = "VarSurf_Constraint.svg"
    MODE = "Handles"
    PANEL = ("varsurf.gui.task_constraint", "TaskPanelConstraint")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit constraint")

    def attach(self, vobj):
        super().attach(vobj)
        if getattr(self, "handles", None) is None:  # FreeCAD attaches again when Proxy is set
            self.handles = ConstraintHandles()
            vobj.addDisplayMode(self.handles.root, self.MODE)
        self.handles.rebuild(vobj.Object)

    def getIcon(self):
        """The kind's own icon (the generic one for a kind without)."""
        kind = str(getattr(getattr(self, "Object", None), "Kind", ""))
        path = resources.icon(f"VarSurf_{kind}.svg")
        return path if kind and os.path.isfile(path) else resources.icon(self.ICON)

    def getDisplayModes(self, vobj):
        return [self.MODE]

    def getDefaultDisplayMode(self):
        return self.MODE

    def setDisplayMode(self, mode):
        return mode

    def updateData(self, obj, prop):
        handles = getattr(self, "handles", None)
        if handles is not None:
            handles.rebuild(obj)


class ViewProviderSolid(_EditedInPanel, _ViewProvider):
    """Tree icon of a Solid, with its Sheets as children; hides them, as Part features hide the
    shapes they consume."""

    TYPE = "VarSurf::ViewProviderSolid"
    ICON = "VarSurf_Solid.svg"
    PANEL = ("varsurf.gui.task_solid", "TaskPanelSolid")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit solid")

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        if obj is None:
            return []
        return list(getattr(obj, "Sheets", None) or []) + list(getattr(obj, "Hinges", None) or [])


class ViewProviderFillHole(_EditedInPanel, _ViewProvider):
    """Tree icon of a FillHole, with the part it fills as its child (the part is hidden, as Part
    features hide the shapes they consume); its panel edits the continuity and tolerance."""

    TYPE = "VarSurf::ViewProviderFillHole"
    ICON = "VarSurf_FillHole.svg"
    PANEL = ("varsurf.gui.task_fill_hole", "TaskPanelFillHole")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit fill hole")

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        base = getattr(obj, "Base", None) if obj is not None else None
        return [base[0]] if base else []


class ViewProviderPdeSurface(_EditedInPanel, _ViewProvider):
    """Tree icon of a PdeSurface (a surface from boundary curves and the Bloor-Wilson PDE), with
    its Constraints as children; double click opens its panel."""

    TYPE = "VarSurf::ViewProviderPdeSurface"
    ICON = "VarSurf_PdeSurface.svg"
    PANEL = ("varsurf.gui.task_pde_surface", "TaskPanelPdeSurface")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit PDE surface")

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        return list(getattr(obj, "Constraints", None) or []) if obj is not None else []


class ViewProviderSubdSurface(_EditedInPanel, _ViewProvider):
    """Tree icon of a SubdSurface (a multiresolution Catmull-Clark surface), with its cage and
    target as children (hidden when it is made), a draggable ball on each pin
    (gui.subd_handles.SubdHandles); double click opens its panel (levels, pins, regions)."""

    TYPE = "VarSurf::ViewProviderSubdSurface"
    ICON = "VarSurf_SubdSurface.svg"
    PANEL = ("varsurf.gui.task_subd_surface", "TaskPanelSubdSurface")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit subdivision surface")

    def attach(self, vobj):
        super().attach(vobj)
        if getattr(self, "handles", None) is None:  # FreeCAD attaches again when Proxy is set
            self.handles = SubdHandles(vobj)

    def updateData(self, obj, prop):
        handles = getattr(self, "handles", None)
        if handles is not None and prop in ("PinTargets", "Mesh", "Curves", "CurveMotion"):
            handles.rebuild(obj)

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        return [o for o in (getattr(obj, "Source", None), getattr(obj, "Target", None)) if o is not None]


class ViewProviderSubdBRep(_ViewProvider):
    """Tree icon of a SubdBRep (a SubdSurface's limit surface as B-rep faces), with its
    SubdSurface as child."""

    TYPE = "VarSurf::ViewProviderSubdBRep"
    ICON = "VarSurf_SubdSurface.svg"

    def claimChildren(self):
        base = getattr(getattr(self, "Object", None), "Base", None)
        return [base] if base is not None else []


class ViewProviderTriangularSurface(_EditedInPanel, _ViewProvider):
    """Tree icon of a TriangularSurface (triangular Bezier patches over a mesh), with its mesh as
    child; double click opens its task panel."""

    TYPE = "VarSurf::ViewProviderTriangularSurface"
    ICON = "VarSurf_TriangularSurface.svg"
    PANEL = ("varsurf.gui.task_triangular_surface", "TaskPanelTriangularSurface")

    def claimChildren(self):
        source = getattr(getattr(self, "Object", None), "Source", None)
        return [source] if source is not None else []


class ViewProviderSpaceCurve(_ViewProvider):
    """Tree icon of a variational SpaceCurve, drawn thick so it reads as a handle-driven curve,
    with a draggable pin on each handle (gui.handles.CurveHandles)."""

    TYPE = "VarSurf::ViewProviderSpaceCurve"
    ICON = "VarSurf_SpaceCurve.svg"

    def on_created(self, vobj):
        if hasattr(vobj, "LineWidth"):
            vobj.LineWidth = 4.0
            vobj.LineColor = (0.85, 0.35, 0.0)

    def attach(self, vobj):
        super().attach(vobj)
        if getattr(self, "handles", None) is None:  # FreeCAD attaches again when Proxy is set
            self.handles = CurveHandles(vobj)

    def updateData(self, obj, prop):
        handles = getattr(self, "handles", None)
        if handles is not None and prop in ("Handles", "Shape"):
            handles.rebuild(obj)


class ViewProviderHinge(_EditedInPanel, _ViewProvider):
    """Tree icon of a Hinge (data of its Solid: nothing of its own to draw); its panel edits the
    angle."""

    TYPE = "VarSurf::ViewProviderHinge"
    ICON = "VarSurf_Hinge.svg"
    PANEL = ("varsurf.gui.task_hinge", "TaskPanelHinge")
    EDIT_TEXT = QT_TRANSLATE_NOOP("VarSurf", "Edit hinge")
