# SPDX-License-Identifier: LGPL-2.1-or-later
"""Property names shown whole: when a VarSurf object is selected, the property editor's name
column is widened to its longest property name.

FreeCAD 0.20 opens its property editor with a 100 px name column, which cuts VarSurf's longer
names ("Projection Direction", "Join Curvature Jumps") at the default panel width. The column is
only ever widened, never beyond NAME_SHARE of the editor (the values stay readable), and a column
the user has widened is left alone."""

from __future__ import annotations

import FreeCADGui as Gui
from PySide import QtCore, QtGui

#: The largest share of the property editor's width the name column may take.
NAME_SHARE = 0.65

#: Padding of a name cell beside its text (Qt's item margins and the expand arrow's gap).
PADDING = 12


def _is_varsurf(obj) -> bool:
    return type(getattr(obj, "Proxy", None)).__module__.startswith("varsurf.")


def name_width(editor) -> int:
    """The width the name column needs for every name the editor lists (its groups' members are
    indented one level)."""
    model, metrics = editor.model(), editor.fontMetrics()
    widest = 0
    for group in range(model.rowCount(QtCore.QModelIndex())):
        parent = model.index(group, 0, QtCore.QModelIndex())
        widest = max(widest, metrics.horizontalAdvance(str(model.data(parent))))
        for row in range(model.rowCount(parent)):
            text = str(model.data(model.index(row, 0, parent)))
            widest = max(widest, editor.indentation() + metrics.horizontalAdvance(text))
    return widest + PADDING


def fit(editor) -> None:
    """Widen ``editor``'s name column to its names (see the module's doc)."""
    wanted = min(name_width(editor), int(NAME_SHARE * editor.viewport().width()))
    if editor.columnWidth(0) < wanted:
        editor.setColumnWidth(0, wanted)
        # The value column stretches over the rest, but not below the size it had before the
        # stretch (100 px: a horizontal scroll bar would appear); let it start from its minimum.
        header = editor.header()
        header.resizeSection(1, header.minimumSectionSize())


def _refilled(editor) -> None:
    if any(_is_varsurf(obj) for obj in Gui.Selection.getSelection()):
        fit(editor)


def install() -> None:
    """Fit the names each time a property editor is filled for a selected VarSurf object (FreeCAD
    fills it a moment after the selection changes, inserting its rows: fitted once they are
    in)."""
    window = Gui.getMainWindow()
    if window is None:
        return
    for editor in window.findChildren(QtGui.QTreeView):
        if editor.metaObject().className() != "Gui::PropertyEditor::PropertyEditor":
            continue
        if editor.property("varsurfFitsNames"):
            continue
        editor.setProperty("varsurfFitsNames", True)
        settle = QtCore.QTimer(editor)
        settle.setSingleShot(True)
        settle.setInterval(0)
        settle.timeout.connect(lambda editor=editor: _refilled(editor))
        editor.model().rowsInserted.connect(lambda *_rows, settle=settle: settle.start())
