# SPDX-License-Identifier: LGPL-2.1-or-later
"""Registers VarSurf's commands with FreeCAD.

FreeCAD's macro recorder writes ``import <module>`` into a macro for each command run in it, where
<module> is the name of the file that called ``FreeCADGui.addCommand`` (FreeCAD 0.20 reads it from
the caller's frame). The commands are registered from here, a top-level module that imports
without the GUI, so that line of a recorded macro (``import VarSurfGui``) also runs in freecadcmd.
"""


def add_command(name, command):
    """FreeCADGui.addCommand, called from this file (see above)."""
    import FreeCADGui

    FreeCADGui.addCommand(name, command)
