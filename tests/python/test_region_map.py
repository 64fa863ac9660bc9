# SPDX-License-Identifier: LGPL-2.1-or-later
"""The RegionMap constraint (Du & Qin 4.7.5): a rectangle of the sheet's normalized (u, v) is
mapped onto a destination face, point for point onto the face's parameter rectangle. Measured on
the result face against the destination at the mapped parameters: the region is fitted like a
curve, its RMS within Tolerance (the discrepancy principle), so its largest distance, at the
corners, may pass Tolerance a little (measured: 1.0 and 1.5 x); the residual the Sheet reports is
that largest distance. Bad links and regions."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from scenes import add_face, flat_face, poles_of
from step_check import assert_reads_back

V = FreeCAD.Vector
REGION = (0.3, 0.7, 0.25, 0.75)


def bump(x0, y0, width, depth, height, z=0.0):
    """A bicubic patch over [x0, x0 + width] x [y0, y0 + depth] rising `height` in its middle."""
    knots, mults = [0.0, 1.0], [4, 4]
    poles = [[V(x0 + width * i / 3, y0 + depth * j / 3, z + (height if 0 < i < 3 and 0 < j < 3 else 0.0))
              for j in range(4)] for i in range(4)]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
    return surface.toShape()


def scene(doc, destination, region=REGION):
    base = add_face(doc, flat_face(100.0, 80.0))
    patch = add_face(doc, destination, "Destination")
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [])
    c = varsurf.make_constraint(sheet, "RegionMap", reference=(patch, "Face1"), region=region)
    doc.recompute()
    return sheet, c, patch


def mapped_error(sheet, patch, region=REGION):
    """Largest distance between the sheet over the region and the destination at the mapped
    parameters, on a 21 x 21 grid."""
    surface = sheet.Shape.Faces[0].Surface
    u0, u1, v0, v1 = surface.bounds()
    face = patch.Shape.Faces[0]
    a0, a1, b0, b1 = face.ParameterRange
    worst = 0.0
    for i in range(21):
        for j in range(21):
            x, y = i / 20, j / 20
            u = u0 + (region[0] + x * (region[1] - region[0])) * (u1 - u0)
            v = v0 + (region[2] + y * (region[3] - region[2])) * (v1 - v0)
            worst = max(worst, (surface.value(u, v) - face.valueAt(a0 + x * (a1 - a0), b0 + y * (b1 - b0))).Length)
    return worst


@pytest.mark.parametrize("tolerance", [1e-2, 1e-3, 1e-4])
def test_the_region_takes_the_destinations_shape(doc, native, tolerance):
    base = add_face(doc, flat_face(100.0, 80.0))
    patch = add_face(doc, bump(30.0, 20.0, 40.0, 40.0, 12.0), "Destination")
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [], tolerance=tolerance)
    c = varsurf.make_constraint(sheet, "RegionMap", reference=(patch, "Face1"), region=REGION)
    doc.recompute()
    assert sheet.isValid() and c.isValid(), sheet.getStatusString()
    error = mapped_error(sheet, patch)
    assert error < 2.0 * tolerance
    reported = sheet.ConstraintResiduals[list(sheet.ConstraintNames).index(c.Label)]
    assert reported == pytest.approx(error, rel=0.05)
    assert sheet.Shape.BoundBox.ZMax > 6.0  # the bump is there (its top is 2/3 of its poles')


def test_a_destination_elsewhere_is_mapped_onto_the_region(doc, native):
    """The destination floats 30 mm above and to the side: the region goes to it, point for point."""
    sheet, c, patch = scene(doc, bump(120.0, 10.0, 50.0, 30.0, 8.0, z=30.0))
    assert sheet.isValid(), sheet.getStatusString()
    assert mapped_error(sheet, patch) < 2.0 * float(sheet.Tolerance)


def test_the_sheets_own_patch_leaves_the_sheet_alone(doc, native):
    """The destination is the base under the region (a plane over the same rectangle): nothing moves."""
    sheet, c, patch = scene(doc, Part.makePlane(40.0, 40.0, V(30.0, 20.0, 0.0)))
    assert max(abs(p[2]) for p in poles_of(sheet)) < 1e-9
    assert mapped_error(sheet, patch) < 1e-9


def test_bad_links_and_regions_are_reported_on_the_constraint(doc, native, console_errors):
    sheet, c, patch = scene(doc, bump(30.0, 20.0, 40.0, 40.0, 12.0))
    good = poles_of(sheet)
    c.Reference = None
    doc.recompute()
    assert not c.isValid() and "needs a Reference face" in c.getStatusString(), c.getStatusString()
    assert "needs a Reference face" in console_errors()
    c.Reference = (patch, "Face1")
    c.RegionU0, c.RegionU1 = 0.8, 0.2
    doc.recompute()
    assert not c.isValid() and "the region must satisfy" in c.getStatusString(), c.getStatusString()
    assert max(math.dist(p, q) for p, q in zip(good, poles_of(sheet))) < 1e-12
    c.RegionU0, c.RegionU1 = 0.3, 0.7
    doc.recompute()
    assert c.isValid() and sheet.isValid()


def test_a_fillet_face_as_destination_survives_step(doc, native, tmp_path):
    """The destination one of the fillets of a Part box's four top edges (a cylindrical face OCCT
    made, converted to a B-spline for the map): the one whose parameters run along the sheet's
    (u along +x, v along +y), so the map asks for no twist. The region dips onto it, and the sheet
    written to STEP reads back sound."""
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 40.0, 40.0, 20.0
    box.Placement.Base = V(20.0, 20.0, -25.0)
    doc.recompute()
    fillet = doc.addObject("Part::Fillet", "Fillet")
    fillet.Base = box
    fillet.Edges = [(k, 8.0, 8.0) for k, e in enumerate(box.Shape.Edges, 1)
                    if all(abs(v.Point.z + 5.0) < 1e-9 for v in e.Vertexes)]
    box.Visibility = False
    doc.recompute()

    def aligned(f):
        a0, a1, b0, b1 = f.ParameterRange
        start = f.valueAt(a0, b0)
        return (f.Surface.TypeId == "Part::GeomCylinder" and f.valueAt(a1, b0).x - start.x > 5.0
                and f.valueAt(a0, b1).y - start.y > 30.0)

    face = next(k for k, f in enumerate(fillet.Shape.Faces, 1) if aligned(f))
    base = add_face(doc, flat_face(100.0, 80.0))
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [], tolerance=0.01)
    c = varsurf.make_constraint(sheet, "RegionMap", reference=(fillet, f"Face{face}"), region=REGION)
    doc.recompute()
    assert sheet.isValid() and c.isValid(), sheet.getStatusString()

    class Patch:  # mapped_error reads the destination's face from .Shape
        Shape = fillet.Shape.Faces[face - 1].toNurbs()

    assert mapped_error(sheet, Patch) < 2.0 * 0.01
    assert sheet.Shape.BoundBox.ZMin < -12.0  # it reached down to the fillet
    path = tmp_path / "region_map.step"
    varsurf.export_step(sheet, str(path))
    assert_reads_back(sheet.Shape, path, native)


def test_a_base_of_few_spans_is_mapped_on_the_spans_solved(doc, native):
    """A base face of 3 spans a side, which the sheet refines to 16: the map's lines follow the
    spans solved, not the base's (lines at the base's Gauss points alone left the surface 0.25 mm
    from its destination between them while the reported residual said 4e-13)."""
    poles = [[V(20 * i, 20 * j, 6 * math.sin(math.pi * i / 5) * math.sin(math.pi * j / 5)) for j in range(6)]
             for i in range(6)]
    surface = Part.BSplineSurface()
    knots, mults = [0.0, 1 / 3, 2 / 3, 1.0], [4, 1, 1, 4]
    surface.buildFromPolesMultsKnots(poles, mults, mults, knots, knots, False, False, 3, 3)
    base = add_face(doc, surface.toShape())
    region = (0.35, 0.65, 0.35, 0.65)
    patch = add_face(doc, bump(35.0, 35.0, 30.0, 30.0, 5.0, z=14.0), "Destination")
    doc.recompute()
    sheet = varsurf.make_sheet((base, "Face1"), [])
    c = varsurf.make_constraint(sheet, "RegionMap", reference=(patch, "Face1"), region=region)
    doc.recompute()
    assert sheet.isValid() and c.isValid(), sheet.getStatusString()
    assert len(sheet.Shape.Faces[0].Surface.getUKnots()) > 4  # refined beyond the base's spans
    error = mapped_error(sheet, patch, region)
    assert error < 2.0 * float(sheet.Tolerance)
    reported = sheet.ConstraintResiduals[list(sheet.ConstraintNames).index(c.Label)]
    assert reported == pytest.approx(error, rel=0.05, abs=1e-9)
