# SPDX-License-Identifier: LGPL-2.1-or-later
"""Dynamic sculpting (Du & Qin 3.4, 4.8): a Point's pin pulls a PdeSurface by a spring. The
surface has mass and damping, so it follows the pointer with inertia; released, the pin pulls
hard at the release point and the surface settles there. ``finish`` writes the target (one
undoable step) and the recompute puts the surface through it: the static solution the motion
settled toward.

The surface's own stiffness at the point is measured when the pin is grabbed (the equilibrium
under a unit spring), so the properties are relative and the same numbers feel alike on any
surface: ``Spring`` is the pin's stiffness in units of the surface's, ``Mass`` scales the mass
that gives a natural period of ``PERIOD`` with the pin held, ``Damping`` is the damping ratio of
that motion (1: critical)."""

from __future__ import annotations

import copy
import math
import time

import FreeCAD

from varsurf.app import drag
from varsurf.app import pde_surface as pde_feature
from varsurf.solve import pde_surface as pde_solve
from varsurf.solve.errors import SheetError
from varsurf.solve.native import native
from varsurf.solve.shapes import shape_from_binary, single_face

#: Seconds a full swing takes with Mass 1 and the pin held (the feel of the default).
PERIOD = 0.3
#: Released, the pin pulls this many times the surface's stiffness: it settles within 1 % of the
#: release point, and the recompute's exact pass through it is no visible jump.
SETTLE_SPRING = 100.0
#: Steps one move may take (the time since the last move, one step a frame of 1/60 s).
MAX_STEPS = 8
TIME_STEP = 1.0 / 60.0
#: Conditions a dynamic drag cannot carry: the core's dynamics hold a sheet by its fixed poles.
_OTHER_TERMS = ("tangents", "normals", "plane_points", "line_points", "ribbons", "curves", "curvatures",
                "point_curvatures", "attractors", "directors", "repellers", "shape_attractors")


class DynamicDrag(drag.WrittenOnRelease):
    """One dynamic drag of a Point's target on a PdeSurface whose DragMode is Dynamic: ``move``
    as the pointer moves, ``release`` and ``settle`` until ``settled``, then ``finish`` (the
    static solution through the target: one undoable step) or ``cancel``."""

    def __init__(self, surface, constraint):
        self.sheet, self.constraint, self.doc = surface, constraint, surface.Document
        if not pde_feature.is_pde_surface(surface) or str(getattr(surface, "DragMode", "Static")) != "Dynamic":
            raise drag.NotQuadratic(f"{surface.Label} is not a PdeSurface with DragMode Dynamic: it is dragged "
                                    "statically")
        if not surface.isValid():
            raise drag.DragError(f"{surface.Label} is in error: fix it before dragging")
        outcome = pde_feature.outcome_of(surface)
        problem = copy.copy(outcome.problem)
        index = drag._point_index(surface, constraint)
        points = list(problem.points)
        others = [name for name in _OTHER_TERMS if len(getattr(problem, name))]
        if len(points) != 1 or others or problem.pressure:
            raise drag.NotQuadratic(f"{surface.Label}: a dynamic drag holds the surface by its boundary conditions "
                                    "and frozen regions alone (it has other constraints): it is dragged statically")
        if index != 0:
            raise drag.DragError(f"{constraint.Label} is not among {surface.Label}'s solved points")
        nat = native()
        self.u, self.v = points[0].u, points[0].v
        problem.points = []
        # It starts where it is, at rest: the energy acts on the displacement from the solved shape
        # (which the Point holds there), so the spring pulls only by what the pointer moves. The
        # energy being quadratic, the shape the motion settles to is the recompute's with the
        # target moved, short only by the pin's give (1 / (1 + SETTLE_SPRING)).
        problem.initial_poles = outcome.surface.poles
        problem.rest_poles = outcome.surface.poles
        self.space = problem.space
        self.surface_of = outcome.surface_of
        self.natural = True  # a PdeSurface covers its parameter rectangle: the view draws the surface
        start = FreeCAD.Vector(*points[0].target)
        size = max(surface.Shape.BoundBox.DiagonalLength, 1.0)
        if (start - drag.point_target(constraint)).Length > drag._SAME_TARGET * size + 1e-12:
            raise drag.DragError(f"{surface.Label} is not up to date with {constraint.Label}: recompute first")
        self.start_shape = surface.Shape.copy()
        try:
            # The surface's own stiffness at the pin and the mass of the shape it deflects in.
            pin = nat.pin_stiffness(problem, self.u, self.v)
            self.stiffness, shape_mass = pin.stiffness, pin.shape_mass
            k = (1.0 + float(surface.Spring)) * self.stiffness  # the surface and the pin together
            omega = 2.0 * math.pi / PERIOD
            # Per unit of relative mass: the density that swings in PERIOD, and the damping
            # density of ratio 1 (2 sqrt(k m) for the shape's mass m).
            density = k / (omega * omega * shape_mass)
            parameters = nat.DynamicsParameters()
            parameters.mass, parameters.damping = pde_solve.material_fields(
                nat, pde_feature.settings_of(surface), float(surface.Mass), float(surface.Damping),
                density, 2.0 * math.sqrt(k * density / shape_mass))
            parameters.time_step = TIME_STEP
            self.dynamics = nat.DynamicSheet(problem, parameters)
            self.dynamics.set_springs([nat.Spring(self.u, self.v, list(start), float(surface.Spring) * self.stiffness)])
        except (nat.InvalidInput, nat.SolveFailure, SheetError) as error:
            raise drag.DragError(f"{surface.Label}: {error}") from error
        self.clock = time.perf_counter()
        self.released = False
        self.moves = 0
        self.doc.openTransaction(drag.TRANSACTION)

    def _surface(self):
        return self.surface_of(self.dynamics.poles)

    def _advance(self, steps):
        if steps is None:  # as many whole frames as have passed (the motion keeps real time)
            now = time.perf_counter()
            steps = int((now - self.clock) / TIME_STEP)
            if steps > MAX_STEPS:  # a slow frame: the motion waits rather than leaping
                steps, self.clock = MAX_STEPS, now
            else:
                self.clock += steps * TIME_STEP
        if steps > 0:
            self.dynamics.step(int(steps))

    def move(self, target, steps=None, update_shape=False):
        """Pull the pin toward `target` for `steps` frames (None: the frames since the last call);
        returns the moved native surface (the Shape shows it with update_shape)."""
        target = FreeCAD.Vector(target)
        if not all(math.isfinite(c) for c in target):
            raise drag.DragError("the dragged target is not finite")
        self.dynamics.move_targets([[target.x, target.y, target.z]])
        self._advance(steps)
        self.moves += 1
        surface = self._surface()
        if update_shape:
            self.sheet.Shape = single_face(shape_from_binary(native().face_binary(surface)))
        return surface

    def release(self, target):
        """The pointer let go at `target`: the pin now pulls hard there (SETTLE_SPRING)."""
        target = FreeCAD.Vector(target)
        nat = native()
        self.dynamics.set_springs([nat.Spring(self.u, self.v, [target.x, target.y, target.z],
                                              SETTLE_SPRING * self.stiffness)])
        self.released = True
        self.clock = time.perf_counter()

    def settle(self, steps=None):
        """Let the released surface move on for `steps` frames; returns it."""
        self._advance(steps)
        return self._surface()

    def energy(self):
        return float(self.dynamics.kinetic_energy()) + float(self.dynamics.potential_energy())

    @property
    def settled(self):
        """At rest: its kinetic energy under a millionth of the pin's at a tenth of the surface's
        size."""
        size = max(self.start_shape.BoundBox.DiagonalLength, 1.0)
        return float(self.dynamics.kinetic_energy()) < 1e-6 * self.stiffness * (0.1 * size) ** 2
