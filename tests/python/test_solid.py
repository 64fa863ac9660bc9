# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Solid feature: sheets joined along shared curves, trimmed and sewn into a solid; the
pillow example, STEP and save/reopen round trips, edits, and bad inputs."""

import itertools
import math
import re

import FreeCAD
import Part
import pytest

import varsurf

import brep_measure  # noqa: E402
import pillow  # noqa: E402
import rounded_box  # noqa: E402

V = FreeCAD.Vector


def assert_seam_angles_measured(solid, within=1e-3):
    """SeamAngles, pair by pair, against the angle across each shared edge measured with Part at
    the same 22 interior points (each edge point projected onto both faces)."""
    shape = solid.Shape
    pairs = list(zip(solid.SeamAngles[::2], solid.SeamAngles[1::2]))
    measured = []
    for i in range(len(shape.Faces)):
        for j in range(i + 1, len(shape.Faces)):
            for edge in brep_measure.shared_edges(shape, i, j):
                angles, far = brep_measure.seam_angles(shape.Faces[i], shape.Faces[j], edge, 24)
                assert far <= solid.Tolerance.Value, far
                measured.append((min(angles), max(angles)))
    assert len(measured) == len(pairs), (measured, pairs)
    for got in pairs:  # the Solid lists its seams in its own edge order
        best = min(measured, key=lambda m: abs(m[0] - got[0]) + abs(m[1] - got[1]))
        assert abs(best[0] - got[0]) <= within and abs(best[1] - got[1]) <= within, (got, best)
    return measured


@pytest.fixture
def solid(doc, native):
    s = pillow.build(doc)
    assert s.isValid(), s.getStatusString()
    return s


def test_pillow_is_a_valid_closed_solid(solid):
    shape = solid.Shape
    assert solid.Closed and solid.Status.startswith("OK: solid")
    assert shape.ShapeType == "Solid" and len(shape.Faces) == 2
    assert shape.isValid() and shape.check(True) is None
    # The volume from the faces' surfaces and trims alone (divergence theorem; measured: 44762.97
    # against OCCT's 44762.73, 5.4e-6 apart at 40 quadrature points, the surfaces being piecewise).
    assert brep_measure.enclosed_volume(shape, 40) == pytest.approx(shape.Volume, rel=1e-4)
    assert shape.Volume > 0.0  # outward oriented
    # The rim maps to itself turned 180 degrees about each axis, and so does the pillow (the top
    # sheet pushed up, the bottom one down): its centre of mass is the origin (measured: 3e-5 mm,
    # the sheets meeting the rim within 0.001 mm).
    assert shape.CenterOfMass.Length <= 0.002, shape.CenterOfMass
    assert max(solid.SeamGaps) <= solid.Tolerance.Value
    # The sheets end on the rim (Trim Loop), so the overhang of their bases does not pull the rim
    # into a valley: the faces meet at a wide angle all along it (measured: 74.2 to 110.5 degrees);
    # SeamAngles agrees with the angle measured across each edge with Part at the same points.
    assert solid.SeamAngles and all(60.0 < a < 125.0 for a in solid.SeamAngles), list(solid.SeamAngles)
    assert_seam_angles_measured(solid)
    assert "knife" not in solid.Status
    assert solid.MaxEdgeTolerance <= solid.Tolerance.Value
    # The seam: the two faces' shared edge lies on the rim (sampled, measured by OCCT).
    rim = solid.Document.getObject("Rim").Shape
    for edge in shape.Edges:
        for p in edge.discretize(50):
            assert rim.distToShape(Part.Vertex(p))[0] <= solid.Tolerance.Value


def test_sheets_solved_over_their_whole_bases_make_a_knife_edge_and_the_solid_says_where(solid):
    """The pillow's sheets untrimmed (Trim Automatic keeps their whole bases): the pressure inflates
    the overhang beyond the rim and the rim sits in a valley, a lip of a few degrees (measured: 0.46
    to 14.6). The Solid warns and says where its sharpest point is."""
    doc = solid.Document
    for name in ("Top", "Bottom"):
        doc.getObject(name).Trim = "Automatic"
    doc.recompute()
    assert solid.isValid(), solid.getStatusString()
    assert_seam_angles_measured(solid)
    sharpest = min(solid.SeamAngles)
    assert sharpest < 5.0, list(solid.SeamAngles)
    knife = re.search(r"knife edges?, the sharpest ([0-9.e-]+)° at \(([^)]*)\)", solid.Status)
    assert knife and float(knife.group(1)) == pytest.approx(sharpest, rel=0.05), solid.Status
    at = V(*(float(c) for c in knife.group(2).split(",")))
    assert doc.getObject("Rim").Shape.distToShape(Part.Vertex(at))[0] <= 0.01  # printed to 4 digits


@pytest.mark.parametrize("angle", [10.0, 45.0, 90.0, 150.0])
def test_the_wall_inside_a_wedge_is_its_depth_times_the_sine_of_its_angle(angle):
    """Two planar faces meeting at ``angle`` along the x axis: depth sin(angle) apart that far
    inside the seam."""
    from varsurf.solve.assembly import _wall

    a = Part.makePlane(40, 20, V(-20, 0, 0))
    b = a.copy()
    b.rotate(V(0, 0, 0), V(1, 0, 0), angle)
    p = V(3.0, 0, 0)
    for depth in (0.5, 4.0):
        wall = _wall(a, b, p, a.normalAt(0, 0), b.normalAt(0, 0), V(1, 0, 0), depth)
        assert wall == pytest.approx(depth * math.sin(math.radians(angle)), rel=1e-9), (angle, depth)


def test_the_thinnest_wall_near_the_seams_is_reported(solid):
    """The pillow's sheets ending on the rim: a wedge of about 74 degrees, 0.47 mm thick 0.49 mm
    inside. On their whole bases: a lip (measured: 0.0035 mm); a vertical line 0.65 mm inside the
    rim, where the sheets curve toward each other, crosses 0.0083 mm of it (OCCT's common of the
    line and the solid, sampled at 200 rim points)."""
    doc = solid.Document
    depth = 0.005 * solid.Shape.BoundBox.DiagonalLength
    assert solid.ThinnestWall == pytest.approx(depth * math.sin(math.radians(min(solid.SeamAngles))), rel=0.05)
    assert f"thinnest wall {solid.ThinnestWall:.3g} mm" in solid.Status
    for name in ("Top", "Bottom"):
        doc.getObject(name).Trim = "Automatic"
    doc.recompute()
    rim = doc.getObject("Rim").Shape.Edges[0]
    depth = 0.005 * solid.Shape.BoundBox.DiagonalLength
    chords = []
    for k in range(200):
        t = rim.FirstParameter + (rim.LastParameter - rim.FirstParameter) * k / 200
        p, tangent = rim.valueAt(t), rim.tangentAt(t)
        inward = V(-tangent.y, tangent.x, 0).normalize()
        if (V(p.x, p.y, 0) + inward).Length > V(p.x, p.y, 0).Length:
            inward = -inward
        q = p + inward * depth
        chords.append(solid.Shape.common(Part.LineSegment(V(q.x, q.y, -100), V(q.x, q.y, 100)).toShape()).Length)
    assert solid.ThinnestWall < 0.02 and min(chords) < 0.02, (solid.ThinnestWall, min(chords))


def test_a_knife_edge_asked_for_by_a_hinge_is_not_warned_of():
    """The knife-edge rule alone: seams below 5 degrees are named, sharpest first, unless a hinge
    asks for about that angle."""
    from varsurf.solve.assembly import AssemblyOutcome, knife_edges

    outcome = AssemblyOutcome(shape=None, seam_angles=[(3.0, 20.0), (90.0, 95.0), (0.5, 4.0), (5.0, 9.0)],
                              seam_sharpest=[(1, 0, 0), (2, 0, 0), (3, 0, 0), (4, 0, 0)])
    assert knife_edges(outcome) == [(0.5, (3, 0, 0)), (3.0, (1, 0, 0))]
    assert knife_edges(outcome, hinge_angles=[3.5]) == [(0.5, (3, 0, 0))]
    assert knife_edges(outcome, hinge_angles=[0.4, 2.5]) == []


def test_step_and_save_round_trips(solid, native, tmp_path):
    doc = solid.Document
    shape = solid.Shape
    path = str(tmp_path / "pillow.step")
    varsurf.export_step([solid], path)
    from step_check import assert_reads_back

    back = assert_reads_back(shape, path, native)
    assert len(back.Solids) == 1
    from scenes import recompute_all, reopened

    name, volume = solid.Name, shape.Volume
    with reopened(doc, tmp_path / "pillow.FCStd") as again:
        s = again.getObject(name)
        assert s.Shape.Volume == pytest.approx(volume, rel=1e-12)
        recompute_all(again)
        assert s.isValid(), s.getStatusString()
        assert s.Shape.Volume == pytest.approx(volume, rel=1e-9)


def test_editing_the_shared_curve_updates_both_sheets(solid):
    doc = solid.Document
    rim = doc.getObject("Rim")
    before = solid.Shape.Volume
    rim.Shape = rim.Shape.copy().scale(1.2)  # a bigger rim
    doc.recompute()
    assert solid.isValid() and solid.Closed, solid.Status
    assert solid.Shape.isValid()
    assert solid.Shape.Volume > 1.3 * before  # area grows by 1.44


def test_bad_inputs_are_reported(doc, native, console_errors):
    rim = doc.addObject("Part::Feature", "Arc")
    rim.Shape = Part.Edge(Part.Arc(V(-30, 0, 0), V(0, 20, 2), V(30, 0, 0)))  # open: no loop
    lone = doc.addObject("Part::Feature", "Lone")
    lone.Shape = Part.LineSegment(V(-20, -20, 1), V(20, -20, 1)).toShape()
    sheets = []
    for name, curves in (("A", [(rim, "Edge1")]), ("B", [(rim, "Edge1")]), ("C", [(lone, "Edge1")])):
        base = doc.addObject("Part::Feature", name + "Base")
        base.Shape = Part.makePlane(120, 90, V(-60, -45, 0))
        doc.recompute()
        sheets.append(varsurf.make_sheet((base, "Face1"), curves, name=name))
    doc.recompute()
    open_loop = varsurf.make_solid(sheets[:2], name="OpenLoop")
    doc.recompute()
    status = open_loop.getStatusString()
    # said in mm: the arc's ends, (-30, 0, 0) and (30, 0, 0), are what the loop lacks
    assert not open_loop.isValid() and "do not close a loop: their ends are up to 60 mm apart" in status, status
    unshared = varsurf.make_solid([sheets[0], sheets[1], sheets[2]], name="Unshared")
    doc.recompute()
    # A and B fail on their open loop first; C shares nothing: either is reported, nothing built.
    assert not unshared.isValid() and unshared.Shape.isNull()
    empty = varsurf.make_solid([sheets[2]], name="Alone")
    doc.recompute()
    assert not empty.isValid() and "shares no curve" in empty.getStatusString()
    assert "VarSurf" in console_errors()
    with pytest.raises(ValueError):
        varsurf.make_solid([])


def test_solid_command_joins_selected_sheets_in_one_transaction(doc, native):
    from varsurf.app import actions, macro
    from scenes import Sel

    pillow.build(doc)  # makes a Pillow already; the command adds a second Solid of the same Sheets
    doc.UndoMode = 1
    top, bottom = doc.getObject("Top"), doc.getObject("Bottom")
    lines = []
    s = actions.run_solid_command([Sel(top), Sel(bottom, "Face1")],
                                  do_command=lambda line: (lines.append(line), macro.exec_line(line)))
    assert s is not None and s.isValid() and s.Closed, s.Status
    assert any("varsurf.make_solid(" in line for line in lines), lines
    name = s.Name
    doc.undo()
    assert name not in [o.Name for o in doc.Objects]
    messages = []
    assert actions.run_solid_command([Sel(top)], on_error=messages.append) is None
    assert "joins two or more Sheets, and only Top is selected" in messages[0], messages
    rim = doc.getObject("Rim")
    assert actions.run_solid_command([Sel(top), Sel(rim)], on_error=messages.append) is None
    assert "is not a Sheet" in messages[1]


def test_a_box_of_flat_sheets_is_the_cube(doc, native, monkeypatch):
    """The rounded box with straight edges: six flat sheets through the twelve edges of a 100 mm
    cube (each edge inside its two base planes) are the cube's faces, so the Solid is the cube:
    volume 10^6 mm^3, area 6 x 10^4 mm^2, every seam 90 degrees."""
    monkeypatch.setattr(rounded_box, "BOW", 0.0)
    solid = rounded_box.build(doc)
    assert solid.isValid() and solid.Closed, solid.Status
    shape = solid.Shape
    assert shape.isValid() and shape.check(True) is None and len(shape.Faces) == 6
    assert shape.Volume == pytest.approx(1.0e6, rel=1e-9)
    assert brep_measure.enclosed_volume(shape, 8) == pytest.approx(1.0e6, rel=1e-9)
    assert shape.Area == pytest.approx(6.0e4, rel=1e-9)
    assert shape.CenterOfMass.Length <= 1e-9
    corners = sorted((round(v.X, 6), round(v.Y, 6), round(v.Z, 6)) for v in shape.Vertexes)
    assert corners == sorted(itertools.product((-50.0, 50.0), repeat=3)), corners
    assert solid.SeamAngles and max(abs(a - 90.0) for a in solid.SeamAngles) <= 1e-6, list(solid.SeamAngles)
    measured = assert_seam_angles_measured(solid, within=1e-6)
    assert len(measured) == 12 and all(abs(a - 90.0) <= 1e-6 and abs(b - 90.0) <= 1e-6 for a, b in measured)


def test_rounded_box_of_six_sheets_and_twelve_shared_curves(doc, native, tmp_path):
    solid = rounded_box.build(doc)
    assert solid.isValid() and solid.Closed, solid.Status
    shape = solid.Shape
    assert shape.ShapeType == "Solid" and len(shape.Faces) == 6
    assert shape.isValid() and shape.check(True) is None
    # The volume from the faces' surfaces and trims alone (divergence theorem; measured: 1e-7
    # from OCCT's 1,363,134 mm^3); the box is symmetric about the origin.
    assert brep_measure.enclosed_volume(shape, 40) == pytest.approx(shape.Volume, rel=1e-6)
    assert shape.CenterOfMass.Length <= 1e-6, shape.CenterOfMass
    # The twelve seams are alike (the cube's symmetries map one to another) and sharp, opened by
    # the bulging faces: measured 105.5011 to 113.5215 degrees on every one, by SeamAngles and by
    # Part across each edge at the same points, within 1e-6 degrees.
    measured = assert_seam_angles_measured(solid, within=1e-4)
    assert len(measured) == 12
    lo, hi = measured[0]
    assert 100.0 < lo < hi < 120.0, measured
    assert "knife" not in solid.Status, solid.Status
    assert all(abs(a - lo) <= 1e-5 and abs(b - hi) <= 1e-5 for a, b in measured), measured
    path = str(tmp_path / "box.step")
    varsurf.export_step([solid], path)
    from step_check import assert_reads_back

    assert len(assert_reads_back(shape, path, native).Solids) == 1


def test_a_sheet_that_misses_a_join_curve_is_reported(solid):
    doc = solid.Document
    solid.Tolerance = 1e-5  # tighter than the sheets meet the rim (about 6e-4 mm)
    doc.recompute()
    assert not solid.isValid()
    assert "from a join curve" in solid.getStatusString(), solid.getStatusString()
    solid.Tolerance = 0.02
    doc.recompute()
    assert solid.isValid() and solid.Closed


def _line(doc, name, a, b):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = Part.LineSegment(V(*a), V(*b)).toShape()
    return obj


def test_two_sheets_meeting_at_an_angle_make_an_open_shell(doc, native):
    # Sheet A is the square x in [5, 50], y in [5, 55] at z = 0; sheet B continues it beyond the
    # seam x = 50, tilted up by 30 degrees. They share only the seam: their own edges complete
    # their loops and bound the open shell.
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    tilt = lambda x, y: (50 + (x - 50) * c, y, (x - 50) * s)  # noqa: E731
    seam = _line(doc, "Seam", (50, 5, 0), (50, 55, 0))
    own_a = [_line(doc, "A1", (50, 55, 0), (5, 55, 0)), _line(doc, "A2", (5, 55, 0), (5, 5, 0)),
             _line(doc, "A3", (5, 5, 0), (50, 5, 0))]
    own_b = [_line(doc, "B1", tilt(50, 55), tilt(95, 55)), _line(doc, "B2", tilt(95, 55), tilt(95, 5)),
             _line(doc, "B3", tilt(95, 5), tilt(50, 5))]
    base_a = doc.addObject("Part::Feature", "BaseA")
    base_a.Shape = Part.makePlane(70, 70, V(-5, -5, 0))
    base_b = doc.addObject("Part::Feature", "BaseB")
    base_b.Shape = Part.Face(Part.makePolygon([V(*tilt(x, y)) for x, y in
                                               ((45, -5), (105, -5), (105, 65), (45, 65), (45, -5))]))
    doc.recompute()
    a = varsurf.make_sheet((base_a, "Face1"), [(o, "Edge1") for o in [seam] + own_a], name="A")
    b = varsurf.make_sheet((base_b, "Face1"), [(o, "Edge1") for o in [seam] + own_b], name="B")
    solid = varsurf.make_solid([a, b], name="Hinge")
    doc.recompute()
    assert solid.isValid(), solid.getStatusString()
    assert not solid.Closed and "open shell" in solid.Status
    shape = solid.Shape
    assert len(shape.Faces) == 2 and shape.isValid()
    assert shape.Area == pytest.approx(2 * 45 * 50, rel=1e-4)  # two flat 45 x 50 mm faces
    angles = list(solid.SeamAngles)
    assert angles and all(abs(x - 150.0) < 0.05 for x in angles), angles
