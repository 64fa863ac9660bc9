# SPDX-License-Identifier: LGPL-2.1-or-later
"""A SubdSurface's pin dragged (Boier-Martin et al. 4.3): each move the approximate answer, the
pins' masks moved by least norm and the rest by the Catmull-Clark rules, edited from the captured
levels the last recompute kept (no capture, no topology work: milliseconds on 10,000 faces); the
release writes the target in one undoable step and the recompute refines it with the feature's
Solve."""

from __future__ import annotations

import FreeCAD
import numpy as np

from varsurf.app.drag import DragError
from varsurf.app.feature import last_outcome
from varsurf.app.macro import ref
from varsurf.app.subd_surface import (compute, curve_edges, curves_of, is_subd_surface, normals_of, pins_of,
                                      placement_matrix)
from varsurf.app.transaction import run_in_transaction
from varsurf.solve import multiresolution
from varsurf.solve.errors import SheetError

TRANSACTION = "Drag VarSurf subdivision pin"
CURVE_TRANSACTION = "Turn VarSurf subdivision curves"


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
            # The Curves hold their vertices while the pin moves (their chains found once).
            self.curves = curves_of(subd)
            self.chained = multiresolution.curve_vertices(self.outcome.editor, self.outcome.captured, self.curves,
                                                          self.pins) if self.curves else None
        except SheetError as error:
            raise DragError(f"{subd.Label}: {error}") from error
        self.subd, self.index = subd, int(index)

    def move(self, target):
        """The limit surface's points with the pin at `target` (the approximate solve)."""
        pins = list(self.pins)
        p = pins[self.index]
        pins[self.index] = multiresolution.Pin(p.level, p.vertex, (target.x, target.y, target.z), p.influence)
        return multiresolution.edited_limit(self.outcome, pins, normals=self.normals, curves=self.chained,
                                            curve_matrix=self.curves.matrix if self.curves else None)

    def finish(self, target, do_command=None):
        """Write the target (one undoable step, recorded through do_command) and recompute."""
        t = FreeCAD.Vector(target)
        lines = ["import varsurf",
                 f"varsurf.move_pin({ref(self.subd)}, {self.index}, App.Vector({t.x!r}, {t.y!r}, {t.z!r}))",
                 f"App.getDocument({self.subd.Document.Name!r}).recompute()"]
        run_in_transaction(self.subd.Document, TRANSACTION, lines, do_command)


class CurveDrag:
    """The Curves of a SubdSurface turned and moved as one (their arcball, Boier-Martin et al.'s
    Fig. 9): move(placement) gives the limit points to draw with `placement` applied after the
    CurveMotion the drag started from (the approximate solve on the captured levels);
    finish(placement) writes the composed CurveMotion in one undoable step."""

    def __init__(self, subd):
        if not is_subd_surface(subd):
            raise DragError(f"{subd.Label} is not a SubdSurface")
        try:
            self.curves = curves_of(subd)
            self.pins, self.normals = pins_of(subd), normals_of(subd)
            self.outcome = last_outcome(subd, compute)
        except SheetError as error:
            raise DragError(f"{subd.Label}: {error}") from error
        if self.curves is None:
            raise DragError(f"{subd.Label} has no Curves or CurveLoops: link edges lying on it, or list "
                            "boundary loops, first")
        try:  # the chains once: a move only turns their vertices
            self.chained = multiresolution.curve_vertices(self.outcome.editor, self.outcome.captured, self.curves,
                                                          self.pins)
        except SheetError as error:
            raise DragError(f"{subd.Label}: {error}") from error
        self.subd, self.start = subd, FreeCAD.Placement(subd.CurveMotion)

    def motion(self, placement):
        return FreeCAD.Placement(placement).multiply(self.start)

    def move(self, placement):
        """The limit surface's points with the curves moved by `placement` after their motion."""
        try:
            return multiresolution.edited_limit(self.outcome, self.pins, normals=self.normals, curves=self.chained,
                                                curve_matrix=placement_matrix(self.motion(placement)))
        except SheetError as error:
            raise DragError(f"{self.subd.Label}: {error}") from error

    def finish(self, placement, do_command=None):
        """Write the composed CurveMotion (one undoable step, recorded through do_command)."""
        p = self.motion(placement)
        q = p.Rotation.Q
        lines = [f"{ref(self.subd)}.CurveMotion = App.Placement(App.Vector({p.Base.x!r}, {p.Base.y!r}, {p.Base.z!r}), "
                 f"App.Rotation({q[0]!r}, {q[1]!r}, {q[2]!r}, {q[3]!r}))",
                 f"App.getDocument({self.subd.Document.Name!r}).recompute()"]
        run_in_transaction(self.subd.Document, CURVE_TRANSACTION, lines, do_command)


def curves_centre(subd):
    """Where the arcball of a SubdSurface's Curves and CurveLoops stands: the centre of their box
    where CurveMotion puts them (the loops' vertices as the last recompute moved them), or None
    without either."""
    motion = subd.CurveMotion.toMatrix()
    boxes = [edge.BoundBox.transformed(motion) for edge in curve_edges(subd, strict=False)]
    outcome = getattr(getattr(subd, "Proxy", None), "outcome", None)
    if outcome is not None:
        finest = np.asarray(outcome.levels[-1], float)
        for loop in getattr(subd, "CurveLoops", ()):
            try:
                vertices = multiresolution.loop_vertices(outcome.editor, len(outcome.levels) - 1, loop)
            except SheetError:  # a loop the cage lacks: the recompute names it
                continue
            boxes.append(FreeCAD.BoundBox(*finest[vertices].min(axis=0), *finest[vertices].max(axis=0)))
    if not boxes:
        return None
    box = boxes[0]
    for other in boxes[1:]:
        box.add(other)
    return box.Center
