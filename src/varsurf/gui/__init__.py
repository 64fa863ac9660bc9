"""GUI side of VarSurf: commands, view providers and task panels (needs FreeCADGui)."""
