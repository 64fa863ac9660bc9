"""The GUI tier: commands, view providers, task panels, handles and overlays (needs FreeCADGui)."""
