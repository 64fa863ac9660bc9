# SPDX-License-Identifier: LGPL-2.1-or-later
"""The App tier: document features, make-functions, selections, macro lines, transactions,
drags, progress, preferences and persistence. Needs FreeCAD but not its GUI (imports varsurf.gui
only under ``if FreeCAD.GuiUp:``, for the view providers of new objects)."""
