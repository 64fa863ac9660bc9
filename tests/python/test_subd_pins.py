# SPDX-License-Identifier: LGPL-2.1-or-later
"""A SubdSurface's pins and normals edited one at a time (varsurf.app.subd_pins, what its task
panel runs): a picked vertex pinned where it is changes nothing; the region of influence shrinks
with the influence level and equals the vertices an actual move moves; a normal held at a pin
changes nothing until the pin moves, then keeps the surface's normal there; removing a pin removes
its normal; bad indices are named."""

import FreeCAD
import pytest

import varsurf
from varsurf.app import subd_pins
from varsurf.solve.errors import SheetError

V = FreeCAD.Vector


@pytest.fixture
def sphere_subd(doc):
    box = doc.addObject("Part::Box", "Cage")
    box.Length = box.Width = box.Height = 20.0
    box.Placement.Base = V(-10, -10, -10)
    sphere = doc.addObject("Part::Sphere", "Target")
    sphere.Radius = 13.0
    doc.recompute()
    subd = varsurf.make_subd_surface(box, levels=4, target=sphere)
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    return subd


def points(subd):
    return [V(*p) for p in subd.Proxy.outcome.points]


def test_a_picked_vertex_is_pinned_where_it_is(doc, sphere_subd):
    subd = sphere_subd
    before = points(subd)
    top = subd_pins.pick_vertex(subd, 3, V(0.3, -0.2, 14.0))
    level3 = subd.Proxy.outcome.levels[3]
    assert (V(*level3[top]) - V(0, 0, 13)).Length < 0.5  # the vertex at the sphere's top
    assert subd_pins.add_pin(subd, 3, top, 1) == 0
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    assert max((a - b).Length for a, b in zip(before, points(subd))) < 1e-9
    with pytest.raises(SheetError, match="already: drag that pin"):
        subd_pins.add_pin(subd, 3, top, 1)
    with pytest.raises(SheetError, match="no vertex 99999 at level 3"):
        subd_pins.add_pin(subd, 3, 99999, 1)


def test_the_region_of_influence_shrinks_with_the_level_and_is_what_a_move_moves(doc, sphere_subd):
    subd = sphere_subd
    top = subd_pins.pick_vertex(subd, 4, V(0, 0, 14.0))
    subd_pins.add_pin(subd, 4, top, 0)
    doc.recompute()
    sizes = []
    for influence in range(5):
        subd_pins.set_influence(subd, 0, influence)
        doc.recompute()
        region = set(subd_pins.region(subd, 0).tolist())
        sizes.append(len(region))
        # A real move of the pin (the feature's Approximate solve) moves exactly those vertices.
        before = points(subd)
        subd.Solve = "Approximate"
        varsurf.move_pin(subd, 0, V(*subd.Proxy.outcome.levels[4][top]) + V(0.5, 0.3, 2.0))
        doc.recompute()
        moved = {k for k, (a, b) in enumerate(zip(before, points(subd))) if (a - b).Length > 1e-9}
        assert moved == region, (influence, len(moved), len(region))
        varsurf.move_pin(subd, 0, V(subd.PinTargets[0]) - V(0.5, 0.3, 2.0))
        subd.Solve = "Direct"
        doc.recompute()
    assert sizes[0] == len(points(subd)), sizes  # level 0: the whole closed surface
    assert all(a > b for a, b in zip(sizes, sizes[1:])), sizes
    with pytest.raises(SheetError, match="influence must lie in 0..4"):
        subd_pins.set_influence(subd, 0, 5)


def test_a_held_normal_keeps_the_tilt_when_the_pin_moves(doc, sphere_subd):
    subd = sphere_subd
    side = subd_pins.pick_vertex(subd, 3, V(14.0, 0, 3.0))
    subd_pins.add_pin(subd, 3, side, 1)
    doc.recompute()
    before = points(subd)
    subd_pins.hold_normal(subd, 0)
    subd_pins.hold_normal(subd, 0)  # twice: one normal
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    assert len(subd.NormalDirections) == 1 and list(subd.NormalInfluence) == [1]
    held = V(subd.NormalDirections[0])
    assert max((a - b).Length for a, b in zip(before, points(subd))) < 1e-7  # holding moves nothing
    outcome = subd.Proxy.outcome
    varsurf.move_pin(subd, 0, V(*outcome.levels[3][side]) + V(0, 0, 4.0))
    doc.recompute()
    assert subd.isValid() and subd.NormalAngle < 1e-4, (subd.NormalAngle, subd.getStatusString())
    from varsurf.solve import multiresolution
    now = V(*multiresolution.vertex_normal(subd.Proxy.outcome, 3, side))
    assert min(now.getAngle(held), now.getAngle(-held)) < 1e-5
    # Without the normal the same move tilts the surface there.
    varsurf.set_normals(subd, [])
    doc.recompute()
    free = V(*multiresolution.vertex_normal(subd.Proxy.outcome, 3, side))
    assert min(free.getAngle(held), free.getAngle(-held)) > 0.01  # 1 degree, against 1e-5 held
    subd_pins.hold_normal(subd, 0)
    subd_pins.remove_pin(subd, 0)
    doc.recompute()
    assert len(subd.PinTargets) == 0 and len(subd.NormalDirections) == 0
    with pytest.raises(SheetError, match="has no pins: add one first"):
        subd_pins.remove_pin(subd, 0)
