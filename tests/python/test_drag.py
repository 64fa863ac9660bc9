# SPDX-License-Identifier: LGPL-2.1-or-later
"""Dragging a Point constraint's target: each move is a back-substitution on the Sheet's kept
factorization and equals a fresh solve; finishing is one undoable step; cancel writes nothing."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.app import drag
from varsurf.app import sheet as sheet_feature
from scenes import add_vertex, railed_sheet

V = FreeCAD.Vector


@pytest.fixture
def sheet(doc, native):
    return railed_sheet(doc)


def _poles(sheet):
    return sheet_feature.outcome_of(sheet).surface.poles


def test_a_drag_equals_a_fresh_solve_and_one_undo_restores(sheet):
    doc = sheet.Document
    pin = add_vertex(doc, "Pin", (60.0, 50.0, 12.0))
    c = varsurf.make_constraint(sheet, "Point", location=(pin, "Vertex1"), name="Pin")
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    before_poles, before_area = _poles(sheet).copy(), sheet.Shape.Area
    session = drag.PointDrag(sheet, c)
    for k in range(1, 6):  # the pointer moves up by 1.5 mm five times
        session.move(V(60.0, 50.0, 12.0 + 1.5 * k))
        assert sheet.Shape.isValid() and sheet.Shape.distToShape(Part.Vertex(V(60, 50, 12 + 1.5 * k)))[0] < 1e-6
    dragged = session.last.poles.copy()
    assert session.moves == 5
    session.finish(V(60.0, 50.0, 19.5))
    assert (pin.X, pin.Y, pin.Z) == (60.0, 50.0, 19.5)  # the linked vertex moved
    assert sheet.isValid(), sheet.getStatusString()
    fresh = _poles(sheet)
    assert fresh.shape == dragged.shape and abs(fresh - dragged).max() < 1e-8  # drag == recompute
    assert abs(fresh - before_poles).max() > 1.0
    doc.undo()  # one step: the vertex and the sheet
    doc.recompute()
    assert pin.Z == 12.0
    assert abs(_poles(sheet) - before_poles).max() < 1e-9
    assert abs(sheet.Shape.Area - before_area) < 1e-9 * before_area


def test_cancel_writes_nothing_and_bad_drags_are_refused(sheet):
    doc = sheet.Document
    c = varsurf.make_constraint(sheet, "Point", uv=(0.4, 0.6), origin=(40.0, 48.0, 9.0), name="Pin")
    n = varsurf.make_constraint(sheet, "Normal", uv=(0.5, 0.5), vector=(0, 0, 1), name="Up")
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    area = sheet.Shape.Area
    session = drag.PointDrag(sheet, c)
    session.move(V(40.0, 48.0, 20.0))
    assert abs(sheet.Shape.Area - area) > 1.0
    with pytest.raises(drag.DragError, match="not finite"):
        session.move(V(40.0, 48.0, math.nan))
    session.cancel()
    assert abs(sheet.Shape.Area - area) < 1e-9 * area
    assert tuple(c.Origin) == (40.0, 48.0, 9.0)
    assert "Touched" not in sheet.State
    with pytest.raises(drag.DragError, match="not an enabled Point"):
        drag.PointDrag(sheet, n)
    # The Origin edited without a recompute: the sheet no longer shows this target.
    c.Origin = V(40.0, 48.0, 11.0)
    with pytest.raises(drag.DragError, match="recompute first"):
        drag.PointDrag(sheet, c)
    doc.recompute()
    session = drag.PointDrag(sheet, c)
    session.move(V(30.0, 48.0, 11.0))
    session.finish(V(30.0, 48.0, 11.0))  # no linked vertex: the Origin takes the target
    assert tuple(c.Origin) == (30.0, 48.0, 11.0) and sheet.isValid()


def test_dragging_a_space_curve_handle_moves_the_joined_sheets(doc, native):

    import moving_curve

    solid, curve = moving_curve.build(doc)
    volume = solid.Shape.Volume
    start = V(curve.Handles[1])
    with pytest.raises(drag.DragError, match="no handle 7"):
        drag.HandleDrag(curve, 7)
    session = drag.HandleDrag(curve, 1)
    for k in range(1, 5):
        session.move(start + V(0, 0, 2.0 * k))
    assert session.moves == 4 and session.live_solves >= 1
    session.finish(start + V(0, 0, 8.0))
    assert solid.isValid() and solid.Closed, solid.getStatusString()
    assert solid.Shape.Volume > volume + 1000.0  # the top and front sheets rose with the edge
    assert doc.UndoNames[0] == "Drag VarSurf handle"
    doc.undo()
    doc.recompute()
    assert V(curve.Handles[1]) == start
    assert abs(solid.Shape.Volume - volume) < 1e-6 * volume
    session = drag.HandleDrag(curve, 1)
    session.move(start + V(0, 0, 3.0))
    with pytest.raises(drag.DragError, match="not finite"):
        session.move(V(math.nan, 0, 0))
    session.cancel()
    assert V(curve.Handles[1]) == start and abs(solid.Shape.Volume - volume) < 1e-6 * volume


def test_dragging_an_attractor_origin_re_solves_its_sheet(sheet):
    doc = sheet.Document
    pull = varsurf.make_constraint(sheet, "PointAttractor", origin=(50.0, 40.0, 20.0),
                                   region=(0.3, 0.7, 0.3, 0.7), weight=1.0, name="Pull")
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    area = sheet.Shape.Area
    top = sheet.Shape.BoundBox.ZMax
    session = drag.OriginDrag(pull)
    for z in (24.0, 28.0, 32.0):
        session.move(V(50.0, 40.0, z))
    assert session.live_solves >= 1
    recorded = []

    def record(line):  # what FreeCADGui.doCommand does: run the line, and a macro keeps it
        from varsurf.app.macro import exec_line as _exec_line

        recorded.append(line)
        _exec_line(line)

    session.finish(V(50.0, 40.0, 32.0), do_command=record)
    assert recorded[0].endswith(".Origin = App.Vector(50.0, 40.0, 32.0)") and "recompute()" in recorded[-1]
    assert tuple(pull.Origin) == (50.0, 40.0, 32.0) and sheet.isValid()
    assert sheet.Shape.BoundBox.ZMax > top + 1.0  # pulled higher
    assert doc.UndoNames[0] == "Drag VarSurf origin"
    doc.undo()
    doc.recompute()
    assert tuple(pull.Origin) == (50.0, 40.0, 20.0)
    assert abs(sheet.Shape.Area - area) < 1e-9 * area


def test_a_sheet_with_iterated_terms_drags_by_recomputing(sheet):
    """A repeller makes the solve iterate: no kept factorization, so the pin's drag recomputes."""
    doc = sheet.Document
    varsurf.make_constraint(sheet, "Repeller", origin=(80.0, 60.0, -5.0), region=(0.6, 1.0, 0.6, 1.0),
                            weight=0.5, name="Away")
    pin = varsurf.make_constraint(sheet, "Point", uv=(0.4, 0.6), origin=(40.0, 48.0, 9.0), name="Pin")
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    with pytest.raises(drag.NotQuadratic, match="back-substitution"):
        drag.PointDrag(sheet, pin)
    session = drag.TargetDrag(sheet, pin)
    session.move(V(40.0, 48.0, 12.0))
    session.finish(V(40.0, 48.0, 15.0))
    assert tuple(pin.Origin) == (40.0, 48.0, 15.0) and sheet.isValid()
    assert sheet.Shape.distToShape(Part.Vertex(V(40.0, 48.0, 15.0)))[0] < 1e-3
    assert doc.UndoNames[0] == "Drag VarSurf point"
