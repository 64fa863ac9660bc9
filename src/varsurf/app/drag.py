# SPDX-License-Identifier: LGPL-2.1-or-later
"""Dragging the target of a Sheet's Point constraint, with the Sheet re-solved as it moves
(Welch & Witkin sec. 1: direct manipulation).

The Sheet's last solve is prepared once (native ``PreparedSheet``: the constraints reduced and the
system factored); each move changes only the target, so it costs a back-substitution, and the
Sheet's Shape shows the result at once. Finishing writes the target into the document (the
Location's vertex, or the constraint's Origin) and recomputes, all in one transaction: one undo
puts the target and the sheet back. Cancelling restores the Sheet's shape and writes nothing.
App side only (the view provider's dragger calls it).
"""

from __future__ import annotations

import copy
import math
import time

import FreeCAD
import Part

from varsurf.app import pde_surface as pde_feature
from varsurf.app import references
from varsurf.app import sheet as sheet_feature
from varsurf.app import space_curve as space_curve_feature
from varsurf.app.macro import exec_line, ref
from varsurf.solve.errors import SheetError
from varsurf.solve.native import build, native
from varsurf.solve.shapes import shape_from_binary, single_face

TRANSACTION = "Drag VarSurf point"
#: A target this far (relative to the sheet's size) from the prepared one is not this constraint.
_SAME_TARGET = 1e-9


def _target_lines(constraint, t):
    """Macro lines that write a Point's dragged target (set_point_target)."""
    return ["import varsurf.app.drag",
            f"varsurf.app.drag.set_point_target({ref(constraint)}, App.Vector({t.x!r}, {t.y!r}, {t.z!r}))"]


def _finish(doc, lines, do_command=None):
    """Run a drag's closing lines and a recompute inside its open transaction, then commit it
    (abort on failure)."""
    run = do_command or exec_line
    try:
        for line in lines + [f"App.getDocument({doc.Name!r}).recompute()"]:
            run(line)
    except Exception:
        doc.abortTransaction()
        raise
    doc.commitTransaction()


class DragError(ValueError):
    """The constraint cannot be dragged (the message says why)."""


class NotQuadratic(DragError):
    """The sheet has iterated terms (repellers, shape attractors, pressure): no kept
    factorization; drag its target with a TargetDrag (recomputes) instead."""


def point_target(constraint):
    """The constraint's target now: its Location's vertex, or its Origin."""
    if constraint.Location is not None and not constraint.UseOrigin:
        link, subs = constraint.Location
        subs = [s for s in subs if s]
        shape = Part.getShape(link, subs[0], needSubElement=True) if subs else link.Shape
        if shape.isNull() or not shape.Vertexes:
            raise DragError(f"{constraint.Label}: its Location is not a vertex")
        return FreeCAD.Vector(shape.Vertexes[0].Point)
    return FreeCAD.Vector(constraint.Origin)


def set_point_target(constraint, target):
    """Write a dragged target into the document: into the linked vertex when it is a point object
    with X, Y, Z (Part Vertex, Draft Point) placed without rotation, else into Origin (the
    constraint then uses its Origin)."""
    target = FreeCAD.Vector(target)
    link = constraint.Location[0] if constraint.Location is not None else None
    if link is not None and not constraint.UseOrigin and all(hasattr(link, a) for a in "XYZ"):
        placement = link.Placement
        if placement.Rotation.isNull() or placement.Rotation.Angle < 1e-12:
            local = target - placement.Base
            link.X, link.Y, link.Z = local.x, local.y, local.z
            return
    constraint.Origin = target
    if link is not None:
        constraint.UseOrigin = True


def _point_index(sheet, constraint):
    points = [c for c in (sheet.Constraints or []) if c.Enabled and c.Kind == "Point"]
    if constraint not in points:
        raise DragError(f"{constraint.Label} is not an enabled Point constraint of {sheet.Label}")
    return points.index(constraint)


class WrittenOnRelease:
    """A drag that shows the moved sheet without writing anything until the release: ``finish``
    writes the Point's target, ``cancel`` puts the shape back. Subclasses set sheet, constraint,
    doc and start_shape, and open the TRANSACTION."""

    def finish(self, target, do_command=None):
        """Write the target and recompute: one undoable step. do_command (FreeCADGui.doCommand in
        the GUI) runs the macro lines that do it, so a macro records the drag's outcome."""
        _finish(self.doc, _target_lines(self.constraint, FreeCAD.Vector(target)), do_command)
        if not self.sheet.isValid():
            raise SheetError(f"{self.sheet.Label}: {self.sheet.Status}")

    def cancel(self):
        """Put the Sheet's shape back; nothing is written."""
        self.sheet.Shape = self.start_shape
        self.doc.abortTransaction()
        self.sheet.purgeTouched()


class PointDrag(WrittenOnRelease):
    """One drag of a Point constraint's target: ``move`` as often as the pointer moves, then
    ``finish`` or ``cancel``."""

    def __init__(self, sheet, constraint):
        self.sheet, self.constraint, self.doc = sheet, constraint, sheet.Document
        if not sheet.isValid():
            raise DragError(f"{sheet.Label} is in error: fix it before dragging")
        if references.is_sheet(sheet):
            outcome = sheet_feature.outcome_of(sheet)
        elif pde_feature.is_pde_surface(sheet):  # its last round's problem: boundary rows held
            outcome = pde_feature.outcome_of(sheet)
        else:
            raise NotQuadratic(f"{sheet.Label} is neither a Sheet nor a PdeSurface: it is dragged by recomputing")
        self.problem = copy.copy(outcome.problem)
        self.index = _point_index(sheet, constraint)
        points = list(self.problem.points)
        if self.index >= len(points):
            raise DragError(f"{constraint.Label} is not among {sheet.Label}'s solved points")
        start = FreeCAD.Vector(*points[self.index].target)
        size = max(sheet.Shape.BoundBox.DiagonalLength, 1.0)
        if (start - point_target(constraint)).Length > _SAME_TARGET * size + 1e-12:
            raise DragError(f"{sheet.Label} is not up to date with {constraint.Label}: recompute first")
        self.start = start
        self.start_shape = sheet.Shape.copy()
        nat = native()
        try:
            self.prepared = nat.PreparedSheet(self.problem, outcome.options)
        except nat.InvalidInput as error:
            raise NotQuadratic(f"{sheet.Label} cannot be dragged by back-substitution: {error}") from error
        self.space = self.problem.space
        self.surface_of = getattr(outcome, "surface_of", None)  # a PdeSurface's own (seam tied)
        self.trim = outcome.trim  # the base face's trim: a dragged sheet stays bounded like its base
        #: The sheet covers its whole parameter rectangle, so a view may draw the solved surface
        #: itself; else (a hole, a disc, a chamfered outline) only the Shape shows it bounded.
        self.natural = self.trim is None or bool(self.trim.natural)
        self.last = None  # the last native SolveResult
        self.moves = 0
        self.seconds = 0.0  # spent in move(): solve and shape
        self.doc.openTransaction(TRANSACTION)

    def move(self, target, update_shape=True):
        """Re-solve for the target at `target` (a vector); returns the solved native surface. With
        update_shape the Sheet's Shape shows it, bounded like its base face (a view may draw the
        surface itself instead when the sheet is `natural`)."""
        target = FreeCAD.Vector(target)
        if not all(math.isfinite(c) for c in target):
            raise DragError("the dragged target is not finite")
        began = time.perf_counter()
        nat = native()
        points = list(self.problem.points)
        old = points[self.index]
        points[self.index] = nat.PointConstraint(u=old.u, v=old.v, target=[target.x, target.y, target.z],
                                                 weight=old.weight)
        self.problem.points = points
        try:
            self.last = self.prepared.update(self.problem)
        except (nat.InvalidInput, nat.SolveFailure) as error:
            raise DragError(f"{self.sheet.Label}: {error}") from error
        surface = (self.surface_of(self.last.poles) if self.surface_of is not None
                   else build(nat.BSplineSurface, space=self.space, poles=self.last.poles))
        if update_shape:
            try:  # bounded and oriented like the base face, as the Sheet's own result
                data = self.trim.face_binary(surface) if self.trim is not None else nat.face_binary(surface)
            except (nat.InvalidInput, nat.GeometryError) as error:
                raise DragError(f"{self.sheet.Label}: the dragged sheet cannot be bounded like its base "
                                f"face: {error}") from error
            self.sheet.Shape = single_face(shape_from_binary(data))
        self.moves += 1
        self.seconds += time.perf_counter() - began
        return surface


HANDLE_TRANSACTION = "Drag VarSurf handle"
#: While a handle moves, the curve follows every move; the sheets joined to it are solved again
#: whenever at least this many times their last recompute has passed since it ended, so slow joint
#: solves still follow, less often, and the pointer never waits more than one of them.
FOLLOW_SPACING = 1.0


class RecomputeDrag:
    """A drag that writes a property on every move and lets the document recompute, as often as
    that takes (FOLLOW_SPACING); the release recomputes exactly and is one undoable step.
    Subclasses set TRANSACTION and implement _place(target) and _preview() (the cheap update
    between full recomputes)."""

    TRANSACTION = "Drag VarSurf handle"

    def __init__(self, doc, start):
        self.doc, self.start = doc, FreeCAD.Vector(start)
        self.next_follow = 0.0  # perf_counter time after which the next move recomputes all
        self.moves = 0
        self.live_solves = 0
        self.doc.openTransaction(self.TRANSACTION)

    def _checked(self, target):
        target = FreeCAD.Vector(target)
        if not all(math.isfinite(c) for c in target):
            raise DragError("the dragged handle is not finite")
        return target

    def _place(self, target):
        raise NotImplementedError

    def _preview(self):
        pass

    def move(self, target):
        self._place(self._checked(target))
        self.moves += 1
        began = time.perf_counter()
        if began >= self.next_follow:
            self.doc.recompute()
            self.live_solves += 1
            ended = time.perf_counter()
            self.next_follow = ended + FOLLOW_SPACING * (ended - began)
        else:
            self._preview()

    def finish(self, target, do_command=None):
        """Place the target and recompute: one undoable step, through macro lines when
        do_command is given (FreeCADGui.doCommand records them)."""
        _finish(self.doc, self._lines(self._checked(target)), do_command)

    def _lines(self, target):
        raise NotImplementedError

    def cancel(self):
        self._place(self.start)
        self.doc.recompute()
        self.doc.abortTransaction()


class HandleDrag(RecomputeDrag):
    """One drag of a variational SpaceCurve's handle. Each move re-solves the curve; the solids
    joined to it follow as often as their recompute allows (FOLLOW_SPACING), and exactly at the
    release. ``finish`` is one undoable step."""

    TRANSACTION = HANDLE_TRANSACTION

    def __init__(self, curve, index):
        if not space_curve_feature.is_space_curve(curve):
            raise DragError(f"{curve.Label} is not a SpaceCurve")
        if not 0 <= int(index) < len(curve.Handles):
            raise DragError(f"{curve.Label} has {len(curve.Handles)} handles, no handle {index}")
        self.curve, self.index = curve, int(index)
        super().__init__(curve.Document, curve.Handles[self.index])

    def _place(self, target):
        handles = list(self.curve.Handles)
        handles[self.index] = target
        self.curve.Handles = handles

    def _lines(self, t):
        return ["import varsurf",
                f"varsurf.move_handle({ref(self.curve)}, {self.index}, App.Vector({t.x!r}, {t.y!r}, {t.z!r}))"]

    def _preview(self):
        self.curve.recompute()


ORIGIN_TRANSACTION = "Drag VarSurf origin"


class OriginDrag(RecomputeDrag):
    """One drag of a constraint's or operator's Origin (a plane's or line's point, an attractor's
    or repeller's centre): its Sheet is solved again as often as that takes, and exactly at the
    release. Operators change the solve's terms, so there is no kept factorization to reuse."""

    TRANSACTION = ORIGIN_TRANSACTION

    def __init__(self, constraint):
        if constraint.Kind == "Point" and constraint.Location is not None and not constraint.UseOrigin:
            raise DragError(f"{constraint.Label} takes its target from its Location: drag its pin")
        self.constraint = constraint
        super().__init__(constraint.Document, constraint.Origin)

    def _place(self, target):
        self.constraint.Origin = target

    def _lines(self, t):
        return [f"{ref(self.constraint)}.Origin = App.Vector({t.x!r}, {t.y!r}, {t.z!r})"]


class TargetDrag(RecomputeDrag):
    """A Point's target dragged on a sheet whose solve iterates (no factorization to keep): the
    sheet is recomputed as often as that takes, and exactly at the release."""

    TRANSACTION = TRANSACTION

    def __init__(self, sheet, constraint):
        _point_index(sheet, constraint)
        self.sheet, self.constraint = sheet, constraint
        super().__init__(sheet.Document, point_target(constraint))

    def _place(self, target):
        set_point_target(self.constraint, target)

    def _lines(self, t):
        return _target_lines(self.constraint, t)
