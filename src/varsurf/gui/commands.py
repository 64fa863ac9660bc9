# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI commands of the VarSurf workbench."""

from __future__ import annotations

import os
import tempfile

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtGui
from VarSurfGui import add_command

from varsurf.app import actions, references, selection
from varsurf.app.macro import ref
from varsurf.app.transaction import run_in_transaction
from varsurf.gui import resources
from varsurf.gui.command_tips import explain
from varsurf.solve.analysis import MODES

try:
    from PySide.QtCore import QT_TRANSLATE_NOOP
except ImportError:  # pragma: no cover - FreeCAD always ships the PySide shim

    def QT_TRANSLATE_NOOP(context, text):
        return text


def _dialogs_allowed() -> bool:
    """No modal dialog under tests or scripted runs: they would block."""
    return App.GuiUp and not os.environ.get("VARSURF_NO_DIALOGS")


def show_selection_error(message: str):
    if _dialogs_allowed():
        title = QtGui.QApplication.translate("VarSurf_Sheet", "VarSurf sheet")
        QtGui.QMessageBox.warning(Gui.getMainWindow(), title, message)


class CommandSheet:
    """Create a variational sheet from one selected face and selected edges."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("VarSurf_Sheet.svg"),
            "MenuText": QT_TRANSLATE_NOOP("VarSurf_Sheet", "Variational sheet"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "VarSurf_Sheet",
                "Create a sheet over the selected face that passes through the selected edges.\n"
                "Select one face (the base surface) and any number of edges, then run this command.",
            ),
        }

    def IsActive(self):
        if App.ActiveDocument is None:
            return False
        problem = selection.selection_problem(Gui.Selection.getSelectionEx())
        explain("VarSurf_Sheet", problem)
        return problem is None

    def Activated(self):
        actions.run_sheet_command(
            Gui.Selection.getSelectionEx(), do_command=Gui.doCommand, on_error=show_selection_error
        )


class CommandFromSelection:
    """A command that acts on the current selection: enabled when ``check`` accepts it, runs
    ``run`` (recorded macro lines, one undoable transaction) when activated."""

    def __init__(self, name: str, icon: str, menu_text: str, tool_tip: str, check, run):
        self.name, self.icon, self.menu_text, self.tool_tip = name, icon, menu_text, tool_tip
        self.check, self.run = check, run

    def GetResources(self):
        return {"Pixmap": resources.icon(self.icon), "MenuText": self.menu_text, "ToolTip": self.tool_tip}

    def IsActive(self):
        if App.ActiveDocument is None:
            return False
        try:
            self.check(Gui.Selection.getSelectionEx())
        except ValueError as problem:
            explain(self.name, problem)
            return False
        explain(self.name, None)
        return True

    def Activated(self):
        self.run(Gui.Selection.getSelectionEx(), do_command=Gui.doCommand, on_error=show_selection_error)


# Commands on a selection of sheets and curves: name, icon, menu text, tooltip, selection check,
# what it runs.
SELECTION_COMMANDS = [
    ("VarSurf_Solid", "VarSurf_Solid.svg",
     QT_TRANSLATE_NOOP("VarSurf_Solid", "Join sheets into a solid"),
     QT_TRANSLATE_NOOP(
         "VarSurf_Solid",
         "Join Sheets along the curves they share: each is trimmed to its shared curves and\n"
         "the faces form a shell, a solid when closed. Select two or more Sheets."),
     selection.solid_selection_to_sheets, actions.run_solid_command),
    ("VarSurf_FillHole", "VarSurf_FillHole.svg",
     QT_TRANSLATE_NOOP("VarSurf_FillHole", "Fill hole / replace face"),
     QT_TRANSLATE_NOOP(
         "VarSurf_FillHole",
         "Replace a part's face by a sheet, or fill the hole its free edges bound, G1 to the faces\n"
         "around; the result is the whole part. Select the face (or the free edges) and, optionally,\n"
         "curves inside it."),
     selection.fill_hole_selection_to_args, actions.run_fill_hole_command),
    ("VarSurf_Tube", "VarSurf_Tube.svg",
     QT_TRANSLATE_NOOP("VarSurf_Tube", "Tube through sections"),
     QT_TRANSLATE_NOOP(
         "VarSurf_Tube",
         "A closed sheet through closed sections (sketches of smoothly joined lines and arcs, circles,\n"
         "closed splines), ordered along the tube, and through curves between them. Select two or more\n"
         "sections and, optionally, edges of the curves."),
     selection.tube_selection_to_args, actions.run_tube_command),
    ("VarSurf_PdeSurface", "VarSurf_PdeSurface.svg",
     QT_TRANSLATE_NOOP("VarSurf_PdeSurface", "PDE surface from boundary curves"),
     QT_TRANSLATE_NOOP(
         "VarSurf_PdeSurface",
         "A surface between two boundary curves whose interior solves the Bloor-Wilson PDE (Du & Qin):\n"
         "select the two boundary curves, then optionally a derivative curve beside each (Hermite:\n"
         "the tangent across the boundary points to it), or four edges closing a loop (Coons)."),
     selection.pde_surface_selection_to_args, actions.run_pde_surface_command),
    ("VarSurf_SubdSurface", "VarSurf_SubdSurface.svg",
     QT_TRANSLATE_NOOP("VarSurf_SubdSurface", "Subdivision surface from a cage"),
     QT_TRANSLATE_NOOP(
         "VarSurf_SubdSurface",
         "A multiresolution Catmull-Clark surface (Boier-Martin et al.) of a cage: a Mesh, a shape whose\n"
         "faces make the control mesh, or a VarSurf sheet's poles. Select the cage and, optionally, a Mesh\n"
         "or shape whose detail is captured onto its levels; pins then reshape it and keep the detail."),
     selection.subd_surface_selection_to_args, actions.run_subd_surface_command),
    ("VarSurf_SubdBRep", "VarSurf_SubdSurface.svg",
     QT_TRANSLATE_NOOP("VarSurf_SubdBRep", "Subdivision surface to B-rep"),
     QT_TRANSLATE_NOOP(
         "VarSurf_SubdBRep",
         "The limit surface of a SubdSurface as bicubic B-spline faces sewn into a shell or solid (exact\n"
         "where regular, within a measured deviation at extraordinary vertices). Select one SubdSurface."),
     selection.subd_brep_selection_to_args, actions.run_subd_brep_command),
    ("VarSurf_TriangularSurface", "VarSurf_TriangularSurface.svg",
     QT_TRANSLATE_NOOP("VarSurf_TriangularSurface", "Triangular surface from a mesh"),
     QT_TRANSLATE_NOOP(
         "VarSurf_TriangularSurface",
         "The fairest G1 surface of triangular Bezier patches through a coarse triangle mesh (Veltkamp &\n"
         "Wesselink): one patch per triangle, any topology (N-sided regions, branches, closed shapes of any\n"
         "genus), written exactly as B-spline faces sewn into a shell or solid. Select one Mesh."),
     selection.triangular_selection_to_args, actions.run_triangular_command),
    ("VarSurf_SpaceCurve", "VarSurf_SpaceCurve.svg",
     QT_TRANSLATE_NOOP("VarSurf_SpaceCurve", "Variational space curve"),
     QT_TRANSLATE_NOOP(
         "VarSurf_SpaceCurve",
         "A curve reshaped by handles (both ends and the middle): sheets that pass through it\n"
         "follow it, and in a Solid it is solved with them. Select one edge."),
     selection.space_curve_selection_to_base, actions.run_space_curve_command),
    ("VarSurf_Hinge", "VarSurf_Hinge.svg",
     QT_TRANSLATE_NOOP("VarSurf_Hinge", "Hinge"),
     QT_TRANSLATE_NOOP(
         "VarSurf_Hinge",
         "Hold the angle between two Sheets across the curve they share (180 degrees: smooth).\n"
         "Select two Sheets of a Solid and their shared edge, or the Solid's edge between them."),
     selection.hinge_selection_to_args, actions.run_hinge_command),
]


class CommandConstraint:
    """Add a constraint or operator of one kind to the selected Sheet."""

    def __init__(self, name: str, kind: str, menu_text: str, tool_tip: str):
        self.name = name
        self.kind = kind
        self.menu_text = menu_text
        self.tool_tip = tool_tip

    def GetResources(self):
        return {
            "Pixmap": resources.icon(f"VarSurf_{self.kind}.svg"),
            "MenuText": self.menu_text,
            "ToolTip": self.tool_tip,
        }

    def IsActive(self):
        if App.ActiveDocument is None:
            return False
        try:
            selection.constraint_selection_to_args(self.kind, Gui.Selection.getSelectionEx())
        except ValueError as problem:
            explain(self.name, problem)
            return False
        explain(self.name, None)
        return True

    def Activated(self):
        actions.run_constraint_command(
            self.kind, Gui.Selection.getSelectionEx(), do_command=Gui.doCommand,
            on_error=show_selection_error,
        )


# Command name, kind, menu text, tool tip (what to select).
CONSTRAINT_COMMANDS = [
    ("VarSurf_Point", "Point",
     QT_TRANSLATE_NOOP("VarSurf_Point", "Point constraint"),
     QT_TRANSLATE_NOOP("VarSurf_Point", "The sheet passes through a vertex.\nSelect a Sheet and a vertex.")),
    ("VarSurf_TangentU", "TangentU",
     QT_TRANSLATE_NOOP("VarSurf_TangentU", "Tangent along u"),
     QT_TRANSLATE_NOOP("VarSurf_TangentU", "Prescribe the u derivative at a point.\nSelect a Sheet (and optionally a vertex for the point).")),
    ("VarSurf_TangentV", "TangentV",
     QT_TRANSLATE_NOOP("VarSurf_TangentV", "Tangent along v"),
     QT_TRANSLATE_NOOP("VarSurf_TangentV", "Prescribe the v derivative at a point.\nSelect a Sheet (and optionally a vertex for the point).")),
    ("VarSurf_Normal", "Normal",
     QT_TRANSLATE_NOOP("VarSurf_Normal", "Normal constraint"),
     QT_TRANSLATE_NOOP("VarSurf_Normal", "Prescribe the surface normal at a point.\nSelect a Sheet (and optionally a vertex for the point).")),
    ("VarSurf_PointInPlane", "PointInPlane",
     QT_TRANSLATE_NOOP("VarSurf_PointInPlane", "Point in plane"),
     QT_TRANSLATE_NOOP("VarSurf_PointInPlane", "Keep a point of the sheet in a plane.\nSelect a Sheet (and optionally a vertex for the point).")),
    ("VarSurf_PointOnLine", "PointOnLine",
     QT_TRANSLATE_NOOP("VarSurf_PointOnLine", "Point on line"),
     QT_TRANSLATE_NOOP("VarSurf_PointOnLine", "Keep a point of the sheet on a line.\nSelect a Sheet (and optionally a vertex for the point).")),
    ("VarSurf_Curvature", "Curvature",
     QT_TRANSLATE_NOOP("VarSurf_Curvature", "Curvature at a point"),
     QT_TRANSLATE_NOOP("VarSurf_Curvature", "Prescribe the sheet's normal curvatures along u and v at a point (1 / radius;\n"
                       "they start as the sheet's own). Select a Sheet (and optionally a vertex for the point).")),
    ("VarSurf_PointAttractor", "PointAttractor",
     QT_TRANSLATE_NOOP("VarSurf_PointAttractor", "Point attractor"),
     QT_TRANSLATE_NOOP("VarSurf_PointAttractor", "Pull a region of the sheet toward a point.\nSelect a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.")),
    ("VarSurf_PlaneAttractor", "PlaneAttractor",
     QT_TRANSLATE_NOOP("VarSurf_PlaneAttractor", "Plane attractor"),
     QT_TRANSLATE_NOOP("VarSurf_PlaneAttractor", "Pull a region of the sheet onto a plane.\nSelect a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.")),
    ("VarSurf_LineAttractor", "LineAttractor",
     QT_TRANSLATE_NOOP("VarSurf_LineAttractor", "Line attractor"),
     QT_TRANSLATE_NOOP("VarSurf_LineAttractor", "Pull a region of the sheet onto a line.\nSelect a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.")),
    ("VarSurf_Director", "Director",
     QT_TRANSLATE_NOOP("VarSurf_Director", "Director"),
     QT_TRANSLATE_NOOP("VarSurf_Director", "Push the normals of a region toward a direction.\nSelect a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.")),
    ("VarSurf_Repeller", "Repeller",
     QT_TRANSLATE_NOOP("VarSurf_Repeller", "Repeller"),
     QT_TRANSLATE_NOOP("VarSurf_Repeller", "Push a region of the sheet away from a point.\nSelect a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.")),
    ("VarSurf_Ribbon", "Ribbon",
     QT_TRANSLATE_NOOP("VarSurf_Ribbon", "Ribbon"),
     QT_TRANSLATE_NOOP("VarSurf_Ribbon", "Along an edge, the sheet's normal follows a face's normal, the strip toward a second edge,\nor (with neither) its own base's normal, turned by an angle.\nSelect a Sheet, an edge and, optionally, a face or a second edge.")),
    ("VarSurf_G0", "G0",
     QT_TRANSLATE_NOOP("VarSurf_G0", "G0 join"),
     QT_TRANSLATE_NOOP("VarSurf_G0", "The sheet contains an edge: position continuity with the face it bounds.\nSelect a Sheet and the shared edge.")),
    ("VarSurf_G1", "G1",
     QT_TRANSLATE_NOOP("VarSurf_G1", "G1 join"),
     QT_TRANSLATE_NOOP("VarSurf_G1", "The sheet contains an edge and joins a face there tangent-continuously.\nSelect a Sheet, the shared edge and the neighbouring face.")),
    ("VarSurf_G2", "G2",
     QT_TRANSLATE_NOOP("VarSurf_G2", "G2 join"),
     QT_TRANSLATE_NOOP("VarSurf_G2", "The sheet contains an edge and joins a face there curvature-continuously (iterated).\nSelect a Sheet (degree 3 or more), the shared edge and the neighbouring face.")),
    ("VarSurf_CurveMap", "CurveMap",
     QT_TRANSLATE_NOOP("VarSurf_CurveMap", "Curve map"),
     QT_TRANSLATE_NOOP("VarSurf_CurveMap", "Map a source curve on the sheet onto a destination curve, point for point.\n"
                       "Select a Sheet, then the source edge and then the destination edge.")),
    ("VarSurf_RegionMap", "RegionMap",
     QT_TRANSLATE_NOOP("VarSurf_RegionMap", "Region map"),
     QT_TRANSLATE_NOOP("VarSurf_RegionMap", "Map a rectangle of the sheet's (u, v) onto a destination face, point for point.\n"
                       "Select a Sheet and the destination face.")),
    ("VarSurf_SurfaceAttractor", "SurfaceAttractor",
     QT_TRANSLATE_NOOP("VarSurf_SurfaceAttractor", "Surface attractor"),
     QT_TRANSLATE_NOOP("VarSurf_SurfaceAttractor", "Pull a region of the sheet onto another face.\nSelect a Sheet, the face and, optionally, closed edges bounding the region.")),
    ("VarSurf_CurveAttractor", "CurveAttractor",
     QT_TRANSLATE_NOOP("VarSurf_CurveAttractor", "Curve attractor"),
     QT_TRANSLATE_NOOP("VarSurf_CurveAttractor", "Pull a region of the sheet onto an edge.\nSelect a Sheet and the edge.")),
    ("VarSurf_FrozenRegion", "FrozenRegion",
     QT_TRANSLATE_NOOP("VarSurf_FrozenRegion", "Frozen region"),
     QT_TRANSLATE_NOOP("VarSurf_FrozenRegion", "Keep a region of the sheet as the base shape.\nSelect a Sheet and, optionally, closed edges (e.g. a sketch) bounding the region.")),
]


def _selected_sheets():
    return [s.Object for s in Gui.Selection.getSelectionEx() if references.is_sheet(s.Object)]


class CommandColorMap:
    """Switch the selected Sheets' color map to the next analysis (view property Analysis)."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("VarSurf_ColorMap.svg"),
            "MenuText": QT_TRANSLATE_NOOP("VarSurf_ColorMap", "Color map"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "VarSurf_ColorMap",
                "Show the next color map on the selected sheets: deviation from the base (or installed rest\n"
                "shape), mean curvature, Gaussian curvature, zebra stripes, none. Select one or more Sheets.\n"
                "The range of the colors is the view property AnalysisRange.",
            ),
        }

    def IsActive(self):
        return bool(_selected_sheets())

    def Activated(self):
        for sheet in _selected_sheets():
            mode = str(getattr(sheet.ViewObject, "Analysis", "None"))
            following = MODES[(MODES.index(mode) + 1) % len(MODES)] if mode in MODES else MODES[0]
            Gui.doCommandGui(f"{ref(sheet)}.ViewObject.Analysis = {following!r}")


class CommandLCurve:
    """Plot the L-curve of the selected Sheet's TSVD/MTSVD solve."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("VarSurf_LCurve.svg"),
            "MenuText": QT_TRANSLATE_NOOP("VarSurf_LCurve", "L-curve"),
            "ToolTip": QT_TRANSLATE_NOOP(
                "VarSurf_LCurve",
                "Plot the L-curve of the selected sheet's truncated SVD solve, its chosen corner marked.\n"
                "Select one Sheet solved in TSVD or MTSVD mode.",
            ),
        }

    def IsActive(self):
        sheets = _selected_sheets()
        return len(sheets) == 1 and bool(sheets[0].LCurveResiduals)

    def Activated(self):
        sheet = _selected_sheets()[0]
        path = os.path.join(tempfile.gettempdir(), f"varsurf-lcurve-{sheet.Document.Name}-{sheet.Name}.png")
        Gui.doCommand("import varsurf.app.analysis")
        Gui.doCommand(f"varsurf.app.analysis.plot_lcurve({ref(sheet)}, {path!r})")
        App.Console.PrintMessage(
            App.Qt.translate("VarSurf_LCurve", "VarSurf: L-curve of {} written to {}").format(sheet.Label, path) + "\n")
        if _dialogs_allowed():
            dialog = QtGui.QDialog(Gui.getMainWindow())
            dialog.setWindowTitle(QtGui.QApplication.translate("VarSurf_LCurve", "L-curve"))
            layout = QtGui.QVBoxLayout(dialog)
            label = QtGui.QLabel(dialog)
            label.setPixmap(QtGui.QPixmap(path))
            layout.addWidget(label)
            dialog.show()


class CommandRestShape:
    """Install the selected Sheets' results as their rest shapes, or melt them (api functions)."""

    def __init__(self, function, icon, menu_text, tool_tip):
        self.function, self.icon, self.menu_text, self.tool_tip = function, icon, menu_text, tool_tip

    def GetResources(self):
        return {"Pixmap": resources.icon(self.icon), "MenuText": self.menu_text, "ToolTip": self.tool_tip}

    def IsActive(self):
        return bool(_selected_sheets())

    def Activated(self):
        sheets = _selected_sheets()
        doc = sheets[0].Document
        lines = ["import varsurf"] + [f"varsurf.{self.function}({ref(s)})" for s in sheets]
        lines.append(f"App.getDocument({doc.Name!r}).recompute()")
        try:
            run_in_transaction(doc, f"VarSurf {self.function.replace('_', ' ')}", lines, Gui.doCommand)
        except ValueError as error:
            show_selection_error(str(error))


REST_COMMANDS = [
    ("VarSurf_InstallRest", "install_rest_shape", "VarSurf_InstallRest.svg",
     QT_TRANSLATE_NOOP("VarSurf_InstallRest", "Install rest shape"),
     QT_TRANSLATE_NOOP("VarSurf_InstallRest", "Make the selected sheets' current results their rest shapes: later edits\n"
                       "keep this shape's detail (the energy acts on the displacement). Select one or more Sheets.")),
    ("VarSurf_Melt", "melt", "VarSurf_Melt.svg",
     QT_TRANSLATE_NOOP("VarSurf_Melt", "Melt"),
     QT_TRANSLATE_NOOP("VarSurf_Melt", "Forget the selected sheets' rest shapes: they become as fair as their constraints\n"
                       "allow. Select one or more Sheets.")),
]

COMMANDS = ["VarSurf_Sheet"] + [row[0] for row in SELECTION_COMMANDS] + [row[0] for row in REST_COMMANDS]
ANALYSIS = ["VarSurf_ColorMap", "VarSurf_LCurve"]
CONSTRAINTS = [name for name, _kind, _menu, _tip in CONSTRAINT_COMMANDS]

# The constraint kinds by family, one drop-down button each on the toolbar (17 buttons overflowed
# a 1600 px window); the menu lists them all. Group name, its menu text and tooltip, members.
CONSTRAINT_GROUPS = [
    ("VarSurf_PointConstraints", QT_TRANSLATE_NOOP("VarSurf_PointConstraints", "Point constraints"),
     QT_TRANSLATE_NOOP("VarSurf_PointConstraints", "Constraints at a point of the sheet: position, tangents, normal,\n"
                       "in a plane, on a line, curvature"),
     ["VarSurf_Point", "VarSurf_TangentU", "VarSurf_TangentV", "VarSurf_Normal", "VarSurf_PointInPlane",
      "VarSurf_PointOnLine", "VarSurf_Curvature"]),
    ("VarSurf_CurveJoins", QT_TRANSLATE_NOOP("VarSurf_CurveJoins", "Joins along curves"),
     QT_TRANSLATE_NOOP("VarSurf_CurveJoins", "Joins along an edge: G0, G1, G2 to a neighbouring face, a ribbon, or a curve mapped\n"
                       "onto another"),
     ["VarSurf_G1", "VarSurf_G0", "VarSurf_G2", "VarSurf_Ribbon", "VarSurf_CurveMap"]),
    ("VarSurf_Operators", QT_TRANSLATE_NOOP("VarSurf_Operators", "Shape operators"),
     QT_TRANSLATE_NOOP("VarSurf_Operators", "Operators on a region of the sheet: attractors to a point, plane, line,\n"
                       "face or edge, a repeller, a director, a frozen region, a region mapped onto a face"),
     ["VarSurf_PointAttractor", "VarSurf_PlaneAttractor", "VarSurf_LineAttractor", "VarSurf_SurfaceAttractor",
      "VarSurf_CurveAttractor", "VarSurf_Repeller", "VarSurf_Director", "VarSurf_FrozenRegion", "VarSurf_RegionMap"]),
]
CONSTRAINT_TOOLBAR = [name for name, *_rest in CONSTRAINT_GROUPS]


class CommandGroup:
    """A drop-down toolbar button of several commands (FreeCAD's Python command group): it shows
    the last one used; each member keeps its own icon, tooltip and greyed-out state."""

    def __init__(self, menu_text: str, tool_tip: str, members):
        self.menu_text, self.tool_tip, self.members = menu_text, tool_tip, tuple(members)

    def GetCommands(self):
        return self.members

    def GetDefaultCommand(self):
        return 0

    def GetResources(self):
        return {"MenuText": self.menu_text, "ToolTip": self.tool_tip}

    def IsActive(self):
        return App.ActiveDocument is not None


add_command("VarSurf_Sheet", CommandSheet())
add_command("VarSurf_ColorMap", CommandColorMap())
for _name, *_rest in REST_COMMANDS:
    add_command(_name, CommandRestShape(*_rest))
add_command("VarSurf_LCurve", CommandLCurve())
for _name, *_resources in SELECTION_COMMANDS:
    add_command(_name, CommandFromSelection(_name, *_resources))
for _name, _kind, _menu, _tip in CONSTRAINT_COMMANDS:
    add_command(_name, CommandConstraint(_name, _kind, _menu, _tip))
for _name, _menu, _tip, _members in CONSTRAINT_GROUPS:
    add_command(_name, CommandGroup(_menu, _tip, _members))
