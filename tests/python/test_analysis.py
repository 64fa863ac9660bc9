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
    # a scale set by the user replaces the data's range (sheets compared on one scale)
    assert analysis.color_range("Deviation", grid, 2.0) == (-2.0, 2.0)
    assert analysis.colors("Deviation", grid, 1.0)[grid.values.index(max(grid.values))] == (1.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="scale"):
        analysis.color_range("Deviation", grid, -1.0)


def test_zebra_stripes_and_bad_requests(doc, native):
    sheet = railed_sheet(doc)
    zebra = analysis.analyse(sheet.Shape, "Zebra", n=30)
    assert zebra.stripes == analysis.STRIPES and all(0.0 <= v <= analysis.STRIPES for v in zebra.values)
    flat = analysis.analyse(Part.makePlane(10, 10), "Zebra", n=4)
    assert all(abs(v) < 1e-12 for v in flat.values)  # a plane facing the direction: phase 0, white
    assert analysis.colors("Zebra", flat)[0] == (1.0, 1.0, 1.0)
    # On a sphere the phase is stripes * (the normal's angle to the direction) / pi, exactly: the
    # stripes are the sphere's latitude bands, white then black, whatever their count and direction.
    for stripes, direction in ((12, (0, 0, 1)), (5, (1, 0, 0)), (30, (1, 1, 1))):
        sphere = analysis.analyse(Part.makeSphere(10.0).Faces[0], "Zebra", n=24, stripes=stripes,
                                  direction=direction)
        d = [c / math.sqrt(sum(x * x for x in direction)) for c in direction]
        worst = 0.0
        for v, p in zip(sphere.values, sphere.points):
            if math.isfinite(v) and math.hypot(p[0], p[1]) > 1e-6:  # the poles' normals are not defined
                angle = math.acos(max(-1.0, min(1.0, sum(a * b / 10.0 for a, b in zip(p, d)))))
                worst = max(worst, abs(v - stripes * angle / math.pi))
        assert worst < 1e-9, (stripes, worst)
        colors = analysis.colors("Zebra", sphere)
        assert set(colors) <= {(1.0, 1.0, 1.0), (0.0, 0.0, 0.0), (0.6, 0.6, 0.6)}  # crisp: no greys
        assert analysis.color_range("Zebra", sphere) == (0.0, float(stripes))
    assert analysis.zebra_white(0.49) and not analysis.zebra_white(0.51) and analysis.zebra_white(3.2)
    with pytest.raises(ValueError, match="stripes"):
        analysis.analyse(sheet.Shape, "Zebra", stripes=0)
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
