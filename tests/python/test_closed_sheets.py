# SPDX-License-Identifier: LGPL-2.1-or-later
"""Sheets on closed base faces (a cylinder, a 360° revolve, a sphere): the base's seam is not a
boundary. The sheet's two ends are one seam, free to move and tied smooth, so a curve anywhere
on the face shapes the sheet the same whichever side of the seam it is on; the seam neither
creases nor opens. Measured on the result's own B-spline (OCCT's evaluation, not the solver's),
on FreeCAD parts: the issue's scenes creased by 7.0°, 8.1° and 1.8° and opened by 6.4 mm."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from step_check import assert_reads_back
from varsurf.solve import continuity

V = FreeCAD.Vector
R = 10.0  # the cylinder's radius
H = 30.0  # its height


def _lateral(shape, type_id):
    return next(f for f in shape.Faces if f.Surface.TypeId == type_id)


def _bump(radius, height, start, sweep, lift, rise=0.0, points=9):
    """An open B-spline over the side of a cylinder about z: at `radius` (the face's own radius
    puts it on the face) from angle `start` over `sweep`, at `height` plus `rise` * sin."""
    pts = [V(radius * math.cos(a), radius * math.sin(a), height + rise * math.sin(math.pi * k / (points - 1)))
           for k, a in enumerate(start + sweep * k / (points - 1) for k in range(points))]
    pts = [p + V(p.x, p.y, 0).normalize() * lift * math.sin(math.pi * k / (points - 1)) for k, p in enumerate(pts)]
    curve = Part.BSplineCurve()
    curve.interpolate(pts)
    return curve.toShape()


def _ring(radius, height, start, wobble=0.0, points=24):
    """A closed periodic B-spline around the z axis starting at angle `start`."""
    curve = Part.BSplineCurve()
    curve.interpolate([V(radius * math.cos(a), radius * math.sin(a), height + wobble * math.sin(3 * a))
                       for a in (start + 2 * math.pi * k / points for k in range(points))], PeriodicFlag=True)
    return curve.toShape()


def _seam(face, samples=40):
    """Along the result's seam: the largest angle between the normals on its two sides (°), the
    largest gap between them (mm) and the largest relative jump of the normal curvature across it
    (|k1 - k2| / max |k|), by OCCT's evaluation of the face's B-spline at both ends of its range."""
    surface = face.Surface
    u0, u1, v0, v1 = surface.bounds()
    closed_u = (surface.value(u0, 0.5 * (v0 + v1)) - surface.value(u1, 0.5 * (v0 + v1))).Length < 1e-3
    angle = gap = jump = 0.0
    for k in range(1, samples):
        t = k / samples
        if closed_u:
            a, b, dirs = (u0, v0 + (v1 - v0) * t), (u1, v0 + (v1 - v0) * t), 0
        else:
            a, b, dirs = (u0 + (u1 - u0) * t, v0), (u0 + (u1 - u0) * t, v1), 1
        gap = max(gap, (surface.value(*a) - surface.value(*b)).Length)
        na, nb = surface.normal(*a), surface.normal(*b)
        angle = max(angle, math.degrees(na.getAngle(nb)))
        across = surface.getDN(a[0], a[1], 1 - dirs, dirs)
        ka = continuity.normal_curvature(surface, a[0], a[1], across)
        kb = continuity.normal_curvature(surface, b[0], b[1], across)
        jump = max(jump, abs(ka - kb) / max(abs(ka), abs(kb), 1e-12))
    return angle, gap, jump


def _grid(face, n=12):
    """Points of a face's surface on an n x n grid of its parameter range."""
    u0, u1, v0, v1 = face.ParameterRange
    return [face.Surface.value(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n)
            for i in range(n + 1) for j in range(n + 1)]


def _far(a, b):
    """The largest distance from grid points of face `a` to face `b`."""
    return max(b.distToShape(Part.Vertex(p))[0] for p in _grid(a))


def _sheet(doc, base, sub, curves, **options):
    sheet = varsurf.make_sheet((base, sub), curves, doc=doc, **options)
    doc.recompute()
    assert sheet.isValid(), sheet.Status
    return sheet


def _cylinder(doc, name="Cyl"):
    cyl = doc.addObject("Part::Cylinder", name)
    cyl.Radius, cyl.Height = R, H
    doc.recompute()
    face = next(i for i, f in enumerate(cyl.Shape.Faces) if f.Surface.TypeId == "Part::GeomCylinder")
    return cyl, f"Face{face + 1}"


def _curve_object(doc, edge, name):
    obj = doc.addObject("Part::Feature", name)
    obj.Shape = edge
    doc.recompute()
    return obj


@pytest.mark.parametrize("fix_boundary", [True, False])
def test_a_bump_on_the_far_side_of_a_cylinder_neither_creases_nor_opens_its_seam(doc, fix_boundary):
    """The issue's scene: a curve pushed out opposite the seam. Kept boundary: the seam used to be
    held and creased (7.0°); free boundary: the seam opened (6.4 mm)."""
    cyl, sub = _cylinder(doc)
    bump = _curve_object(doc, _bump(R, 15.0, 0.55 * math.pi, 0.9 * math.pi, 2.0, rise=3.0), "Bump")
    sheet = _sheet(doc, cyl, sub, [bump], fix_boundary=fix_boundary, tolerance=0.01)
    face = sheet.Shape.Faces[0]
    angle, gap, jump = _seam(face)
    assert angle <= 0.01 and gap <= 1e-7, (angle, gap)
    assert jump <= 0.01, jump  # the cylinder's rational circles keep their curvature across
    assert max(sheet.MaxDeviations) <= sheet.Tolerance.Value
    assert face.isValid() and face.check(True) is None
    # One face closed on itself: its seam is one edge used twice, as on the cylinder.
    assert len(face.Edges) == len(cyl.Shape.getElement(sub).Edges)
    if fix_boundary:  # the top and bottom circles stay where they were
        for z in (0.0, H):
            for a in (0.3, 2.0, 4.5):
                p = V(R * math.cos(a), R * math.sin(a), z)
                assert face.distToShape(Part.Vertex(p))[0] <= 1e-7


@pytest.mark.parametrize("curve", ["bump", "ring"])
def test_the_seam_does_not_matter_a_cylinder_turned_about_its_axis_gives_the_same_sheet(doc, curve):
    """The same curve on a cylinder whose seam is elsewhere (turned 100° about its axis): the
    ring starts on one cylinder's seam (one pre-image) and crosses the other's (cut in two). The
    sheets agree to the discretization's size (the thin plate is measured in each base's own
    parameters, and their rational circles' speeds differ by up to 1.5 %): measured for the bump
    0.097 mm at 16 spans, 0.060 at 32 and 0.023 at 64, for the ring 0.41, 0.075 and 0.023,
    against the 1 to 2 mm the curves move the sheet."""
    a, sub_a = _cylinder(doc, "CylA")
    b, sub_b = _cylinder(doc, "CylB")
    b.Placement.Rotation = FreeCAD.Rotation(V(0, 0, 1), 100)
    doc.recompute()
    edge = _bump(R, 15.0, 1.5, 2.5, 2.0, rise=3.0) if curve == "bump" else _ring(R + 1.0, 12.0, 0.0, wobble=1.5)
    shaping = _curve_object(doc, edge, "Shaping")
    one = _sheet(doc, a, sub_a, [shaping], tolerance=0.01, min_spans=32, max_spans=32)
    two = _sheet(doc, b, sub_b, [shaping], tolerance=0.01, min_spans=32, max_spans=32)
    assert max(list(one.MaxDeviations) + list(two.MaxDeviations)) <= 0.01
    assert _far(two.Shape.Faces[0], one.Shape) <= 0.1
    assert max(_seam(one.Shape.Faces[0])[0], _seam(two.Shape.Faces[0])[0]) <= 0.01


def test_a_ring_around_a_cylinder_across_its_seam_is_met(doc, native, tmp_path):
    """A closed ring 3 mm outside the cylinder, starting off the seam (so it crosses it): the
    issue's scene was refused as contradictory. The sheet (free boundary) passes through it, is
    smooth across its seam, and survives a STEP round trip."""
    cyl, sub = _cylinder(doc)
    ring = _curve_object(doc, _ring(R + 3.0, 15.0, 1.0, wobble=2.0), "Ring")
    sheet = _sheet(doc, cyl, sub, [ring], fix_boundary=False, tolerance=0.01)
    assert max(sheet.MaxDeviations) <= 0.01, sheet.MaxDeviations
    face = sheet.Shape.Faces[0]
    angle, gap, _jump = _seam(face)
    assert angle <= 0.01 and gap <= 1e-7
    # Around the ring the sheet is the ring's distance out: 13 mm from the axis at mid height.
    mid = face.Surface.value(0.5 * sum(face.ParameterRange[:2]), face.Surface.parameter(V(R + 3, 0, 15))[1])
    assert math.hypot(mid.x, mid.y) == pytest.approx(R + 3.0, abs=0.5)
    path = tmp_path / "ring.step"
    varsurf.export_step([sheet], str(path))
    assert_reads_back(sheet.Shape, path, native)


def test_a_revolved_profile_and_a_sphere_keep_their_seams_smooth(doc, native, tmp_path):
    """A vase (a sketch-like B-spline profile revolved 360°) and a sphere, each with a curve that
    pushes the far side out, their boundary kept (the sphere's: its two poles): no crease at the
    seam (the issue: 8.1° and 1.8°)."""
    profile = Part.BSplineCurve()
    profile.interpolate([V(12, 0, 0), V(16, 0, 10), V(10, 0, 22), V(13, 0, 34)])
    vase = doc.addObject("Part::Feature", "Vase")
    vase.Shape = profile.toShape().revolve(V(0, 0, 0), V(0, 0, 1), 360)
    sphere = doc.addObject("Part::Sphere", "Ball")
    sphere.Radius = 15
    doc.recompute()
    cases = [(vase, "Face1", _bump(15.0, 12.0, 0.6 * math.pi, 0.8 * math.pi, 0.0, rise=2.0)),
             (sphere, "Face1", _bump(15.0 * math.cos(0.3), 15.0 * math.sin(0.3), 0.6 * math.pi, 0.8 * math.pi, 1.5))]
    for base, sub, edge in cases:
        # The curve's points onto the face first (it must lie over it), then pushed by `lift`.
        curve = _curve_object(doc, edge, f"{base.Name}Curve")
        sheet = _sheet(doc, base, sub, [curve], tolerance=0.01)
        assert max(sheet.MaxDeviations) <= 0.01, (base.Name, sheet.MaxDeviations)
        face = sheet.Shape.Faces[0]
        angle, gap, _jump = _seam(face)
        assert angle <= 0.01 and gap <= 1e-7, (base.Name, angle, gap)
        assert face.check(True) is None
        path = tmp_path / f"{base.Name}.step"
        varsurf.export_step([sheet], str(path))
        assert_reads_back(sheet.Shape, path, native)


def test_local_refinement_on_a_cylinder_meets_a_bump_with_fewer_poles_and_keeps_the_seam(doc):
    """Local refinement on a rational base (a Part cylinder's face): the layers carry its weight
    function, so the sheet stays a cylinder where nothing pulls it. A bump 2 mm out over 72° at
    1e-4 mm: uniform refinement stops at its 64 spans short of the tolerance (measured 1.9e-4 mm
    with 4 690 poles); local refinement meets it with about a fifth of the unknowns, and its
    seam stays closed and smooth."""
    cyl, sub = _cylinder(doc)
    bump = _curve_object(doc, _bump(R, 15.0, 0.8 * math.pi, 0.4 * math.pi, 2.0), "Bump")
    c = R * math.sqrt(0.5)  # a generator at -45°, away from the bump (144° to 216°)
    line = _curve_object(doc, Part.LineSegment(V(c, -c, 4), V(c, -c, 26)).toShape(), "Generator")
    sheets = {}
    for mode in ("Uniform", "Local"):
        sheets[mode] = varsurf.make_sheet((cyl, sub), [bump, line], doc=doc, tolerance=1e-4, name=mode)
        sheets[mode].Refinement = mode
        sheets[mode].MaxDepth = 5
    doc.recompute()
    uniform, local = sheets["Uniform"], sheets["Local"]
    assert uniform.isValid() and local.isValid(), (uniform.Status, local.Status)
    assert local.Status.startswith("OK"), local.Status
    assert max(local.MaxDeviations) <= 1e-4, local.MaxDeviations  # measured by OCCT on the result
    assert local.RefinementDepth >= 1
    assert 2 * local.DegreesOfFreedom < uniform.DegreesOfFreedom, (local.DegreesOfFreedom, uniform.DegreesOfFreedom)
    face = local.Shape.Faces[0]
    assert face.Surface.isURational() or face.Surface.isVRational()
    assert face.isValid() and face.check(True) is None
    angle, gap, _jump = _seam(face)
    assert angle <= 0.01 and gap <= 1e-7, (angle, gap)
    for z in (0.0, H):  # the kept boundary circles are still the cylinder's
        for a in (0.3, 2.0, 4.5):
            assert face.distToShape(Part.Vertex(V(R * math.cos(a), R * math.sin(a), z)))[0] <= 1e-7


def test_local_refinement_on_a_cylinder_through_its_own_generator_is_the_cylinder(doc):
    """Curves on the face reproduce the face: a generator of the cylinder and a manual refinement
    region (layers that have nothing to do) give back the cylinder itself."""
    cyl, sub = _cylinder(doc)
    line = _curve_object(doc, Part.LineSegment(V(0, R, 3), V(0, R, 27)).toShape(), "Generator")
    sheet = varsurf.make_sheet((cyl, sub), [line], doc=doc, tolerance=1e-4)
    sheet.Refinement = "Local"
    sheet.RefineRegions = [1, 0.0, 0.5, 0.3, 0.7]
    doc.recompute()
    assert sheet.isValid(), sheet.Status
    assert sheet.RefinementDepth == 2
    surface = sheet.Shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    worst = max(abs(math.hypot(p.x, p.y) - R)
                for p in (surface.value(u0 + (u1 - u0) * i / 24, v0 + (v1 - v0) * j / 12)
                          for i in range(25) for j in range(13)))
    assert worst <= 1e-9 * R, worst
