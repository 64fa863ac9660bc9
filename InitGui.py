# SPDX-License-Identifier: LGPL-2.1-or-later
# VarSurf workbench: GUI initialization.
#
# FreeCAD exec()s this file with separate globals and locals and without __file__ (0.20): names
# defined at the top level here are not visible from class bodies or methods, so everything the
# workbench needs is found or imported inside the class. The Mod folder is found on sys.path.

import FreeCADGui


class VarSurfWorkbench(FreeCADGui.Workbench):
    """Variational B-spline sheets over a base face, constrained by curves."""

    def _find_mod_folder():
        import os
        import sys

        for entry in list(sys.path):
            if not isinstance(entry, str) or not entry:
                continue
            if os.path.isfile(os.path.join(entry, "package.xml")) and os.path.isfile(
                os.path.join(entry, "src", "varsurf", "__init__.py")
            ):
                return os.path.normpath(entry)
        return ""

    def _icon_path(folder):
        import os

        return os.path.join(folder, "Resources", "icons", "VarSurf.svg")

    _folder = _find_mod_folder()
    MenuText = "VarSurf"
    ToolTip = "Variational B-spline surface modeling"
    Icon = _icon_path(_folder)
    _find_mod_folder = staticmethod(_find_mod_folder)
    _icon_path = staticmethod(_icon_path)

    def Initialize(self):
        import os
        import sys

        src = os.path.join(self._folder, "src")
        if self._folder and src not in sys.path:
            sys.path.append(src)
        import varsurf.gui.commands  # registers the commands

        commands = varsurf.gui.commands.COMMANDS
        constraints = varsurf.gui.commands.CONSTRAINTS
        self.appendToolbar("VarSurf", commands)
        analysis = varsurf.gui.commands.ANALYSIS
        # one drop-down button per family of constraint kinds (the menu lists every kind)
        self.appendToolbar("VarSurf constraints", varsurf.gui.commands.CONSTRAINT_TOOLBAR)
        self.appendToolbar("VarSurf analysis", analysis)
        self.appendMenu("&VarSurf", commands)
        self.appendMenu(["&VarSurf", "Constraints"], constraints)
        self.appendMenu(["&VarSurf", "Analysis"], analysis)
        ui = os.path.join(self._folder, "Resources", "ui", "preferences.ui")
        if os.path.isfile(ui):
            # the Preferences dialog shows a group's icon by name: preferences-<group in lower case>
            FreeCADGui.addIconPath(os.path.join(self._folder, "Resources", "icons"))
            FreeCADGui.addPreferencePage(ui, "VarSurf")

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def ContextMenu(self, recipient):
        import varsurf.gui.commands

        self.appendContextMenu("VarSurf", varsurf.gui.commands.COMMANDS + varsurf.gui.commands.CONSTRAINTS)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(VarSurfWorkbench())
