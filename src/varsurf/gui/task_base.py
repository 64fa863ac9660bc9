# SPDX-License-Identifier: LGPL-2.1-or-later
"""What every VarSurf task panel does: load its .ui form, open one transaction for the edit,
preview with Update, commit on OK, restore on Cancel (as FreeCAD's own panels do)."""

from __future__ import annotations

import FreeCAD as App
import FreeCADGui as Gui
from PySide import QtGui

from varsurf.gui import resources


class PropertyTaskPanel:
    """Subclasses set UI, ICON, TRANSACTION and EDITABLE (the properties Cancel restores), and
    implement load() (object -> widgets), store() (widgets -> object) and show_results()."""

    UI = ""
    ICON = "VarSurf.svg"
    TRANSACTION = "Edit VarSurf object"
    EDITABLE = ()

    def __init__(self, obj):
        self.obj = obj
        self.doc = obj.Document
        self.form = Gui.PySideUic.loadUi(resources.ui(self.UI))
        self.form.setWindowIcon(QtGui.QIcon(resources.icon(self.ICON)))
        # FreeCAD's combo view starts about 250 px wide: a field that does not fit beside its
        # label goes under it, instead of being cut off at the panel's edge.
        for layout in self.form.findChildren(QtGui.QFormLayout):
            layout.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)
        self._original = {name: getattr(obj, name) for name in self.EDITABLE}
        self.doc.openTransaction(self.TRANSACTION)

    def child(self, kind, name):
        widget = self.form.findChild(kind, name)
        if widget is None:
            raise RuntimeError(f"{self.UI} has no {kind.__name__} named {name}")
        return widget

    def load(self):
        raise NotImplementedError

    def store(self):
        raise NotImplementedError

    def show_results(self):
        pass

    def update(self):
        """Apply the values and recompute, keeping the transaction open (a preview)."""
        self.store()
        self.doc.recompute()
        self.show_results()

    # -- task dialog protocol --
    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        self.store()
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
        if any("Touched" in o.State for o in self.doc.Objects):
            self.doc.recompute()
        Gui.ActiveDocument.resetEdit()
        return True


def translate(context, text):
    """User strings go through FreeCAD's translation (Qt's tr) like FreeCAD's own."""
    return App.Qt.translate(context, text)


def message(text):
    App.Console.PrintError(f"VarSurf: {text}\n")
