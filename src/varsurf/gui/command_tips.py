# SPDX-License-Identifier: LGPL-2.1-or-later
"""Why a command is greyed out, said in its tooltip and status tip: a command is enabled only when
the selection fits, and a disabled button alone does not say what to select."""

from __future__ import annotations

import html

import FreeCADGui as Gui
from PySide import QtGui

_plain = {}  # command name -> its own tooltip, as FreeCAD made it


def explain(name: str, problem):
    """Show ``problem`` (None: the selection fits) under the tooltip of the command ``name``."""
    command = Gui.Command.get(name)
    if command is None:
        return
    for action in command.getAction():
        plain = _plain.setdefault(name, action.toolTip())
        if problem is None:
            tip, status = plain, ""
        else:
            heading = QtGui.QApplication.translate("VarSurf", "Not available now:")
            tip = f"{plain}<p><b>{heading}</b> {html.escape(str(problem))}</p>"
            status = f"{heading} {problem}"
        if action.toolTip() != tip:
            action.setToolTip(tip)
            action.setStatusTip(status)
