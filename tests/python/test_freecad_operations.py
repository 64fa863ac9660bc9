# SPDX-License-Identifier: LGPL-2.1-or-later
"""The example solids and hole fills survive FreeCAD's own operations: booleans with random
half-spaces and a cylinder drilled through a seam, fillets on the sharp seams, offsets, shelling.
Volumes are checked against the solid's inside measured independently of FreeCAD's booleans and
volume integration (vertical columns through a fine tessellation, brep_measure.Columns)."""

import math
import random

import FreeCAD
import Part
import pytest

import corner_blend
import crowned_lid
import pillow
import rounded_box
import smooth_box
from brep_measure import Columns

V = FreeCAD.Vector

EXAMPLES = {"pillow": pillow.build, "rounded box": rounded_box.build, "crowned lid": crowned_lid.build,
            "corner blend": corner_blend.build, "smooth box": smooth_box.build}
#: Hole fills: their seams are the edges of the sheet sewn into the part, not every edge.
HOLE_FILLS = {"crowned lid", "corner blend"}


def seams(name, shape):
    """The edges where VarSurf's sheets meet each other or the part they were sewn into."""
    if name not in HOLE_FILLS:
        return list(shape.Edges)
    sheet = [f for f in shape.Faces if f.Surface.TypeId == "Part::GeomBSplineSurface"]
    sheet = max(sheet, key=lambda f: f.Area)
    return [e for e in shape.Edges if any(e.isSame(k) for k in sheet.Edges)]


def sharp(shape, edges, degrees=10.0):
    """The edges along which their two faces' normals differ by more than `degrees` at the middle
    (a fillet rounds those; a tangent (G1) seam has nothing to round)."""
    found = []
    for edge in edges:
        faces = [f for f in shape.Faces if any(edge.isSame(k) for k in f.Edges)]
        if len(faces) != 2:
            continue
        p = edge.valueAt(0.5 * (edge.FirstParameter + edge.LastParameter))
        normals = [f.normalAt(*f.Surface.parameter(p)) for f in faces]
        if normals[0].getAngle(normals[1]) > math.radians(degrees):
            found.append(edge)
    return found


@pytest.fixture(params=sorted(EXAMPLES))
def example(request, doc, native):
    solid = EXAMPLES[request.param](doc)
    assert solid.isValid() and solid.Closed, solid.getStatusString()
    shape = solid.Shape
    # The columns mesh a copy: the booleans below must see the shape as built (see the note in
    # Columns: a meshed shape's booleans can differ).
    columns = Columns(shape.copy())
    assert columns.odd == 0
    # The columns' volume agrees with OCCT's (measured: pillow 5.6e-4 apart, the tessellation's
    # chords): the margin below is three times that.
    assert columns.volume() == pytest.approx(shape.Volume, rel=1.5e-3)
    return request.param, shape, columns


def _half_space(origin, normal):
    """A box far larger than the examples with its bottom face on the plane through origin."""
    box = Part.makeBox(2000, 2000, 1000, V(-1000, -1000, 0))
    box.Placement = FreeCAD.Placement(origin, FreeCAD.Rotation(V(0, 0, 1), normal))
    return box


def _valid(shape):
    """Valid, and the BOP check (check(True)) finds nothing."""
    try:
        return shape.isValid() and shape.check(True) is None
    except ValueError:  # the BOP check's faults
        return False


def _valid_but_c0(shape):
    """Valid, and the BOP check finds nothing but C0 geometry: OCCT's own fillet and offset
    surfaces of B-spline faces are approximations that are only C0 at their knots (the sheets
    themselves are C2; the check of the solid before the operation is clean)."""
    if not shape.isValid():
        return False
    try:
        shape.check(True)
    except ValueError as error:
        found = set(line for line in str(error).splitlines()[1:] if line)
        return found <= {"Error in Edge: BOPAlgo GeomAbs_C0", "Error in Face: BOPAlgo GeomAbs_C0"}
    return True


def _pcurve_fault_only(shape):
    """The BOP check finds C0 geometry and curves off their surfaces, nothing else."""
    try:
        shape.check(True)
    except ValueError as error:
        found = set(line for line in str(error).splitlines()[1:] if line)
        return found <= {"Error in Edge: BOPAlgo GeomAbs_C0", "Error in Face: BOPAlgo GeomAbs_C0",
                         "Error in Edge: BOPAlgo_InvalidCurveOnSurface", "Error in Face: BOPAlgo_InvalidCurveOnSurface"}
    return True


def test_twenty_random_half_spaces_cut_the_right_volume(example):
    name, shape, columns = example
    rng = random.Random(20)
    box = shape.BoundBox
    for k in range(20):
        normal = V(rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)).normalize()
        origin = V(rng.uniform(box.XMin, box.XMax), rng.uniform(box.YMin, box.YMax),
                   rng.uniform(box.ZMin, box.ZMax)) * 0.8 + box.Center * 0.2
        half = _half_space(origin, normal)
        common, cut = shape.common(half), shape.cut(half)
        # A plane can miss a rounded solid near its box's corner: that side is then empty (no
        # face to check; FreeCAD's BOP check calls an empty shape a bad type), its volume zero.
        assert all(not r.Faces or _valid(r) for r in (common, cut)), (name, k)
        expected = columns.half_space_volume(origin, normal)
        assert common.Volume == pytest.approx(expected, abs=2e-3 * shape.Volume), (name, k)
        assert cut.Volume == pytest.approx(shape.Volume - expected, abs=2e-3 * shape.Volume), (name, k)


def _seam_points(name, shape, count=3):
    """Points along the solid's seams (edges shared by two faces)."""
    points = []
    for edge in seams(name, shape):
        t0, t1 = edge.FirstParameter, edge.LastParameter
        points += [edge.valueAt(t0 + (t1 - t0) * (k + 0.5) / count) for k in range(count)]
    return points


def test_a_cylinder_drilled_through_a_seam_takes_what_is_inside_it(example):
    name, shape, columns = example
    for p in _seam_points(name, shape)[:4]:
        drill = Part.makeCylinder(5.0, 2000, V(p.x, p.y, -1000), V(0, 0, 1))
        common, cut = shape.common(drill), shape.cut(drill)
        assert _valid(common) and _valid(cut), (name, p)
        expected = columns.cylinder_volume(p, 5.0)
        assert expected > 0.0
        # 78 columns fall in the drill: the midpoint rule's error on the disc's edge is a few %.
        assert common.Volume == pytest.approx(expected, rel=0.06), (name, p)
        assert common.Volume + cut.Volume == pytest.approx(shape.Volume, rel=1e-4), (name, p)


def test_the_seams_take_a_fillet(example):
    name, shape, _columns = example
    radius = 1.0
    edges = sharp(shape, seams(name, shape))
    if not edges:
        pytest.skip(f"every seam of the {name} is tangent (G1): nothing to round")
    filleted = shape.makeFillet(radius, edges)
    # OCCT's fillet along the pillow's closed rim (three edges in a chain) is one B-spline surface
    # that is only C0 where the edges meet.
    if not _valid_but_c0(filleted):
        # On some machines (an Intel Xeon: yes; an AMD EPYC: no, at the same commit) OCCT 7.6's
        # fillet of the smooth box's seams leaves pcurves off their 3D curves
        # (BOPAlgo_InvalidCurveOnSurface), a single seam's too; the fillet is still a valid solid
        # that FreeCAD keeps working on (below). Any other fault, or on another example, fails.
        assert name == "smooth box" and filleted.isValid() and _pcurve_fault_only(filleted), name
    # And it is a solid FreeCAD keeps working on: a half-space through its middle.
    half = _half_space(filleted.BoundBox.Center, V(0.3, 0.2, 0.9).normalize())
    assert filleted.common(half).isValid() and filleted.cut(half).isValid()
    removed = shape.Volume - filleted.Volume
    # A fillet takes material from a convex seam only, at most radius^2 of cross-section where the
    # faces meet at more than 60 degrees (the smallest seam angle of these examples).
    length = sum(e.Length for e in edges)
    assert 0.0 < removed < length * radius ** 2, (name, removed)


@pytest.mark.parametrize("distance", [1.0, -1.0])
def test_offsets_by_a_millimetre(example, distance):
    name, shape, _columns = example
    offset = shape.makeOffsetShape(distance, 1e-3)
    assert offset.ShapeType == "Solid" and _valid(offset), name
    # Steiner: V + d A to first order (measured: pillow within 1.2 %).
    assert abs(offset.Volume) == pytest.approx(shape.Volume + distance * shape.Area, rel=0.03), name


def test_a_shell_by_make_thickness(example):
    """One face removed, the rest made 1 mm thick inwards: about the remaining area times 1 mm
    less than the solid's volume taken away."""
    name, shape, _columns = example
    if name == "pillow":
        # OCCT 7.6 thickens a lens of two spherical caps, but not the same lens converted to
        # B-splines (toNurbs): every thickness fails there as it does on the pillow. While that
        # control fails, the pillow's failure is OCCT's; once it passes, so must the pillow.
        lens = Part.makeSphere(50, V(0, 0, -40)).common(Part.makeSphere(50, V(0, 0, 40))).Solids[0].toNurbs()
        top = max(lens.Faces, key=lambda f: f.CenterOfMass.z)
        try:
            lens.makeThickness([top], -1.0, 1e-3)
        except Part.OCCError:
            pytest.xfail("OCCT's makeThickness fails on a solid of two B-spline faces (the pillow, and a lens of "
                         "two spherical caps converted to B-splines; the analytic lens passes)")
    height = (lambda f: f.Surface.value(*f.Surface.parameter(f.CenterOfMass)).z)
    # A hole fill is opened at the part's bottom: OCCT cannot shell its own filleted box (the corner
    # blend's part before the fill) from the top at -1, -0.5 or +1 mm, and from the bottom it
    # shells that box and the blended one alike (measured 7765.5 and 7765.6 mm^3 at -1 mm).
    opened = (min if name in HOLE_FILLS else max)(shape.Faces, key=height)
    thick = shape.makeThickness([opened], -1.0, 1e-3)
    assert _valid_but_c0(thick), name
    rest = shape.Area - opened.Area
    assert thick.Volume == pytest.approx(rest * 1.0, rel=0.05), name
