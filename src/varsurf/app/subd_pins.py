# SPDX-License-Identifier: LGPL-2.1-or-later
"""A SubdSurface's pins and normals edited one at a time, as its task panel does and as a macro
replays it: a pin added on a picked vertex of a level (where the vertex is, so nothing moves until
it is dragged), its influence level changed, a normal held at a pin's vertex (the surface's own
normal there, so holding it changes nothing until the pin moves), a pin removed; and the region
of influence of a pin, the finest vertices it moves."""

from __future__ import annotations

import FreeCAD
import numpy as np

from varsurf.app.feature import last_outcome, value
from varsurf.app.subd_surface import compute, curves_of, normals_of, pins_of, set_normals, set_pins
from varsurf.solve import multiresolution
from varsurf.solve.errors import SheetError


def _pin_tuples(obj):
    return [(p.level, p.vertex, FreeCAD.Vector(*p.target), p.influence) for p in pins_of(obj)]


def _check_index(obj, index):
    count = len(value(obj, "PinTargets"))
    if not 0 <= int(index) < count:
        raise SheetError(f"{obj.Label} has {count} pins, no pin {index}: give one of 0..{count - 1}"
                         if count else f"{obj.Label} has no pins: add one first")
    return int(index)


def pick_vertex(obj, level: int, point) -> int:
    """The vertex of `level` nearest to `point` (a pick on the surface in the view)."""
    p = FreeCAD.Vector(point)
    return multiresolution.nearest_vertex(last_outcome(obj, compute), int(level), (p.x, p.y, p.z))


def add_pin(obj, level: int, vertex: int, influence: int = 0) -> int:
    """Pin `vertex` of `level` where it is now, propagated to `influence`; its index."""
    outcome = last_outcome(obj, compute)
    level, vertex = int(level), int(vertex)
    if not 0 <= level < len(outcome.levels) or not 0 <= vertex < len(outcome.levels[level]):
        raise SheetError(f"{obj.Label} has no vertex {vertex} at level {level}: pick a vertex of levels "
                         f"0..{len(outcome.levels) - 1}")
    pins = _pin_tuples(obj)
    if any(p[0] == level and p[1] == vertex for p in pins):
        raise SheetError(f"{obj.Label} pins vertex {vertex} of level {level} already: drag that pin")
    pins.append((level, vertex, FreeCAD.Vector(*outcome.levels[level][vertex]), min(max(int(influence), 0), level)))
    set_pins(obj, pins)
    return len(pins) - 1


def set_influence(obj, index: int, influence: int):
    """Propagate pin `index` to level `influence` (0: the whole shape .. its own level: local)."""
    index = _check_index(obj, index)
    pins = _pin_tuples(obj)
    level, vertex, target, _ = pins[index]
    if not 0 <= int(influence) <= level:
        raise SheetError(f"pin {index} of {obj.Label} is on level {level}: its influence must lie in 0..{level}")
    pins[index] = (level, vertex, target, int(influence))
    set_pins(obj, pins)


def remove_pin(obj, index: int):
    """Remove pin `index` (and a normal held at its vertex)."""
    index = _check_index(obj, index)
    pins = _pin_tuples(obj)
    level, vertex = pins[index][:2]
    del pins[index]
    set_pins(obj, pins)
    normals = [(n.level, n.vertex, FreeCAD.Vector(*n.direction), n.influence) for n in normals_of(obj)
               if (n.level, n.vertex) != (level, vertex)]
    set_normals(obj, normals)


def hold_normal(obj, index: int):
    """Hold the surface's normal at pin `index`'s vertex as it is now, with the pin's influence:
    dragging the pin then keeps the surface's tilt there."""
    index = _check_index(obj, index)
    level, vertex, _, influence = _pin_tuples(obj)[index]
    normals = [(n.level, n.vertex, FreeCAD.Vector(*n.direction), n.influence) for n in normals_of(obj)]
    if any((n[0], n[1]) == (level, vertex) for n in normals):
        return
    direction = multiresolution.vertex_normal(last_outcome(obj, compute), level, vertex)
    normals.append((level, vertex, FreeCAD.Vector(*direction), influence))
    set_normals(obj, normals)


def region(obj, index: int):
    """The finest level's vertices that pin `index` moves: its region of influence."""
    index = _check_index(obj, index)
    return multiresolution.influence_region(last_outcome(obj, compute), pins_of(obj), index, normals_of(obj),
                                            curves_of(obj))


def loop_at(obj, point) -> int:
    """The number of the cage's boundary loop that comes nearest to `point` (a pick in the view),
    as CurveLoops and HeldLoops number them."""
    outcome = last_outcome(obj, compute)
    cage = np.asarray(outcome.levels[0], float)
    loops = multiresolution.boundary_loops(outcome.faces[0])
    if not loops:
        raise SheetError(f"{obj.Label}'s cage is closed: it has no boundary loops to move or hold")
    p = np.asarray(FreeCAD.Vector(point), float)
    return int(np.argmin([np.min(np.linalg.norm(cage[loop] - p, axis=1)) for loop in loops]))


#: A boundary loop's modes: moved with the curves by CurveMotion, held where it is, or free.
LOOP_MODES = ("moved", "held", "free")


def set_loop(obj, loop: int, mode: str):
    """Make the cage's boundary loop `loop` moved (CurveLoops), held (HeldLoops) or free."""
    try:  # the loop exists (its vertices on the cage)
        multiresolution.loop_vertices(last_outcome(obj, compute).editor, 0, loop)
    except SheetError as error:
        raise SheetError(f"{obj.Label}: {error}") from error
    if mode not in LOOP_MODES:
        raise SheetError(f"a loop is {', '.join(LOOP_MODES)}, not {mode!r}: give one of those")
    moved = [int(n) for n in obj.CurveLoops if int(n) != int(loop)]
    held = [int(n) for n in obj.HeldLoops if int(n) != int(loop)]
    if mode == "moved":
        moved.append(int(loop))
    elif mode == "held":
        held.append(int(loop))
    obj.CurveLoops, obj.HeldLoops = moved, held
