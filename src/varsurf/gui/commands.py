"""GUI commands of the VarSurf workbench."""

from __future__ import annotations

import os

import FreeCAD as App
import FreeCADGui as Gui

from varsurf import api
from varsurf.gui import resources

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
        from PySide import QtGui

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
        return api.selection_problem(Gui.Selection.getSelectionEx()) is None

    def Activated(self):
        api.run_sheet_command(
            Gui.Selection.getSelectionEx(), do_command=Gui.doCommand, on_error=show_selection_error
        )


COMMANDS = ["VarSurf_Sheet"]

Gui.addCommand("VarSurf_Sheet", CommandSheet())
