# SPDX-License-Identifier: LGPL-2.1-or-later
"""Fill hole and face replacement: a sheet where a part's face was, or in the hole its free edges
bound, G0 or G1 to the faces around, sewn with the part into one new solid. Part primitives and
their own edges, checked against the part itself (a sheet G1 to a flat top's fillet is that flat
top), independent volumes (columns through a tessellation), the BOP check and STEP."""

import FreeCAD
import Part
import pytest

import varsurf
from brep_measure import Columns
from step_check import assert_reads_back

V = FreeCAD.Vector


def _face_at_height(shape, z, kind="Part::GeomPlane"):
    return next(i for i, f in enumerate(shape.Faces)
                if f.Surface.TypeId == kind and abs(f.CenterOfMass.z - z) < 1e-6)


def _filleted_cylinder(doc, radius):
    """A Part Cylinder (radius 20, height 30) with its top edge filleted by a Part Fillet."""
    cylinder = doc.addObject("Part::Cylinder", "Cylinder")
    cylinder.Radius, cylinder.Height = 20, 30
    fillet = doc.addObject("Part::Fillet", "Fillet")
    fillet.Base = cylinder
    doc.recompute()
    top_edge = next(i for i, e in enumerate(cylinder.Shape.Edges)
                    if e.Curve.TypeId == "Part::GeomCircle" and abs(e.BoundBox.ZMin - 30) < 1e-9)
    fillet.Edges = [(top_edge + 1, radius, radius)]
    doc.recompute()
    return fillet


@pytest.mark.parametrize("radius", [3.0, 6.0])
def test_a_flat_top_replaced_g1_to_its_fillet_is_the_flat_top(doc, native, tmp_path, radius):
    """A cylinder with its top edge filleted: the top is a disc bounded by the fillet's torus, which
    meets it with a horizontal tangent. Replaced by a sheet G1 to the torus, the fairest sheet is
    that disc: the part comes back with its own volume."""
    fillet = _filleted_cylinder(doc, radius)
    top = _face_at_height(fillet.Shape, 30.0)
    filled = varsurf.make_fill_hole(fillet, f"Face{top + 1}")
    doc.recompute()
    assert filled.isValid(), filled.getStatusString()
    shape = filled.Shape
    assert filled.Closed and shape.ShapeType == "Solid" and shape.isValid() and shape.check(True) is None
    assert shape.Volume == pytest.approx(fillet.Shape.Volume, rel=1e-8)
    assert len(shape.Faces) == len(fillet.Shape.Faces)
    sheet = next(f for f in shape.Faces if f.Surface.TypeId == "Part::GeomBSplineSurface")
    assert max(abs(p.z - 30.0) for p in sheet.tessellate(0.05)[0]) <= 1e-6
    assert filled.JoinNames == ["hole edge 1"] and max(filled.JoinAngles) <= 0.01 and max(filled.JoinGaps) <= 0.001
    assert not fillet.Visibility


def test_a_top_filled_g1_to_its_fillet_reads_back_from_step(doc, native, tmp_path):
    fillet = _filleted_cylinder(doc, 3.0)
    filled = varsurf.make_fill_hole(fillet, f"Face{_face_at_height(fillet.Shape, 30.0) + 1}")
    doc.recompute()
    path = tmp_path / "filleted_top.step"
    varsurf.export_step([filled], str(path))
    assert_reads_back(filled.Shape, path, native)


def _crowned_box(doc):
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 100, 60, 40
    arcs = doc.addObject("Part::Feature", "Arcs")
    arcs.Shape = Part.Compound([Part.Arc(V(x, 0, 40), V(x, 30, 48), V(x, 60, 40)).toShape() for x in (30, 70)])
    doc.recompute()
    top = _face_at_height(box.Shape, 40.0)
    filled = varsurf.make_fill_hole(box, f"Face{top + 1}", curves=[(arcs, "Edge1"), (arcs, "Edge2")],
                                    continuity="G0")
    doc.recompute()
    assert filled.isValid(), filled.getStatusString()
    return box, arcs, filled


def _check_crown(filled, arcs, box_volume):
    shape = filled.Shape
    assert filled.Closed and shape.ShapeType == "Solid" and shape.isValid() and shape.check(True) is None
    # The arcs lie on the new top, which rises 8 mm or a little more.
    for arc in arcs.Shape.Edges:
        assert max(shape.distToShape(Part.Vertex(p))[0] for p in arc.discretize(40)) <= 0.001
    assert 48.0 - 0.001 <= shape.BoundBox.ZMax <= 50.0  # fair: a little above the arcs between them
    # The volume against columns through a fine tessellation (independent of OCCT's volume).
    columns = Columns(shape.copy())
    assert columns.odd == 0
    assert shape.Volume == pytest.approx(columns.volume(), rel=1.5e-3)
    assert shape.Volume > box_volume + 0.5 * 8.0 * 40 * 60  # the crown holds more than a thin wedge


def test_a_box_top_replaced_by_a_crown_along_two_arcs(doc, native, tmp_path):
    box, arcs, filled = _crowned_box(doc)
    _check_crown(filled, arcs, box.Shape.Volume)
    # Parametric: a longer box (the arcs still span its width) gives a longer crowned part.
    before = filled.Shape.Volume
    box.Length = 120
    doc.recompute()
    assert filled.isValid(), filled.getStatusString()
    _check_crown(filled, arcs, box.Shape.Volume)
    assert filled.Shape.Volume > before + 20 * 60 * 40


def test_the_free_edges_of_an_open_box_are_closed_by_a_flat_lid(doc, native):
    """A box shell without its top: its free edges bound a flat square, which the sheet (G0, no
    interior curve) fills exactly."""
    box = Part.makeBox(50, 30, 20)
    top = _face_at_height(box, 20.0)
    shell = Part.Shell([f for i, f in enumerate(box.Faces) if i != top])
    part = doc.addObject("Part::Feature", "OpenBox")
    part.Shape = shell
    doc.recompute()
    free = [i for i, e in enumerate(shell.Edges)
            if abs(e.BoundBox.ZMin - 20.0) < 1e-9 and abs(e.BoundBox.ZMax - 20.0) < 1e-9]
    assert len(free) == 4
    filled = varsurf.make_fill_hole(part, [f"Edge{i + 1}" for i in free], continuity="G0")
    doc.recompute()
    assert filled.isValid(), filled.getStatusString()
    assert filled.Closed and filled.Shape.check(True) is None
    assert filled.Shape.Volume == pytest.approx(50 * 30 * 20, rel=1e-9)


def test_a_shell_with_two_holes_keeps_the_one_not_filled(doc, native):
    """A box shell without top and bottom: filling the top leaves an open shell whose free edges
    are the bottom's four."""
    box = Part.makeBox(50, 30, 20)
    caps = (_face_at_height(box, 20.0), _face_at_height(box, 0.0))
    shell = Part.Shell([f for i, f in enumerate(box.Faces) if i not in caps])
    part = doc.addObject("Part::Feature", "Tube")
    part.Shape = shell
    doc.recompute()
    top = [i for i, e in enumerate(shell.Edges)
           if abs(e.BoundBox.ZMin - 20.0) < 1e-9 and abs(e.BoundBox.ZMax - 20.0) < 1e-9]
    filled = varsurf.make_fill_hole(part, [f"Edge{i + 1}" for i in top], continuity="G0")
    doc.recompute()
    assert filled.isValid(), filled.getStatusString()
    assert not filled.Closed and "open shell (4 free edges)" in filled.Status
    assert filled.Shape.Area == pytest.approx(shell.Area + 50 * 30, rel=1e-9)


def test_bad_holes_are_errors_that_say_what_to_do(doc, native, console_errors):
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    n = len(doc.Objects)
    g2 = varsurf.make_fill_hole(box, "Face6", continuity="G1")
    assert list(g2.getEnumerationsOfProperty("Continuity")) == ["G0", "G1", "G2"]
    with pytest.raises(ValueError):
        g2.Continuity = "G3"  # not a continuity
    holed = doc.addObject("Part::Feature", "Holed")
    plate = Part.makeBox(40, 40, 5).cut(Part.makeCylinder(5, 10, V(20, 20, -1)))
    holed.Shape = plate
    doc.recompute()
    top = _face_at_height(plate, 5.0)
    with_hole = varsurf.make_fill_hole(holed, f"Face{top + 1}")
    nothing = varsurf.make_fill_hole(box, "Vertex1")
    missing = varsurf.make_fill_hole(box, "Face40")
    doc.recompute()
    # G1 (the default) to a box's walls asks the sheet for two tangent planes at each corner: the
    # error names the corners.
    assert not g2.isValid() and "cannot be tangent to both" in g2.Status and "(10, 10, 10)" in g2.Status
    assert not with_hole.isValid() and "a hole of its own" in with_hole.Status
    assert "fill its holes first" in with_hole.Status
    assert not nothing.isValid() and "neither a face nor an edge" in nothing.Status
    assert not missing.isValid() and "has no Face40" in missing.Status
    assert "VarSurf: " in console_errors()
    assert len(doc.Objects) == n + 5  # nothing else added, nothing removed


def test_a_filled_part_reads_back_from_step(doc, native, tmp_path):
    _box, _arcs, filled = _crowned_box(doc)
    path = tmp_path / "crown.step"
    varsurf.export_step([filled], str(path))
    assert_reads_back(filled.Shape, path, native)


def test_the_crowned_lid_example_follows_its_box_and_sketches(doc, native, tmp_path):
    import crowned_lid
    from scenes import recompute_all, reopened

    lid = crowned_lid.build(doc)
    assert lid.isValid() and lid.Closed, lid.getStatusString()
    assert lid.Shape.check(True) is None
    box, arc = doc.getObject("Box"), doc.getObject("Arc1")
    first = lid.Shape.Volume
    box.Length = 130  # the arcs still span the top
    doc.recompute()
    assert lid.isValid() and lid.Closed, lid.getStatusString()
    assert lid.Shape.Volume > first + 30 * 60 * 40
    arc.Placement.Base = V(55, 0, 0)  # the first arc moves along the box
    doc.recompute()
    assert lid.isValid(), lid.getStatusString()
    edge = arc.Shape.Edges[0]
    assert max(lid.Shape.distToShape(Part.Vertex(p))[0] for p in edge.discretize(30)) <= 0.001
    name, volume = lid.Name, lid.Shape.Volume
    with reopened(doc, tmp_path / "lid.FCStd") as again:
        restored = again.getObject(name)
        assert type(restored.Proxy).__name__ == "FillHoleFeature"
        recompute_all(again)
        assert restored.isValid() and restored.Shape.Volume == pytest.approx(volume, rel=1e-9)


def test_the_fill_hole_command_records_lines_that_make_the_same_part(doc, native):
    """The command's selection (the box's top, then the arcs' edges), its recorded lines in one
    undoable transaction, and the part they make equal to the API's; bad selections say what to
    select."""
    from scenes import Sel
    from varsurf.app import actions, macro

    box, arcs, by_api = _crowned_box(doc)
    top = by_api.Base[1][0]
    lines = []

    def run(line):
        lines.append(line)
        macro.exec_line(line)

    made = actions.run_fill_hole_command([Sel(box, top), Sel(arcs, "Edge1", "Edge2")], do_command=run)
    assert made is not None and any("make_fill_hole" in line for line in lines), lines
    # G1 (the command's default) to a box's walls is refused at its corners; G0 is the crown.
    assert not made.isValid() and "cannot be tangent to both" in made.Status
    made.Continuity = "G0"
    doc.recompute()
    assert made.isValid() and made.Shape.Volume == pytest.approx(by_api.Shape.Volume, rel=1e-12)
    n = len(doc.Objects)
    doc.undo()
    assert len(doc.Objects) == n - 1
    errors = []
    assert actions.run_fill_hole_command([], on_error=errors.append) is None
    assert actions.run_fill_hole_command([Sel(arcs), Sel(box, top)], on_error=errors.append) is None
    assert actions.run_fill_hole_command([Sel(box, top, "Edge1")], on_error=errors.append) is None
    assert len(errors) == 3 and all("Select the face of a part to replace" in e for e in errors), errors


def test_the_corner_blend_example_is_g1_to_three_fillets_and_follows_their_radius(doc, native):
    """A box's corner where three fillets meet: the sphere patch OpenCASCADE puts there replaced
    by a sheet G1 to all three. One closed solid that passes the BOP check, the fillets' own
    volume (the sphere patch is itself G1 to them: the fairest sheet differs from it by little),
    G1 within 0.01 degrees; a new radius recomputes it."""
    import corner_blend

    blend = corner_blend.build(doc)
    fillet = doc.getObject("Fillet")
    for radius in (corner_blend.RADIUS, 4.0):
        if radius != corner_blend.RADIUS:
            fillet.Edges = [(k, radius, radius) for k, _r1, _r2 in fillet.Edges]
            blend.Base = (fillet, f"Face{corner_blend.corner_patch(fillet.Shape) + 1}")  # its number may change
            doc.recompute()
        assert blend.isValid() and blend.Closed, blend.getStatusString()
        assert blend.Shape.check(True) is None
        assert len(blend.JoinNames) == 3  # the patch's collapsed (pole) edge bounds nothing
        assert max(blend.JoinGaps) <= 0.001 and max(blend.JoinAngles) <= 0.01, (blend.JoinGaps, blend.JoinAngles)
        assert blend.Shape.Volume == pytest.approx(fillet.Shape.Volume, rel=1e-5)
        sheet = next(f for f in blend.Shape.Faces if f.Surface.TypeId == "Part::GeomBSplineSurface")
        # The fairest sheet is not the sphere, but close to it (measured 0.4 % more area at radius 4).
        assert sheet.Area == pytest.approx(fillet.Shape.Faces[corner_blend.corner_patch(fillet.Shape)].Area, rel=1e-2)


def test_g2_where_fillets_meet_is_refused_naming_the_corners(doc, native, console_errors):
    """G2 to three fillets at a box's corner cannot hold (each fillet is flat along its axis, the
    next one's arc is curved along the same direction there): the FillHole says so, naming each
    corner and by how much the curvatures differ, before any solve."""
    import corner_blend

    blend = corner_blend.build(doc)
    blend.Continuity = "G2"
    doc.recompute()
    assert not blend.isValid()
    assert blend.Status.count("curvatures differ by 100 %") == 3, blend.Status
    assert "join one of them G1" in blend.Status and "meet at (" in blend.Status
    assert "CornerBlend" in console_errors()
    blend.Continuity = "G1"
    doc.recompute()
    assert blend.isValid() and blend.Closed
