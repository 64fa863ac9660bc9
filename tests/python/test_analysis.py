# SPDX-License-Identifier: LGPL-2.1-or-later
"""Analysis fields on a sheet's face: deviation from the base, curvature, zebra; checked against
analytic values."""

import math

import Part
import pytest

from varsurf.app import analysis as sheet_analysis
from varsurf.solve import analysis
from scenes import railed_sheet


def test_curvature_of_a_sphere():
    face = Part.makeSphere(10.0).Faces[0]
    for mode, expected in (("MeanCurvature", 0.1), ("GaussianCurvature", 0.01)):
        grid = analysis.analyse(face, mode, n=12)
        inner = [abs(v) for v, p in zip(grid.values, grid.points) if abs(p[2]) < 9.0 and math.isfinite(v)]
        assert len(inner) > 50
        assert max(abs(v - expected) for v in inner) < 1e-9 * (1 + expected), mode
    assert len(grid.triangles) == 2 * 12 * 12 and len(grid.points) == 13 * 13


def test_deviation_from_the_base_is_the_height(doc, native):
    sheet = railed_sheet(doc)  # flat base at z = 0, a rail 5 mm up
    base = sheet_analysis.reference_of(sheet)
    grid = analysis.analyse(sheet.Shape, "Deviation", reference=base, n=20)
    assert max(abs(v - p[2]) for v, p in zip(grid.values, grid.points)) < 1e-7
    assert grid.range[1] > 4.9  # the sheet reaches the rail
    lo, hi = analysis.color_range("Deviation", grid)
    assert lo == -hi and analysis.ramp(0.0, lo, hi) == (0.0, 1.0, 0.0)
    assert analysis.ramp(hi, lo, hi) == (1.0, 0.0, 0.0) and analysis.ramp(lo, lo, hi) == (0.0, 0.0, 1.0)


def test_zebra_stripes_and_bad_requests(doc, native):
    sheet = railed_sheet(doc)
    zebra = analysis.analyse(sheet.Shape, "Zebra", n=30)
    assert all(0.0 <= v <= 1.0 for v in zebra.values)
    flat = analysis.analyse(Part.makePlane(10, 10), "Zebra", n=4)
    assert all(abs(v - 1.0) < 1e-12 for v in flat.values)  # a plane facing the direction: one stripe
    sphere = analysis.analyse(Part.makeSphere(10.0).Faces[0], "Zebra", n=24)
    finite = [v for v in sphere.values if math.isfinite(v)]
    assert min(finite) < 0.05 and max(finite) > 0.95  # a sphere's normals sweep every stripe
    assert analysis.colors("Zebra", flat)[0] == (1.0, 1.0, 1.0)
    with pytest.raises(ValueError, match="reference"):
        analysis.analyse(sheet.Shape, "Deviation")
    with pytest.raises(ValueError, match="one of"):
        analysis.analyse(sheet.Shape, "Magic")
    with pytest.raises(ValueError, match="zero"):
        analysis.analyse(sheet.Shape, "Zebra", direction=(0, 0, 0))


def test_l_curve_plot_marks_the_corner(doc, native, tmp_path):
    sheet = railed_sheet(doc)
    with pytest.raises(ValueError, match="no L-curve"):
        sheet_analysis.plot_lcurve(sheet, str(tmp_path / "none.png"))
    sheet.SolveMode = "TSVD"
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    path = sheet_analysis.plot_lcurve(sheet, str(tmp_path / "lcurve.png"))
    from PySide2 import QtGui  # noqa: F401  (Qt reads the PNG back: a real picture)

    image = QtGui.QImage(path)
    assert (image.width(), image.height()) == (600, 450)
    # the corner's red ring is drawn
    reds = sum(1 for y in range(0, 450, 2) for x in range(0, 600, 2)
               if (lambda c: c.red() > 180 and c.green() < 80 and c.blue() < 80)(QtGui.QColor(image.pixel(x, y))))
    assert reds > 5


def test_curve_deviation_is_the_distance_to_the_sheet(doc, native):
    sheet = railed_sheet(doc)  # boundary kept at z = 0, so far from the rail the sheet is low
    rail = sheet.Curves[0][0].Shape.Edges[0]
    above = Part.makeLine((10.0, 70.0, 1.0), (90.0, 70.0, 1.0))  # 1 mm above the flat base
    flat = Part.makePlane(100.0, 80.0)
    met, lifted = analysis.curve_deviations(sheet.Shape, [rail]), analysis.curve_deviations(flat, [above], 9)
    assert max(met[0].distances) < float(sheet.Tolerance)  # the sheet passes through its rail
    assert len(lifted[0].points) == 9 and all(abs(d - 1.0) < 1e-9 for d in lifted[0].distances)
    with pytest.raises(ValueError, match="grid analysis"):
        analysis.analyse(sheet.Shape, "CurveDeviation")
