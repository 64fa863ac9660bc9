# SPDX-License-Identifier: LGPL-2.1-or-later
"""Every constraint kind: made through the API, recomputed, saved and reopened with the same
result; and each kind's bad inputs reported on the object in error, never a crash."""

import math

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.solve import constraints
from scenes import add_shape, add_vertex, poles_of, railed_sheet

V = FreeCAD.Vector
NAN = float("nan")


def _scene(doc):
    """Targets for every kind, placed around the railed sheet (x = 100 u, y = 80 v, z = 0)."""
    return dict(
        pin=add_vertex(doc, "Pin", (60.0, 50.0, 12.0)),
        roof=add_shape(doc, "Roof", Part.makePlane(60, 50, V(30, 15, 9))),
        wire=add_shape(doc, "Wire", Part.LineSegment(V(50, 40, 6), V(80, 40, 6)).toShape()),
        seam=add_shape(doc, "Seam", Part.LineSegment(V(60, 25, 0), V(60, 55, 0)).toShape()),
        second=add_shape(doc, "Second", Part.LineSegment(V(80, 20, 5), V(80, 60, 5)).toShape()),
        flat=add_shape(doc, "Flat", Part.makePlane(30, 40, V(60, 20, 0))),
        lifted=add_shape(doc, "Lifted", Part.LineSegment(V(70, 20, 4), V(70, 60, 4)).toShape()),
        triangle=add_shape(doc, "Triangle", Part.makePolygon([V(45, 10, 0), V(95, 10, 0), V(70, 45, 0),
                                                              V(45, 10, 0)])),
    )


#: kind -> make_constraint arguments of a valid constraint (callables take the scene).
VALID = {
    "Point": lambda o: dict(location=(o["pin"], "Vertex1")),
    "TangentU": lambda o: dict(uv=(0.65, 0.55), vector=(100.0, 0.0, 30.0)),
    "TangentV": lambda o: dict(uv=(0.65, 0.55), vector=(0.0, 80.0, -20.0)),
    "Normal": lambda o: dict(uv=(0.65, 0.55), vector=(0.3, -0.2, 1.0)),
    "PointInPlane": lambda o: dict(uv=(0.65, 0.55), vector=(0.2, 0.1, 1.0), origin=(0, 0, 7)),
    "PointOnLine": lambda o: dict(uv=(0.65, 0.55), vector=(0, 0.3, 1), origin=(70, 40, 0)),
    "Curvature": lambda o: dict(uv=(0.65, 0.55), vector=(0, 0, 1), curvature=(0.004, -0.002)),
    "PointAttractor": lambda o: dict(origin=(60, 40, 10), region=(0.5, 0.7, 0.4, 0.6)),
    "PlaneAttractor": lambda o: dict(origin=(60, 40, 10), vector=(0, 0, 1), region=(0.5, 0.7, 0.4, 0.6)),
    "LineAttractor": lambda o: dict(origin=(60, 40, 10), vector=(1, 0, 0), region=(0.5, 0.7, 0.4, 0.6)),
    "Director": lambda o: dict(vector=(0, 0.2, 1), region=(0.35, 0.65, 0.35, 0.65)),
    "Repeller": lambda o: dict(origin=(60, 40, 3), region=(0.45, 0.75, 0.35, 0.65), weight=1e-3),
    "FrozenRegion": lambda o: dict(region_loop=(o["triangle"], [])),
    "SurfaceAttractor": lambda o: dict(reference=(o["roof"], "Face1"), region=(0.55, 0.75, 0.4, 0.6)),
    "CurveAttractor": lambda o: dict(curve=(o["wire"], "Edge1"), region=(0.55, 0.75, 0.45, 0.55), weight=10.0),
    "Ribbon": lambda o: dict(curve=(o["seam"], "Edge1"), reference=(o["second"], "Edge1"), angle=5.0),
    "G1": lambda o: dict(curve=(o["seam"], "Edge1"), reference=(o["flat"], "Face1")),
    "G0": lambda o: dict(curve=(o["lifted"], "Edge1")),
    "G2": lambda o: dict(curve=(o["seam"], "Edge1"), reference=(o["flat"], "Face1")),
    "CurveMap": lambda o: dict(curve=(o["seam"], "Edge1"), reference=(o["second"], "Edge1")),
    "RegionMap": lambda o: dict(reference=(o["roof"], "Face1"), region=(0.55, 0.8, 0.4, 0.7)),
}


def test_the_table_covers_every_kind():
    assert set(VALID) == set(constraints.KINDS)


def test_every_kind_survives_save_and_reopen(doc, native, tmp_path):
    scene = _scene(doc)
    sheets = {}
    for kind in constraints.KINDS:
        sheet = railed_sheet(doc)
        c = varsurf.make_constraint(sheet, kind, name=kind, **VALID[kind](scene))
        doc.recompute()
        assert sheet.isValid() and c.isValid(), (kind, sheet.getStatusString())
        assert list(sheet.ConstraintNames) == [c.Label]
        sheets[sheet.Name] = (kind, poles_of(sheet), list(sheet.ConstraintResiduals))
    path = str(tmp_path / "every_kind.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    again = FreeCAD.openDocument(path)
    try:
        for name, (kind, poles, residuals) in sheets.items():
            sheet = again.getObject(name)
            assert [str(c.Kind) for c in sheet.Constraints] == [kind]
            assert max(math.dist(p, q) for p, q in zip(poles, poles_of(sheet))) < 1e-12  # as saved
            sheet.touch()
        again.recompute()
        for name, (kind, poles, residuals) in sheets.items():
            sheet = again.getObject(name)
            assert sheet.isValid(), (kind, sheet.getStatusString())
            assert max(math.dist(p, q) for p, q in zip(poles, poles_of(sheet))) < 1e-9, kind
            assert list(sheet.ConstraintResiduals) == pytest.approx(residuals, rel=1e-6, abs=1e-9), kind
    finally:
        FreeCAD.closeDocument(again.Name)


# kind, edits applied after a valid make (or None: made without its links), expected text
BAD = [
    ("Point", dict(Location=None), "needs a Location vertex"),
    ("Point", dict(Weight=NAN), "weight"),
    ("TangentU", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("TangentV", dict(U=1.5), "[0, 1]"),
    ("Normal", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("Normal", dict(Weight=NAN), "weight"),
    ("PointInPlane", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("PointOnLine", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("Curvature", dict(CurvatureU=NAN), "must be finite"),
    ("Curvature", dict(Vector=V(1, 0, 0)), "names no side"),
    ("Curvature", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("PointAttractor", dict(RegionU1=1.5), "region"),
    ("PointAttractor", dict(Weight=NAN), "weight"),
    ("PlaneAttractor", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("LineAttractor", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("Director", dict(Vector=V(0, 0, 0)), "non-zero direction"),
    ("Director", dict(Weight=-1.0), "weight"),
    ("Repeller", dict(Weight=float("inf")), "weight"),
    ("FrozenRegion", dict(RegionLoop=None, RegionV0=0.9, RegionV1=0.1), "region"),
    ("FrozenRegion", dict(RegionLoop="open"), "one closed chain"),
    ("SurfaceAttractor", dict(Reference=None), "needs a Reference face"),
    ("SurfaceAttractor", dict(Reference="edge"), "needs a Reference face"),
    ("SurfaceAttractor", dict(RegionU0=-0.5), "region"),
    ("CurveAttractor", dict(Curve=None), "needs a Curve"),
    ("CurveAttractor", dict(Weight=NAN), "weight"),
    ("Ribbon", dict(Curve=None), "needs a Curve"),
    ("Ribbon", dict(Angle=NAN), "Angle must be finite"),
    ("G1", dict(Reference=None), "needs a Curve (an edge) and a Reference"),
    ("G1", dict(Reference="roof"), "from its reference face"),
    ("G2", dict(Reference=None), "needs a Curve (an edge) and a Reference"),
    ("G2", dict(Reference="roof"), "from its reference face"),
    ("G0", dict(Curve=None), "needs a Curve"),
    ("CurveMap", dict(Reference=None), "needs a Curve (the source"),
    ("CurveMap", dict(Reference="roof"), "must be an edge"),
    ("CurveMap", dict(Curve="beyond"), "beyond"),
    ("RegionMap", dict(Reference=None), "needs a Reference face"),
    ("RegionMap", dict(Reference="edge"), "needs a Reference face"),
    ("RegionMap", dict(RegionV0=0.9, RegionV1=0.1), "region"),
    ("G0", dict(Curve="beyond"), "beyond"),
]


@pytest.mark.parametrize("kind, edits, text", BAD, ids=[f"{k}-{'-'.join(e)}" for k, e, _t in BAD])
def test_bad_input_of_every_kind_is_reported_not_crashed(doc, native, tmp_path, kind, edits, text,
                                                         console_errors):
    scene = _scene(doc)
    sheet = railed_sheet(doc)
    c = varsurf.make_constraint(sheet, kind, **VALID[kind](scene))
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()
    good = poles_of(sheet)
    beyond = add_shape(doc, "Beyond", Part.LineSegment(V(70, 20, 4), V(170, 60, 4)).toShape())
    links = {"edge": (scene["wire"], "Edge1"), "roof": (scene["roof"], "Face1"), "beyond": (beyond, "Edge1"),
             "open": (add_shape(doc, "Open", Part.makePolygon([V(45, 10, 0), V(95, 10, 0), V(70, 45, 0)])), [])}
    for prop, value in edits.items():
        setattr(c, prop, links.get(value, value) if isinstance(value, str) else value)
    doc.recompute()
    # Either the constraint itself (its own data is wrong) or the Sheet (it cannot be placed on
    # the base) is in error, with a message that says what is wrong.
    where = c if not c.isValid() else sheet
    assert not where.isValid(), (c.getStatusString(), sheet.getStatusString())
    assert text in where.getStatusString() and c.Label in where.getStatusString(), where.getStatusString()
    assert text in console_errors()
    # The last good sheet is kept and the document still saves and reopens.
    assert max(math.dist(p, q) for p, q in zip(good, poles_of(sheet))) < 1e-12
    path = str(tmp_path / "bad.FCStd")
    doc.saveAs(path)
    names = (c.Name, sheet.Name)
    FreeCAD.closeDocument(doc.Name)
    again = FreeCAD.openDocument(path)
    try:
        assert again.getObject(names[0]) is not None
        assert max(math.dist(p, q) for p, q in zip(good, poles_of(again.getObject(names[1])))) < 1e-12
    finally:
        FreeCAD.closeDocument(again.Name)
