# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the view shows while a sheet is dragged: the solved surface as a Coin mesh sampled on a
grid by the core (varsurf._native.sample_grid), with the Sheet's own shading switched off until the
release. Setting the Sheet's Shape on every move made FreeCAD tessellate a new face each time
(measured on a 64 x 64 pole sheet in the GUI: 15 moves per second with the view redrawn; the
move alone, 24); the grid costs under a millisecond."""

from __future__ import annotations

import numpy
from pivy import coin

from varsurf.solve.native import native

#: Most grid cells per direction (two per span below that).
MAX_CELLS = 96


def _mode_switch(vobj):
    """The view provider's display-mode switch (the first SoSwitch under its root)."""
    root = vobj.RootNode
    for k in range(root.getNumChildren()):
        child = root.getChild(k)
        if child.isOfType(coin.SoSwitch.getClassTypeId()):
            return child
    return None


def styled_root(vobj, ordering):
    """A separator for a preview, in the object's colour, its faces' vertex ordering given."""
    root = coin.SoSeparator()
    material = coin.SoMaterial()
    color = getattr(vobj, "ShapeColor", (0.8, 0.8, 0.8))
    material.diffuseColor.setValue(color[0], color[1], color[2])
    root.addChild(material)
    hints = coin.SoShapeHints()
    hints.vertexOrdering = ordering
    root.addChild(hints)
    return root


def hide_display(vobj):
    """Switch the object's own display off while a preview shows: (switch, what it showed)."""
    switch = _mode_switch(vobj)
    saved = switch.whichChild.getValue() if switch is not None else None
    if switch is not None:
        switch.whichChild = coin.SO_SWITCH_NONE
    return switch, saved


def restore_display(switch, saved):
    if switch is not None:
        switch.whichChild = saved


class DragPreview:
    def __init__(self, vobj, space):
        self.vobj = vobj
        self.cells_u = max(1, min(MAX_CELLS, 2 * (space.nu() - space.degree_u)))
        self.cells_v = max(1, min(MAX_CELLS, 2 * (space.nv() - space.degree_v)))
        self.root = styled_root(vobj, coin.SoShapeHints.UNKNOWN_ORDERING)
        self.coords = coin.SoCoordinate3()
        self.normals = coin.SoNormal()
        binding = coin.SoNormalBinding()
        binding.value = coin.SoNormalBinding.PER_VERTEX_INDEXED
        for node in (self.coords, self.normals, binding):
            self.root.addChild(node)
        faces = coin.SoIndexedFaceSet()
        index = []
        nv = self.cells_v + 1
        for i in range(self.cells_u):
            for j in range(self.cells_v):
                a, b = i * nv + j, (i + 1) * nv + j
                index.extend((a, b, b + 1, -1, a, b + 1, a + 1, -1))
        faces.coordIndex.setValues(0, len(index), index)
        faces.normalIndex.setValues(0, len(index), index)
        self.root.addChild(faces)
        self.switch, self.saved = hide_display(vobj)
        vobj.RootNode.addChild(self.root)
        self.points = None

    def show(self, surface):
        grid = native().sample_grid(surface, self.cells_u, self.cells_v)
        self.points = grid.points
        # Arrays, not lists: in the GUI process (about 100 000 Python objects) the 2 x 9 409 small
        # lists of a 96 x 96 grid set off the garbage collector: 10 ms a move, against 2.4 ms.
        for field, values in ((self.coords.point, grid.points), (self.normals.vector, grid.normals)):
            values = numpy.ascontiguousarray(values, dtype=numpy.float64).reshape(-1, 3)
            field.setValues(0, len(values), values)

    def close(self):
        self.vobj.RootNode.removeChild(self.root)
        restore_display(self.switch, self.saved)
