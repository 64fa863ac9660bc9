# SPDX-License-Identifier: LGPL-2.1-or-later
"""A task panel's table of painted regions: one row a region, the painted values first, then its
rectangle (u0, u1, v0, v1 in 0..1); stored in a float-list property, row after row."""

from __future__ import annotations

from PySide import QtCore, QtGui

from varsurf.gui.task_base import translate


class RegionTable:
    """`table` (a QTableWidget of `columns` columns) holding `prop` of an object; `new_row()` gives
    the values of an added row; unreadable cells are reported on `status`."""

    def __init__(self, table, prop, columns, new_row, status):
        self.table, self.prop, self.columns, self.new_row, self.status = table, prop, columns, new_row, status
        # Short numbers a row: the columns share the panel's width (no sideways scrolling),
        # without row numbers or cell padding, so "0.25" fits FreeCAD's default 250 px combo view.
        table.horizontalHeader().setSectionResizeMode(QtGui.QHeaderView.Stretch)
        table.horizontalHeader().setMinimumSectionSize(10)
        table.verticalHeader().setVisible(False)
        table.setTextElideMode(QtCore.Qt.ElideNone)
        table.setWordWrap(False)
        table.setStyleSheet("QTableWidget::item { padding: 0px; }")
        if columns > 5:  # six numbers in the same width: a point smaller, so "0.25" stays whole
            font = table.font()
            font.setPointSizeF(max(font.pointSizeF() - 1.5, 6.0))
            table.setFont(font)
            table.horizontalHeader().setFont(font)

    def append(self, values):
        row = self.table.rowCount()
        self.table.insertRow(row)
        for column, value in enumerate(values):
            self.table.setItem(row, column, QtGui.QTableWidgetItem(f"{value:g}"))

    def add(self):
        self.append(self.new_row())

    def remove(self):
        row = self.table.currentRow()
        self.table.removeRow(row if row >= 0 else self.table.rowCount() - 1)

    def load(self, obj):
        flat = [float(x) for x in getattr(obj, self.prop)]
        self.table.setRowCount(0)
        for start in range(0, len(flat) - len(flat) % self.columns, self.columns):
            self.append(flat[start:start + self.columns])

    def numbers(self):
        """The table's numbers row by row; None (said on the status line) for an unreadable cell."""
        numbers = []
        for row in range(self.table.rowCount()):
            for column in range(self.columns):
                item = self.table.item(row, column)
                try:
                    numbers.append(float(item.text()))
                except (AttributeError, ValueError):
                    self.status.setText(translate("VarSurf", "{}: region {} has a cell that is not a number: "
                                                             "type a number").format(self.prop, row + 1))
                    return None
        return numbers

    def store(self, obj):
        numbers = self.numbers()
        if numbers is not None and numbers != [float(x) for x in getattr(obj, self.prop)]:
            setattr(obj, self.prop, numbers)
