# SPDX-License-Identifier: LGPL-2.1-or-later
"""G2 joins: the sheet continues a neighbouring face's curvature across an edge (not linear: the
solver iterates, and says so). Checked on FreeCAD parts against analytic curvatures and against
the same scene joined G1 (which must fail the same check), measured by OCCT on the result."""

import math

import FreeCAD
import pytest

import varsurf
from step_check import assert_reads_back
from varsurf.solve import continuity

V = FreeCAD.Vector
R = 20.0  # the sphere's radius
CUT = 12.0  # the height of the plane that cuts its cap off


def _capless_sphere(doc):
    sphere = doc.addObject("Part::Sphere", "Ball")
    sphere.Radius = R
    box = doc.addObject("Part::Box", "Knife")
    box.Length = box.Width = box.Height = 100
    box.Placement.Base = V(-50, -50, CUT)
    cut = doc.addObject("Part::Cut", "Capless")
    cut.Base, cut.Tool = sphere, box
    doc.recompute()
    disc = next(i for i, f in enumerate(cut.Shape.Faces) if f.Surface.TypeId == "Part::GeomPlane")
    return sphere, cut, disc


def _meridian_curvatures(face, rim, samples=60):
    """The face's normal curvature across the rim circle (along the meridian) at points of it,
    signed outward: the sphere's is 1/R everywhere."""
    out = []
    for k in range(samples):
        p = rim.valueAt(rim.FirstParameter + (rim.LastParameter - rim.FirstParameter) * k / samples)
        u, v = face.Surface.parameter(p)
        normal = face.Surface.normal(u, v)
        meridian = normal.cross(rim.tangentAt(rim.Curve.parameter(p)))
        curvature = continuity.normal_curvature(face.Surface, u, v, meridian)
        out.append(curvature if normal.dot(p) < 0 else -curvature)  # positive: bent like the ball
    return out


def test_a_sphere_cap_filled_g2_takes_the_spheres_curvature_across_its_rim(doc, native, tmp_path):
    """The flat cap of a cut sphere replaced by a sheet: G1 leaves the sheet flatter than the ball
    at the rim (a curvature jump); G2 bends it by 1/R across the rim, as the sphere does."""
    _sphere, cut, disc = _capless_sphere(doc)
    g1 = varsurf.make_fill_hole(cut, f"Face{disc + 1}", continuity="G1", name="CapG1")
    g2 = varsurf.make_fill_hole(cut, f"Face{disc + 1}", continuity="G2", name="CapG2")
    doc.recompute()
    for filled in (g1, g2):
        assert filled.isValid(), filled.getStatusString()
        assert filled.Closed and filled.Shape.isValid() and filled.Shape.check(True) is None
        assert max(filled.JoinGaps) <= filled.Tolerance.Value and max(filled.JoinAngles) <= 0.01
    assert max(g2.JoinCurvatureJumps) <= 1.0, g2.JoinCurvatureJumps  # the G2 target, in %
    assert max(g1.JoinCurvatureJumps) >= 10.0, g1.JoinCurvatureJumps  # the check can fail
    assert "G2 in" in g2.Status and "Newton steps" in g2.Status, g2.Status
    rim = next(e for e in cut.Shape.Edges if e.Curve.TypeId == "Part::GeomCircle" and abs(e.BoundBox.ZMin - CUT) < 1e-9)
    sheet = next(f for f in g2.Shape.Faces if f.Surface.TypeId == "Part::GeomBSplineSurface")
    for curvature in _meridian_curvatures(sheet, rim):
        assert curvature == pytest.approx(1.0 / R, rel=0.01)
    flat = next(f for f in g1.Shape.Faces if f.Surface.TypeId == "Part::GeomBSplineSurface")
    assert max(abs(c * R - 1.0) for c in _meridian_curvatures(flat, rim)) > 0.1
    # Bent like the ball at its rim, the G2 cap is nearer the ball's own volume than the G1 cap.
    ball = 4.0 / 3.0 * math.pi * R ** 3
    assert abs(g2.Shape.Volume - ball) < abs(g1.Shape.Volume - ball)
    for filled in (g1, g2):
        path = tmp_path / f"{filled.Name}.step"
        varsurf.export_step([filled], str(path))
        assert_reads_back(filled.Shape, path, native)


def test_a_g2_constraint_on_a_sheet_from_curves(doc, native):
    """The same rim as a Sheet's curve with a G2 Constraint to the ball: the Sheet reports the
    iteration, the Constraint its residual in %, and the join is measured like a G1's."""
    _sphere, cut, _disc = _capless_sphere(doc)
    rim = next(i for i, e in enumerate(cut.Shape.Edges)
               if e.Curve.TypeId == "Part::GeomCircle" and abs(e.BoundBox.ZMin - CUT) < 1e-9)
    ball = next(i for i, f in enumerate(cut.Shape.Faces) if f.Surface.TypeId == "Part::GeomSphere")
    sheet = varsurf.make_sheet(None, [(cut, f"Edge{rim + 1}")], name="Lid")
    join = varsurf.make_constraint(sheet, "G2", curve=(cut, f"Edge{rim + 1}"), reference=(cut, f"Face{ball + 1}"))
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    assert "G2 in" in sheet.Status, sheet.Status
    assert list(sheet.ConstraintUnits) == ["%"] and sheet.ConstraintResiduals[0] <= 1.0
    assert max(sheet.JoinCurvatureJumps) <= 1.0 and max(sheet.JoinAngles) <= 0.01, sheet.JoinCurvatureJumps
    for curvature in _meridian_curvatures(sheet.Shape.Faces[0], cut.Shape.Edges[rim]):
        assert curvature == pytest.approx(1.0 / R, rel=0.01)
    # The same sheet G1 only: the curvature across the rim is the fair sheet's, not the ball's.
    join.Kind = "G1"
    doc.recompute()
    assert sheet.isValid() and "G2 in" not in sheet.Status
    assert max(sheet.JoinCurvatureJumps) >= 10.0
