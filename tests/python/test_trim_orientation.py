# SPDX-License-Identifier: LGPL-2.1-or-later
"""A Sheet keeps its base face's trim and orientation.

Base faces built the way a FreeCAD user builds them: the top of a box with a cylinder cut out (a
plate with a hole), a disc (Part.Face of a circle's wire), the top of a box with a chamfered
corner, a fillet face (a cylinder patch, trimmed where the fillets meet), and the six faces of a
Part box (three of them Reversed). With no curves the sheet is its base face: same area (to
1e-6), within 1e-9 of the model's size of it both ways (OCCT's distToShape from points sampled on
each onto the other), and check(True) passes. Curves over the hole or outside the disc are
refused with a message naming them. Pressure > 0 inflates every face of a box outward.
"""

import math

import pytest

import FreeCAD
import Part
from FreeCAD import Vector

import pillow
import varsurf
from brep_measure import farthest, inside_points
from varsurf.solve import errors
from varsurf.solve.sheet import solve_sheet_on_face
from varsurf.solve.constraints import ConstraintSpec


def plate_top():
    """Top face (z = 40) of a 100 x 80 x 40 box minus a cylinder of radius 10 at its middle."""
    plate = Part.makeBox(100, 80, 40).cut(Part.makeCylinder(10, 60, Vector(50, 40, -10)))
    return next(f for f in plate.Faces if abs(f.CenterOfMass.z - 40) < 1e-9 and len(f.Wires) == 2)


def disc():
    return Part.Face(Part.Wire(Part.makeCircle(30, Vector(0, 0, 0), Vector(0, 0, 1))))


def chamfered_top():
    """Top of a 60 x 60 x 20 box whose vertical edge at (60, 60) is chamfered by 5 mm."""
    box = Part.makeBox(60, 60, 20)
    edge = next(e for e in box.Edges if e.CenterOfMass.isEqual(Vector(60, 60, 10), 1e-9))
    solid = box.makeChamfer(5, [edge])
    return next(f for f in solid.Faces if abs(f.CenterOfMass.z - 20) < 1e-9)


def fillet_face():
    """One of the four fillets (radius 8) along the top edges of a 60 x 60 x 20 box: a cylinder
    patch cut by the neighbouring fillets' mitres."""
    box = Part.makeBox(60, 60, 20)
    solid = box.makeFillet(8, [e for e in box.Edges if abs(e.CenterOfMass.z - 20) < 1e-9])
    return next(f for f in solid.Faces if f.Surface.TypeId == "Part::GeomCylinder")


def drilled_cone():
    """A cone (radii 20 and 10, 40 high) drilled across by a cylinder of radius 5: its conical face
    with the two holes, and the hole's wall (a full turn of a cylinder, cut by the cone)."""
    cone = Part.makeCone(20, 10, 40).cut(Part.makeCylinder(5, 100, Vector(0, -50, 20), Vector(0, 1, 0)))
    return (next(f for f in cone.Faces if f.Surface.TypeId == "Part::GeomCone"),
            next(f for f in cone.Faces if f.Surface.TypeId == "Part::GeomCylinder"))


#: Surfaces whose NURBS conversion changes their parameters (a rational arc is not parametrized by
#: angle): the base face's edges are carried through the change.
CONVERTED = {
    "drilled cone": lambda: drilled_cone()[0],
    "drilled hole's wall": lambda: drilled_cone()[1],
    "dome with its pole, cut off-centre": lambda: next(
        f for f in Part.makeSphere(30).common(Part.makeBox(100, 100, 100, Vector(-5, -50, 10))).Faces
        if f.Surface.TypeId == "Part::GeomSphere"),
}

SCENES = {
    "plate with a hole": plate_top,
    "disc": disc,
    "chamfered top": chamfered_top,
    "fillet face": fillet_face,
}


@pytest.mark.parametrize("scene", list(SCENES))
def test_sheet_without_curves_is_its_trimmed_base_face(scene, native):
    base = SCENES[scene]()
    outcome = solve_sheet_on_face(base, [], rest="base")  # the Sheet feature's default
    result = outcome.shape
    size = base.BoundBox.DiagonalLength
    # The untrimmed sheet filled the hole (8,000 instead of 7,686 mm²), squared the disc and
    # overhung the chamfer (by 21 mm) and the fillet (by 4.9 mm). Areas integrated by OCCT to
    # 1e-10: Part's Area is off by 2e-5 on the fillet's rational sheet.
    area = [native.mass_properties(f.exportBrepToString(), 1e-10)[0] for f in (base, result)]
    assert area[1] == pytest.approx(area[0], rel=1e-9)
    assert result.check(True) is None  # raises on any BRepCheck or BOP problem
    assert result.distToShape(base)[0] <= 1e-9 * size
    assert farthest(inside_points(result, 40, 1), base) <= 1e-9 * size
    assert farthest(inside_points(base, 40, 2), result) <= 1e-9 * size
    # Both boundaries coincide: every vertex of the base is a vertex of the result.
    assert farthest([v.Point for v in base.Vertexes], Part.Compound(result.Vertexes)) <= 1e-7 * size
    assert len(result.Wires) == len(base.Wires)


@pytest.mark.parametrize("scene", list(CONVERTED))
def test_converted_surfaces_keep_their_trim(scene, native):
    """Area integrated by OCCT to 1e-10 (Part's Area is off by ~2e-4 on these rational faces)."""
    base = CONVERTED[scene]()
    result = solve_sheet_on_face(base, [], rest="base").shape
    size = base.BoundBox.DiagonalLength
    area = [native.mass_properties(f.exportBrepToString(), 1e-10)[0] for f in (base, result)]
    assert area[1] == pytest.approx(area[0], rel=1e-6)  # measured: 1e-11
    assert result.isValid()
    assert farthest(inside_points(result, 30, 1), base) <= 1e-9 * size
    assert farthest(inside_points(base, 30, 2), result) <= 1e-9 * size
    # The boundary is the base's: points along each base edge lie on the result's edges.
    along = [p for e in base.Edges if not e.Degenerated for p in e.discretize(20)]
    assert farthest(along, Part.Compound(result.Edges)) <= 1e-7 * size


def test_curves_over_the_hole_are_refused_and_others_met():
    base = plate_top()
    across = Part.makeLine(Vector(20, 40, 45), Vector(80, 40, 45))  # crosses the hole
    with pytest.raises(errors.SheetError, match=r"Sketch:Edge2 lies over a hole of the base face"):
        solve_sheet_on_face(base, [across], names=["Sketch:Edge2"])
    beside = Part.makeLine(Vector(20, 20, 43), Vector(80, 20, 43))  # on the plate, beside it
    outcome = solve_sheet_on_face(base, [beside], names=["Sketch:Edge1"])
    assert outcome.max_deviation < 0.01
    assert outcome.shape.distToShape(beside)[0] < 0.01
    assert len(outcome.shape.Wires) == 2  # still holed
    assert outcome.shape.check(True) is None
    # Constraints over the hole are refused too: a point, and a join along an edge across it.
    point = ConstraintSpec(kind="Point", name="Lift", location=(50.0, 43.0, 45.0))
    with pytest.raises(errors.SheetError, match=r"Lift lies over a hole of the base face"):
        solve_sheet_on_face(base, [], constraints=[point])
    join = ConstraintSpec(kind="G0", name="Join", edge=across)
    with pytest.raises(errors.SheetError, match=r"Join lies over a hole of the base face \(up to 10 mm"):
        solve_sheet_on_face(base, [], constraints=[join])


def _hole_rim(shape):
    """Points along the edges of `shape` that bound the plate's hole (radius 10 about (50, 40))."""
    return [p for e in shape.Edges if math.hypot(e.CenterOfMass.x - 50, e.CenterOfMass.y - 40) < 11
            for p in e.discretize(40)]


def test_a_kept_boundary_keeps_the_holes_rim():
    """FixBoundary keeps the base face's boundary: the hole's rim too, not only the rectangle's."""
    base = plate_top()
    ridge = Part.makeLine(Vector(20, 25, 45), Vector(80, 25, 45))  # 5 mm above the plate, beside the hole
    kept = solve_sheet_on_face(base, [ridge], rest="base", tolerance=0.01)
    rim = _hole_rim(kept.shape)
    assert rim and max(abs(p.z - 40) for p in rim) <= 0.01  # measured: 0.0013 mm
    assert max(abs(math.hypot(p.x - 50, p.y - 40) - 10) for p in rim) < 1e-6
    free = solve_sheet_on_face(base, [ridge], rest="base", tolerance=0.01, fix_boundary=False)
    assert max(p.z for p in _hole_rim(free.shape)) > 41  # without it the rim lifts with the ridge


def test_curves_outside_the_disc_are_refused():
    base = disc()
    corner = Part.makeLine(Vector(20, 24, 2), Vector(28, 28, 2))  # in the square, not the disc
    with pytest.raises(errors.SheetError, match=r"Sketch:Edge1 lies outside the base face's boundary"):
        solve_sheet_on_face(base, [corner], names=["Sketch:Edge1"])
    inside = Part.makeLine(Vector(-10, -10, 3), Vector(10, 10, 3))
    outcome = solve_sheet_on_face(base, [inside])
    assert outcome.max_deviation < 0.01
    assert outcome.shape.check(True) is None
    # Its boundary is still the circle, kept in place (FixBoundary) within the tolerance.
    rim = [p for e in outcome.shape.Edges for p in e.discretize(50)]
    assert max(abs(math.hypot(p.x, p.y) - 30.0) for p in rim) < 1e-6
    assert max(abs(p.z) for p in rim) <= 0.01


def test_a_curve_within_the_tolerance_of_the_holes_edge_is_accepted():
    """A curve 0.005 mm inside the hole, at tolerance 0.01 mm, lies on the face's boundary."""
    base = plate_top()
    arc = Part.Edge(Part.ArcOfCircle(Part.Circle(Vector(50, 40, 40), Vector(0, 0, 1), 10.0 - 0.005),
                                     0.2, 1.2))
    outcome = solve_sheet_on_face(base, [arc], tolerance=0.01, names=["Arc"])
    assert outcome.max_deviation <= 0.01
    deeper = Part.Edge(Part.ArcOfCircle(Part.Circle(Vector(50, 40, 40), Vector(0, 0, 1), 10.0 - 0.05),
                                        0.2, 1.2))
    with pytest.raises(errors.SheetError, match=r"Arc lies over a hole of the base face \(up to 0.05 mm"):
        solve_sheet_on_face(base, [deeper], tolerance=0.01, names=["Arc"])


@pytest.mark.parametrize("index", range(6))
def test_pressure_inflates_every_box_face_outward(index):
    """Faces 1, 3 and 5 of a Part box are Reversed: their sheets used to flip inward."""
    box = Part.makeBox(100, 80, 40)
    base = box.Faces[index]
    centre = base.CenterOfMass
    outward = base.normalAt(*base.Surface.parameter(centre))
    inward_point = box.BoundBox.Center
    assert (centre - inward_point).dot(outward) > 0  # the face's normal is the box's outward one
    outcome = solve_sheet_on_face(base, [], pressure=0.001, stretch=1.0)
    result = outcome.shape
    assert result.Orientation == base.Orientation
    uv = result.Surface.parameter(centre)
    moved = result.valueAt(*uv) - centre
    assert moved.dot(outward) > 0.05  # inflated outward (0.09 to 0.29 mm here)
    assert moved.dot(outward) == pytest.approx(moved.Length, rel=1e-6)
    assert result.normalAt(*uv).dot(outward) > 0.999


def test_pressure_inflates_a_reversed_holed_face_outward():
    """The plate's bottom (z = 0) is Reversed and holed: the sheet bulges down, out of the plate,
    keeps its hole, and faces down like its base."""
    plate = Part.makeBox(100, 80, 40).cut(Part.makeCylinder(10, 60, Vector(50, 40, -10)))
    base = next(f for f in plate.Faces if abs(f.CenterOfMass.z) < 1e-9 and len(f.Wires) == 2)
    assert base.Orientation == "Reversed"
    result = solve_sheet_on_face(base, [], pressure=0.001, stretch=1.0).shape
    assert result.Orientation == "Reversed" and len(result.Wires) == 2
    z = [p.z for p in inside_points(result, 200, 4)]
    assert min(z) < -0.05 and max(z) <= 0.01  # measured: -0.11 mm; the rims stay at z = 0 (Tolerance)
    u, v = result.Surface.parameter(Vector(20, 20, 0))
    assert result.normalAt(u, v).z < -0.99


def test_sheet_feature_on_a_cut_box_keeps_the_hole(doc):
    """Through the document, the way the GUI makes it: a Sheet on the top of Part Box - Cylinder."""
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 100, 80, 40
    cylinder = doc.addObject("Part::Cylinder", "Cylinder")
    cylinder.Radius, cylinder.Height = 10, 60
    cylinder.Placement.Base = FreeCAD.Vector(50, 40, -10)
    cut = doc.addObject("Part::Cut", "Cut")
    cut.Base, cut.Tool = box, cylinder
    doc.recompute()
    name = next(f"Face{i + 1}" for i, f in enumerate(cut.Shape.Faces)
                if abs(f.CenterOfMass.z - 40) < 1e-9 and len(f.Wires) == 2)
    sheet = varsurf.make_sheet((cut, name), [])
    doc.recompute()
    assert sheet.Status.startswith("OK"), sheet.Status
    assert sheet.Shape.Area == pytest.approx(100 * 80 - math.pi * 100, rel=1e-6)


def test_solid_joins_sheets_on_trimmed_faces(doc):
    """The pillow on two discs (radius 50) instead of rectangles: each Sheet is a trimmed disc, and
    the Solid trims the sheets to their shared rim all the same. Its faces lie on the sheets."""
    rim = pillow.add_rim(doc)  # the pillow example's rim
    sheets = []
    for name, pressure in (("Top", 0.1), ("Bottom", -0.1)):
        base = doc.addObject("Part::Feature", name + "Base")
        base.Shape = disc().scale(50 / 30)
        doc.recompute()
        sheet = varsurf.make_sheet((base, "Face1"), [(rim, "Edge1")], name=name)
        sheet.Stretch, sheet.Tolerance, sheet.Pressure = 1.0, 0.001, pressure
        sheets.append(sheet)
    solid = varsurf.make_solid(sheets, name="Pillow")
    doc.recompute()
    for sheet in sheets:
        assert sheet.Status.startswith("OK"), sheet.Status
        assert len(sheet.Shape.Edges) == 1 and sheet.Shape.Area < math.pi * 50 ** 2 * 1.2  # a disc
    assert solid.Status.startswith("OK: solid"), solid.Status
    shape = solid.Shape
    assert shape.check(True) is None and shape.Volume > 0
    assert len(shape.Faces) == 2
    top, bottom = sorted(shape.Faces, key=lambda f: -f.CenterOfMass.z)
    for face, sheet in ((top, sheets[0]), (bottom, sheets[1])):
        assert farthest(inside_points(face, 30, 3), sheet.Shape) <= 1e-6
        assert face.Area < sheet.Shape.Area  # trimmed to the rim, inside the disc


@pytest.mark.parametrize("scene", list(SCENES))
def test_the_result_crosses_as_binary_brep_unchanged(scene, native):
    """A sheet's face comes back from the extension as binary BREP (read by Part's importBinary):
    the same face, orientation and trim included, as the BREP text path gives, to the last bit of
    its written text. The base is also tried reversed."""
    from varsurf.solve.shapes import shape_from_binary, shape_from_brep

    for base in (SCENES[scene](), SCENES[scene]().reversed()):
        text = base.exportBrepToString()
        trim = native.BaseTrim(text)
        surface = native.surface_from_face_brep(solve_sheet_on_face(base, [], rest="base").shape.exportBrepToString())
        by_text = shape_from_brep(trim.face_brep(surface))
        by_binary = shape_from_binary(trim.face_binary(surface))
        assert by_binary.Orientation == by_text.Orientation == base.Orientation
        assert by_binary.exportBrepToString() == by_text.exportBrepToString()
        assert by_binary.isValid()
