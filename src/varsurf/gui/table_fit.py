# SPDX-License-Identifier: LGPL-2.1-or-later
"""Result tables in the narrow task view: the values keep their whole width, the names give way.

Qt's own Stretch / ResizeToContents header modes left the name column at the width it had when the
panel was laid out, so in FreeCAD's default combo view (a 170 px table) the values were cut off
("0.00446 m"). Here the columns are sized on every resize of the table instead.
"""

from __future__ import annotations

import shiboken2
from PySide import QtCore, QtGui

_MIN_NAME_WIDTH = 24
EMPTY = "—"  # a value a row does not have


class _ColumnFitter(QtCore.QObject):
    def __init__(self, table):
        super().__init__(table)
        self.table = table

    def eventFilter(self, watched, event):
        # The viewport still resizes while its table is being destroyed.
        if event.type() == QtCore.QEvent.Resize and shiboken2.isValid(self.table):
            fit_columns(self.table)
        return False


def keep_values_whole(table):
    """Set ``table`` up so that its last column (the values) is always as wide as its contents and
    the first (the names) takes the rest, elided in the middle; no sideways scrolling. Once per
    table: later calls change nothing."""
    if table.property("varsurfColumnsFit"):
        return
    table.setProperty("varsurfColumnsFit", True)
    header = table.horizontalHeader()
    header.setMinimumSectionSize(_MIN_NAME_WIDTH)
    for column in range(table.columnCount()):
        header.setSectionResizeMode(column, QtGui.QHeaderView.Interactive)
    header.setStretchLastSection(False)
    table.verticalHeader().hide()  # row numbers say nothing and take a name's width
    table.setTextElideMode(QtCore.Qt.ElideMiddle)
    table.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
    table.viewport().installEventFilter(_ColumnFitter(table))


def fit_columns(table):
    """Size the columns to the table's current width (call after changing its rows)."""
    columns = table.columnCount()
    if columns == 0:
        return
    header = table.horizontalHeader()
    widths = [0 if table.isColumnHidden(c) else max(table.sizeHintForColumn(c), header.sectionSizeHint(c))
              for c in range(1, columns)]
    for column, width in enumerate(widths, start=1):
        if width:
            table.setColumnWidth(column, width)
    table.setColumnWidth(0, max(_MIN_NAME_WIDTH, table.viewport().width() - sum(widths)))


def fill(table, rows):
    """Put rows of texts (a name, then values aligned right) into ``table`` and fit its columns."""
    keep_values_whole(table)
    table.setRowCount(len(rows))
    for r, row in enumerate(rows):
        for c, text in enumerate(row):
            item = name_item(text) if c == 0 else QtGui.QTableWidgetItem(text)
            if c > 0:
                item.setTextAlignment(QtCore.Qt.AlignRight | QtCore.Qt.AlignVCenter)
            table.setItem(r, c, item)
    for c in range(1, table.columnCount()):  # a measure no row has (a G0 join's angle) is left out
        table.setColumnHidden(c, bool(rows) and all(len(row) > c and row[c] == EMPTY for row in rows))
    fit_columns(table)


def name_item(text):
    """A table cell for a name that may be elided: its tooltip holds it whole."""
    item = QtGui.QTableWidgetItem(text)
    item.setToolTip(text)
    return item
