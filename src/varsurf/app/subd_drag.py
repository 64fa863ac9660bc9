# SPDX-License-Identifier: LGPL-2.1-or-later
"""A SubdSurface's pin dragged (Boier-Martin et al. 4.3): each move the approximate answer, the
pins' masks moved by least norm and the rest by the Catmull-Clark rules, edited from the captured
levels the last recompute kept (no capture, no topology work: milliseconds on 10,000 faces); the
release writes the target in one undoable step and the recompute refines it with the feature's
Solve."""

from __future__ import annotations

import FreeCAD

from varsurf.app.drag import DragError
from varsurf.app.feature import last_outcome
from varsurf.app.macro import ref
from varsurf.app.subd_surface import compute, is_subd_surface, normals_of, pins_of
from varsurf.app.transaction import run_in_transaction
from varsurf.solve import multiresolution
from varsurf.solve.errors import SheetError

TRANSACTION = "Drag VarSurf subdivision pin"


class PinDrag:
    """One drag of pin `index` of a SubdSurface: move(target) gives the limit points to draw,
    finish(target) writes the target."""

    def __init__(self, subd, index):
        if not is_subd_surface(subd):
            raise DragError(f"{subd.Label} is not a SubdSurface")
        if not 0 <= int(index) < len(subd.PinTargets):
            raise DragError(f"{subd.Label} has {len(subd.PinTargets)} pins, no pin {index}")
        try:
            self.pins = pins_of(subd)
            self.normals = normals_of(subd)
            self.outcome = last_outcome(subd, compute)
        except SheetError as error:
            raise DragError(f"{subd.Label}: {error}") from error
        self.subd, self.index = subd, int(index)

    def move(self, target):
        """The limit surface's points with the pin at `target` (the approximate solve)."""
        pins = list(self.pins)
        p = pins[self.index]
        pins[self.index] = multiresolution.Pin(p.level, p.vertex, (target.x, target.y, target.z), p.influence)
        return multiresolution.edited_limit(self.outcome, pins, normals=self.normals)

    def finish(self, target, do_command=None):
        """Write the target (one undoable step, recorded through do_command) and recompute."""
        t = FreeCAD.Vector(target)
        lines = ["import varsurf",
                 f"varsurf.move_pin({ref(self.subd)}, {self.index}, App.Vector({t.x!r}, {t.y!r}, {t.z!r}))",
                 f"App.getDocument({self.subd.Document.Name!r}).recompute()"]
        run_in_transaction(self.subd.Document, TRANSACTION, lines, do_command)
