# SPDX-License-Identifier: LGPL-2.1-or-later
"""The SubdSurface feature (Boier-Martin, Ronfard & Bernardini's multiresolution surfaces) on
FreeCAD inputs: a Part Box's faces as the cage capture a Part Sphere, the fit measured again
against the exact sphere and converging with the levels; a Mesh sphere as a scan; a VarSurf
sheet's pole net as a cage; pins with their region of influence; rigid motion; saving, reopening
and undo; bad input named with the object in error and the document intact."""

import math

import FreeCAD
import Mesh
import Part
import pytest

import varsurf
from scenes import reopened, railed_sheet

V = FreeCAD.Vector
RADIUS = 13.0


def box_and_sphere(doc, place=FreeCAD.Placement()):
    box = doc.addObject("Part::Box", "Cage")
    box.Length = box.Width = box.Height = 20.0
    box.Placement = place.multiply(FreeCAD.Placement(V(-10, -10, -10), FreeCAD.Rotation()))
    sphere = doc.addObject("Part::Sphere", "Target")
    sphere.Radius = RADIUS
    sphere.Placement = place
    doc.recompute()
    return box, sphere


def limit_points(subd):
    return [V(*p) for p in subd.Proxy.outcome.points]


def test_a_box_cage_captures_a_sphere_and_converges_with_the_levels(doc):
    box, sphere = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=3, target=sphere)
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    assert subd.FaceCount == 6 * 4 ** 3
    assert subd.Mesh.CountFacets == 2 * subd.FaceCount and subd.Mesh.isSolid()
    assert not box.Visibility and not sphere.Visibility  # the cage and target stand behind it
    # Measured again against the exact sphere: the reported fit (against the tessellated target)
    # agrees within the tessellation's tolerance.
    exact = max(abs(p.Length - RADIUS) for p in limit_points(subd))
    tolerance = 5e-4 * sphere.Shape.BoundBox.DiagonalLength
    assert abs(exact - subd.FitMax) < 2 * tolerance, (exact, subd.FitMax)
    assert subd.FitRms <= subd.FitMax
    errors = {3: exact}
    subd.Levels = 4
    doc.recompute()
    errors[4] = max(abs(p.Length - RADIUS) for p in limit_points(subd))
    # The limit surface between captured vertices converges at second order.
    assert errors[4] < errors[3] / 3, errors
    assert "captured within" in subd.Status


def test_a_mesh_scan_as_target_and_a_sheets_pole_net_as_cage(doc):
    import MeshPart

    scan = doc.addObject("Mesh::Feature", "Scan")
    deflection = 0.02
    scan.Mesh = MeshPart.meshFromShape(Part.makeSphere(RADIUS), LinearDeflection=deflection)
    box, _ = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=3, target=scan)
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    # Measured on the exact sphere, the fit differs from the one reported against the scan by no
    # more than the scan's own deflection.
    exact = max(abs(p.Length - RADIUS) for p in limit_points(subd))
    assert abs(exact - subd.FitMax) < 2 * deflection, (exact, subd.FitMax)
    sheet = railed_sheet(doc)
    net = varsurf.make_subd_surface(sheet, levels=2, name="FromSheet")
    doc.recompute()
    assert net.isValid(), net.getStatusString()
    poles = sheet.Shape.Faces[0].Surface.getPoles()
    assert net.FaceCount == (len(poles) - 1) * (len(poles[0]) - 1) * 16
    # A pole net's limit surface lies within the poles' box and near the sheet.
    face = sheet.Shape.Faces[0]
    assert max(face.distToShape(Part.Vertex(p))[0] for p in limit_points(net)[::37]) < 1.0


def pin_scene(doc, influence, levels=3, captured=True):
    box, sphere = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=levels, target=sphere if captured else None)
    doc.recompute()
    points = limit_points(subd)
    finest = subd.Proxy.outcome.levels[-1]
    top = min(range(len(finest)), key=lambda k: (V(*finest[k]) - V(0, 0, RADIUS)).Length)
    target = V(*finest[top]) + V(0, 0, 6.0)
    varsurf.set_pins(subd, [(levels, top, target, influence)])
    doc.recompute()
    return subd, points, top, target


def test_a_pin_moves_its_region_of_influence(doc):
    """The same pin on a 6,144-face surface propagated to the cage moves most of it; to finer
    levels, less and less."""
    subd, before, top, target = pin_scene(doc, 0, levels=5)
    fractions = []
    for influence in range(6):
        varsurf.set_pins(subd, [(5, top, target, influence)])
        doc.recompute()
        assert subd.isValid(), subd.getStatusString()
        assert subd.PinResidual < 1e-6
        assert (V(*subd.Proxy.outcome.levels[-1][top]) - target).Length < 1e-6
        after = limit_points(subd)
        fractions.append(sum((p - q).Length > 1e-6 for p, q in zip(before, after)) / len(after))
    # Level 3 has 384 faces: its region (the mask and one ring, about 5 x 5 faces) is a fifth of
    # them; level 4's, with 1,536 faces, under a twentieth.
    assert fractions[0] >= 0.5 and fractions[3] < 0.25 and fractions[4] < 0.05 and fractions[5] < 0.01, fractions
    assert all(a >= b for a, b in zip(fractions, fractions[1:])) and fractions[2] > fractions[3], fractions


def test_the_surface_moves_rigidly_with_its_scene(doc):
    subd, _, top, target = pin_scene(doc, 1, captured=False)
    reference = limit_points(subd)
    motion = FreeCAD.Placement(V(40, -25, 7), FreeCAD.Rotation(V(1, 2, -1), 35))
    for name in ("Cage", "Target"):
        obj = doc.getObject(name)
        obj.Placement = motion.multiply(obj.Placement)
    varsurf.set_pins(subd, [(3, top, motion.multVec(target), 1)])
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    moved = limit_points(subd)
    # The cage's vertex numbering is the same (a box's), so the points correspond one to one.
    assert max((motion.multVec(p) - q).Length for p, q in zip(reference, moved)) < 1e-4


def test_saves_reopens_and_undoes(doc, tmp_path):
    subd, _, top, target = pin_scene(doc, 1)
    pinned = [tuple(p) for p in subd.Proxy.outcome.points]
    doc.openTransaction("Move pin")
    varsurf.set_pins(subd, [(3, top, target + V(3, 0, 0), 1)])
    doc.commitTransaction()
    doc.recompute()
    assert max((V(*p) - V(*q)).Length for p, q in zip(pinned, subd.Proxy.outcome.points)) > 1.0
    doc.undo()
    doc.recompute()
    assert max((V(*p) - V(*q)).Length for p, q in zip(pinned, subd.Proxy.outcome.points)) < 1e-9
    name = subd.Name
    with reopened(doc, tmp_path / "subd.FCStd") as again:
        copy = again.getObject(name)
        assert copy.Mesh.CountFacets == subd_facets(pinned)
        copy.touch()
        again.recompute()
        assert copy.isValid(), copy.getStatusString()
        assert max((V(*p) - V(*q)).Length for p, q in zip(pinned, copy.Proxy.outcome.points)) < 1e-9


def limit_normal(brep, point):
    """The B-rep's face normal at its point nearest to `point` (OCC's evaluation, independent of
    the core's divided differences)."""
    best = min(brep.Shape.Faces, key=lambda f: f.distToShape(Part.Vertex(point))[0])
    u, v = best.Surface.parameter(point)
    return best.Surface.normal(u, v)


@pytest.mark.parametrize("motion", [FreeCAD.Placement(),
                                    FreeCAD.Placement(V(40, -25, 7), FreeCAD.Rotation(V(1, 2, -1), 35))])
def test_a_prescribed_normal_tilts_the_surface_there(doc, motion):
    """The top of a sphere-captured box raised with its normal held 25 degrees off the vertical
    (Boier-Martin et al.'s normal constraint): the surface's normal there, measured on the
    SubdBRep's faces by OCC, follows to a fraction of the tilt, while without the normal it stays
    vertical; the same scene moved rigidly gives the moved answer."""
    subd, _, top, target = pin_scene(doc, 1)
    tilt = FreeCAD.Rotation(V(1, 0, 0), 25).multVec(V(0, 0, 1))
    for name in ("Cage", "Target"):
        obj = doc.getObject(name)
        obj.Placement = motion.multiply(obj.Placement)
    moved_target = motion.multVec(target)
    varsurf.set_pins(subd, [(3, top, moved_target, 1)])
    brep = varsurf.make_subd_brep(subd, isolation=3)
    doc.recompute()
    up = motion.Rotation.multVec(V(0, 0, 1))
    level = math.degrees(limit_normal(brep, moved_target).getAngle(up))
    assert level < 0.5, level
    varsurf.set_normals(subd, [(3, top, motion.Rotation.multVec(tilt), 1)])
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    assert subd.NormalAngle < 1e-4 and subd.PinResidual < 1e-6, (subd.NormalAngle, subd.PinResidual)
    assert "normals within" in subd.Status
    normal = limit_normal(brep, V(*subd.Proxy.outcome.points[top]))
    angle = math.degrees(min(normal.getAngle(motion.Rotation.multVec(tilt)),
                             normal.getAngle(-motion.Rotation.multVec(tilt))))
    assert angle < 0.1 * 25, angle  # the limit averages the ring the constraint holds
    assert brep.isValid() and brep.Shape.isValid()


def subd_facets(points):
    return 2 * (len(points) - 2)  # a closed quad mesh of genus 0: F = V - 2 quads, two triangles each


def box_mesh():
    import MeshPart

    return MeshPart.meshFromShape(Part.makeBox(10, 10, 10), LinearDeflection=1.0)


def fine_mesh():
    import MeshPart

    return MeshPart.meshFromShape(Part.makeSphere(10.0), LinearDeflection=0.2)


def flipped_mesh():
    points, facets = box_mesh().Topology
    facets = [tuple(f) for f in facets]
    facets[0] = facets[0][::-1]
    out = Mesh.Mesh()
    out.addFacets((points, facets))
    return out


@pytest.mark.parametrize("edit, words", [
    (lambda d, s: setattr(d.getObject("Bad"), "Mesh", flipped_mesh()) or setattr(s, "Source", d.getObject("Bad")),
     "inconsistently oriented"),
    (lambda d, s: setattr(d.getObject("Target"), "Placement", FreeCAD.Placement(V(500, 0, 0), FreeCAD.Rotation())),
     "too far from the cage"),
    (lambda d, s: varsurf.set_pins(s, [(2, 10 ** 6, V(), 0)]), "pick one of those"),
    (lambda d, s: varsurf.set_pins(s, [(3, 1, V(), 0)]), "level 3 does not exist"),
    (lambda d, s: varsurf.set_pins(s, [(2, 3, V(), 3)]), "influence level must lie in 0..2"),
    (lambda d, s: setattr(s, "PinLevels", [3, 3]), "give each pin one of each"),
    (lambda d, s: varsurf.set_normals(s, [(2, 5, V(0, 0, 0), 1)]), "is zero or not finite: give a direction"),
    (lambda d, s: varsurf.set_normals(s, [(2, 9999, V(0, 0, 1), 1)]), "the normal on vertex 9999 of level 2"),
    (lambda d, s: varsurf.set_normals(s, [(1, 5, V(0, 0, 1), 1), (1, 5, V(1, 0, 1), 0)]), "given twice"),
    (lambda d, s: setattr(s, "NormalLevels", [2]), "give each normal one of each"),
    (lambda d, s: setattr(d.getObject("Bad"), "Mesh", fine_mesh()) or setattr(s, "Source", d.getObject("Bad"))
     or setattr(s, "Levels", 8), "lower Levels to"),
    (lambda d, s: setattr(s, "Source", None), "no Source"),
])
def test_bad_input_is_named_and_leaves_the_document_intact(doc, edit, words):
    doc.addObject("Mesh::Feature", "Bad").Mesh = box_mesh()
    box, sphere = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=2, target=sphere, pins=[(2, 5, V(0, 0, 12), 1)])
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    edit(doc, subd)
    doc.recompute()
    assert not subd.isValid()
    assert words in subd.getStatusString(), subd.getStatusString()
    assert subd.getStatusString().count("\n") == 0
    assert box.isValid() and sphere.isValid()
    assert math.isclose(box.Shape.Volume, 8000.0)


def test_the_limit_surface_as_a_brep_solid_survives_step(doc, native, tmp_path):
    """A captured SubdSurface as a SubdBRep: a closed solid of bicubic faces whose regular seams
    are tangent to rounding, whose end caps lie within their measured deviation of the limit and
    shrink with the isolation, and whose STEP file reads back through check(True)."""
    from step_check import assert_reads_back

    box, sphere = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=2, target=sphere)
    brep = varsurf.make_subd_brep(subd, isolation=3)
    doc.recompute()
    assert brep.isValid(), brep.getStatusString()
    assert brep.Closed and brep.Shape.ShapeType == "Solid" and brep.Shape.isValid()
    assert len(brep.Shape.Faces) == brep.FaceCount
    assert brep.EndCapCount == 24  # the cube's 8 valence-3 corners, 3 faces each
    # 96 finest faces: the 24 at the corners an end cap and two rectangles each, each side's
    # other 12 in one or two rectangles.
    assert brep.FaceCount <= 24 * 3 + 2 * 6 < brep.PatchCount
    assert brep.RegularSeamAngle < 1e-6
    assert 0.0 < brep.EndCapSeamAngle < 1.0
    # The faces lie on the limit surface: the limit points of the finest vertices (exact, from
    # the core) are on the solid's boundary within the end caps' deviation.
    boundary = brep.Shape.Shells[0]
    worst = max(boundary.distToShape(Part.Vertex(V(*p)))[0] for p in subd.Proxy.outcome.points[::5])
    assert worst <= brep.EndCapDeviation + 1e-7, (worst, brep.EndCapDeviation)
    deviation = brep.EndCapDeviation
    brep.Isolation = 5
    doc.recompute()
    assert brep.EndCapDeviation < deviation / 3 and brep.RegularSeamAngle < 1e-6
    path = tmp_path / "subd.step"
    varsurf.export_step(brep, str(path))
    assert_reads_back(brep.Shape, path, native)
    name, faces = brep.Name, brep.FaceCount
    with reopened(doc, tmp_path / "subd_brep.FCStd") as again:
        copy = again.getObject(name)
        assert copy.Closed and len(copy.Shape.Faces) == faces
        copy.touch()
        again.recompute()
        assert copy.isValid(), copy.getStatusString()


def test_the_merged_faces_are_the_patches(doc, native):
    """The SubdBRep's larger faces (regular patches merged into C2 B-splines, a refined face's
    pieces into one) against the patches themselves, sewn a face each by the OCC bridge: the same
    area and volume to 1e-9, and points of every merged face on the patches' shell within 1e-9
    of the size; MaxSpan 1 merges no mesh faces."""
    from varsurf.solve.shapes import shape_from_brep

    box, sphere = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=3, target=sphere)
    brep = varsurf.make_subd_brep(subd, isolation=3)
    doc.recompute()
    assert brep.isValid(), brep.getStatusString()
    outcome = subd.Proxy.outcome
    finest = native.SubdivisionMesh(outcome.levels[-1], [list(f) for f in outcome.faces[-1]])
    patches = native.limit_patches(finest, 3).patches
    one_each = shape_from_brep(native.patch_shell([p.surface for p in patches], [not p.regular for p in patches],
                                                  1e-7 * 20).shell.brep)
    assert len(one_each.Faces) == brep.PatchCount > 5 * brep.FaceCount, (brep.PatchCount, brep.FaceCount)
    merged = brep.Shape
    # Integrated to 1e-11 (Shape.Area's default integration is off by 8e-7 on the merged faces).
    area, volume = native.mass_properties(merged.exportBrepToString(), 1e-11)
    assert (area, volume) == pytest.approx(native.mass_properties(one_each.exportBrepToString(), 1e-11), rel=1e-9)
    worst = 0.0
    for face in merged.Faces:
        u0, u1, v0, v1 = face.ParameterRange
        for a, b in ((0.13, 0.71), (0.5, 0.5), (0.91, 0.07), (0.37, 0.29)):
            point = face.valueAt(u0 + a * (u1 - u0), v0 + b * (v1 - v0))
            near = [f for f in one_each.Faces if f.BoundBox.isInside(point)]  # a point on them: in its own box
            worst = max(worst, min(f.distToShape(Part.Vertex(point))[0] for f in near))
    assert worst < 1e-9 * 20, worst
    brep.MaxSpan = 1
    doc.recompute()
    assert brep.isValid(), brep.getStatusString()
    assert len(brep.Shape.Faces) == brep.FaceCount >= len(finest.faces) == 6 * 64
    assert native.mass_properties(brep.Shape.exportBrepToString(), 1e-11)[1] == pytest.approx(volume, rel=1e-9)


def test_a_subd_brep_without_a_subd_surface_says_so(doc):
    box, _ = box_and_sphere(doc)
    subd = varsurf.make_subd_surface(box, levels=1)
    brep = varsurf.make_subd_brep(subd)
    doc.recompute()
    assert brep.isValid(), brep.getStatusString()
    brep.Base = box
    doc.recompute()
    assert not brep.isValid() and "link the SubdSurface" in brep.getStatusString()


def test_the_commands_record_their_lines_and_undo(doc):
    """VarSurf_SubdSurface on a selected cage and target, then VarSurf_SubdBRep on the result:
    each records its lines, runs in one undoable transaction, and equals the API's; bad
    selections say what to select."""
    from scenes import Sel
    from varsurf.app import actions, macro

    box, sphere = box_and_sphere(doc)
    lines = []

    def run(line):
        lines.append(line)
        macro.exec_line(line)

    subd = actions.run_subd_surface_command([Sel(box), Sel(sphere)], do_command=run)
    assert subd is not None and subd.isValid(), subd and subd.getStatusString()
    assert any("make_subd_surface" in line and "target=" in line for line in lines), lines
    by_api = varsurf.make_subd_surface(box, levels=3, target=sphere, name="ByApi")
    doc.recompute()
    assert max((V(*p) - V(*q)).Length for p, q in zip(subd.Proxy.outcome.points, by_api.Proxy.outcome.points)) == 0
    brep = actions.run_subd_brep_command([Sel(subd)], do_command=run)
    assert brep is not None and brep.isValid() and brep.Closed, brep and brep.getStatusString()
    n, name = len(doc.Objects), brep.Name
    doc.undo()
    assert len(doc.Objects) == n - 1 and doc.getObject(name) is None
    errors = []
    assert actions.run_subd_surface_command([], on_error=errors.append) is None
    assert actions.run_subd_surface_command([Sel(box), Sel(sphere), Sel(box)], on_error=errors.append) is None
    assert actions.run_subd_brep_command([Sel(box)], on_error=errors.append) is None
    assert len(errors) == 3 and all("Select" in e for e in errors), errors


def test_a_pin_drag_shows_the_approximate_answer_and_writes_one_step(doc):
    """Each move of a dragged pin gives the limit surface the feature computes with Solve =
    Approximate for that target (from the captured levels the recompute kept); the release is one
    undoable step, recorded as a move_pin line, and the recompute refines it (Direct)."""
    from varsurf.app import macro, subd_drag

    subd, _, top, target = pin_scene(doc, 1)
    session = subd_drag.PinDrag(subd, 0)
    moved = target + V(2, -1, 3)
    shown = session.move(moved)
    twin = varsurf.make_subd_surface(doc.getObject("Cage"), levels=3, target=doc.getObject("Target"),
                                     pins=[(3, top, moved, 1)], solve="Approximate", name="Twin")
    doc.recompute()
    # The drag meets its pin to 1e-6 of the model's size, the recompute to 1e-9.
    size = subd.Mesh.BoundBox.DiagonalLength
    assert max((V(*p) - V(*q)).Length for p, q in zip(shown, twin.Proxy.outcome.points)) < 2e-6 * size
    lines = []

    def run(line):
        lines.append(line)
        macro.exec_line(line)

    session.finish(moved, do_command=run)
    assert any("varsurf.move_pin(" in line for line in lines), lines
    assert subd.isValid() and (V(subd.PinTargets[0]) - moved).Length < 1e-12
    assert (V(*subd.Proxy.outcome.levels[-1][top]) - moved).Length < 1e-6
    assert doc.UndoNames[0] == subd_drag.TRANSACTION
    doc.undo()
    doc.recompute()
    assert (V(subd.PinTargets[0]) - target).Length < 1e-12
    with pytest.raises(ValueError, match="no pin 3"):
        subd_drag.PinDrag(subd, 3)


def test_pin_order_does_not_matter(doc):
    """Two pins given in either order (and a normal with them) give the same surface."""
    subd, _, top, target = pin_scene(doc, 1)
    finest = subd.Proxy.outcome.levels[-1]
    side = min(range(len(finest)), key=lambda k: (V(*finest[k]) - V(RADIUS, 0, 0)).Length)
    pins = [(3, top, target, 1), (3, side, V(*finest[side]) + V(4, 1, -2), 2)]
    varsurf.set_pins(subd, pins)
    varsurf.set_normals(subd, [(3, side, V(1, 0, 0.3), 2)])
    doc.recompute()
    forward = [V(*p) for p in subd.Proxy.outcome.points]
    varsurf.set_pins(subd, pins[::-1])
    doc.recompute()
    assert subd.isValid(), subd.getStatusString()
    assert max((a - V(*b)).Length for a, b in zip(forward, subd.Proxy.outcome.points)) < 1e-9


@pytest.mark.parametrize("scale", [0.05, 500.0])
def test_a_pinned_scene_scales(doc, scale):
    """The same pinned cage at 1 mm and at 10 m (a box of 20 mm scaled by 0.05 and by 500, the pin
    with it) gives the same surface scaled; a target sphere scaled with it is captured with the
    scaled fit (the 1 mm sphere once hung OCC's mesher: targets are tessellated at one size; the
    box's face centres, inside the sphere on its axes, have several nearest facets: ties are
    broken by index, not by rounding)."""
    subd, _, top, target = pin_scene(doc, 1, captured=False)
    reference = [V(*p) for p in subd.Proxy.outcome.points]
    other = FreeCAD.newDocument("Scaled")
    try:
        box = other.addObject("Part::Box", "Cage")
        box.Length = box.Width = box.Height = 20.0 * scale
        box.Placement.Base = V(-10, -10, -10) * scale
        sphere = other.addObject("Part::Sphere", "Target")
        sphere.Radius = RADIUS * scale
        other.recompute()
        scaled = varsurf.make_subd_surface(box, levels=3, pins=[(3, top, target * scale, 1)])
        captured = varsurf.make_subd_surface(box, levels=3, target=sphere, name="Captured")
        other.recompute()
        assert scaled.isValid(), scaled.getStatusString()
        worst = max((a * scale - V(*b)).Length for a, b in zip(reference, scaled.Proxy.outcome.points))
        assert worst < 1e-9 * 20.0 * scale, worst
        assert captured.isValid(), captured.getStatusString()
        reference = varsurf.make_subd_surface(doc.getObject("Cage"), levels=3, target=doc.getObject("Target"),
                                              name="Reference")
        doc.recompute()
        ratio = captured.FitMax / scale / reference.FitMax
        assert abs(ratio - 1.0) < 1e-9, ratio
        assert max((V(*a) * scale - V(*b)).Length for a, b in zip(reference.Proxy.outcome.points,
                                                                  captured.Proxy.outcome.points)) < 1e-9 * 20 * scale
    finally:
        FreeCAD.closeDocument(other.Name)
