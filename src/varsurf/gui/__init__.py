# SPDX-License-Identifier: LGPL-2.1-or-later
"""The GUI tier: commands, view providers, task panels, handles and overlays (needs FreeCADGui)."""
