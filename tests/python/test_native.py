# SPDX-License-Identifier: LGPL-2.1-or-later
"""The compiled extension varsurf._native: exceptions for bad input, and shapes crossing to and
from FreeCAD's Part module as BREP strings.

Run with the interpreter FreeCAD uses: /usr/bin/python3 -m pytest tests/python/test_native.py
"""

import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
if str(REPO / "src") not in sys.path:
    sys.path.insert(0, str(REPO / "src"))
FREECAD_LIB = "/usr/lib/freecad-python3/lib"
if FREECAD_LIB not in sys.path:
    sys.path.append(FREECAD_LIB)

from varsurf import _native as nat  # noqa: E402


def plane_sheet(size=10.0, height=0.0, spans=2):
    """Bicubic sheet over [0, 1]^2 whose image is the square [0, size]^2 at z = height.

    Poles of a linear function at the Greville points reproduce it exactly."""
    space = nat.SplineSpace.uniform(3, 3, spans, spans)

    def greville(knots, p):
        return [sum(knots[i + 1 : i + p + 1]) / p for i in range(len(knots) - p - 1)]

    gu, gv = greville(space.knots_u, 3), greville(space.knots_v, 3)
    poles = np.array([[size * u, size * v, height] for u in gu for v in gv])
    return nat.BSplineSurface(space=space, poles=poles)


def line(a, b, t0=0.0, t1=1.0):
    return nat.BSplineCurve(degree=1, knots=[t0, t0, t1, t1], poles=np.array([a, b], dtype=float))


# --------------------------------------------------------------------------------------------
# Exceptions


def test_exception_classes():
    assert issubclass(nat.InvalidInput, ValueError)
    assert issubclass(nat.SolveFailure, RuntimeError)
    assert issubclass(nat.GeometryError, RuntimeError)
    assert not issubclass(nat.GeometryError, nat.SolveFailure)
    for cls in (nat.InvalidInput, nat.SolveFailure, nat.GeometryError):
        assert cls.__module__.startswith("varsurf")
        assert cls.__doc__


def test_nan_pole_raises_invalid_input():
    sheet = plane_sheet()
    poles = sheet.poles.copy()
    poles[4, 2] = math.nan
    sheet.poles = poles
    with pytest.raises(nat.InvalidInput, match="not finite"):
        sheet.evaluate(0.5, 0.5)
    with pytest.raises(nat.InvalidInput, match="not finite"):
        nat.face_brep(sheet)
    with pytest.raises(nat.InvalidInput, match="not finite"):
        nat.project_curve(sheet, line([1, 1, 1], [2, 2, 1]))


def test_nan_parameter_raises_invalid_input():
    with pytest.raises(nat.InvalidInput, match="not finite"):
        plane_sheet().evaluate(math.nan, 0.5)
    with pytest.raises(nat.InvalidInput, match="not finite"):
        line([0, 0, 0], [1, 0, 0]).evaluate(math.inf)


def test_wrong_sizes_raise_invalid_input():
    sheet = plane_sheet()
    sheet.poles = sheet.poles[:-1]
    with pytest.raises(nat.InvalidInput, match="expected 25 poles, got 24"):
        sheet.evaluate(0.5, 0.5)
    with pytest.raises(nat.InvalidInput, match="poles"):
        nat.face_brep(sheet)
    curve = nat.BSplineCurve(degree=3, knots=[0, 0, 0, 0, 1, 1, 1, 1], poles=np.zeros((3, 3)))
    with pytest.raises(nat.InvalidInput, match="too few"):
        curve.evaluate(0.5)
    weighted = line([0, 0, 0], [1, 0, 0])
    weighted.weights = np.array([1.0, 1.0, 1.0])
    with pytest.raises(nat.InvalidInput, match="weight"):
        weighted.evaluate(0.5)
    with pytest.raises(nat.InvalidInput):
        nat.flat_knots([0.0, 1.0], [4])


def test_empty_data_raises_invalid_input():
    empty = nat.BSplineCurve()
    with pytest.raises(nat.InvalidInput):
        empty.evaluate(0.0)
    with pytest.raises(nat.InvalidInput, match="empty"):
        empty.first()
    with pytest.raises(nat.InvalidInput):
        nat.project_curve(plane_sheet(), empty)
    with pytest.raises(nat.InvalidInput):
        nat.max_deviation(plane_sheet(), empty)
    with pytest.raises(nat.InvalidInput):
        nat.face_brep(nat.BSplineSurface())
    with pytest.raises(nat.InvalidInput, match="empty"):
        nat.SplineSpace().domain()
    with pytest.raises(nat.InvalidInput):
        nat.boundary_pole_indices(nat.SplineSpace())
    sheet = plane_sheet()
    with pytest.raises(nat.InvalidInput):
        nat.incidence_error(sheet.space, sheet.poles, nat.CurveConstraint())


def test_pole_array_of_wrong_shape_is_a_type_error():
    sheet = plane_sheet()
    with pytest.raises(TypeError):
        sheet.poles = np.zeros((25, 2))


def test_solver_reports_invalid_problems():
    sheet = plane_sheet()
    problem = nat.SheetProblem(
        space=sheet.space,
        initial_poles=sheet.poles[:-3],
        energy=nat.ThinPlateWeights.isotropic(0.0, 1.0),
    )
    with pytest.raises(nat.InvalidInput, match="initial poles"):
        nat.solve_sheet(problem)
    problem.initial_poles = sheet.poles
    problem.fixed_poles = [1000]
    with pytest.raises(nat.InvalidInput, match="fixed pole"):
        nat.solve_sheet(problem)


def test_numerical_overflow_raises_solve_failure():
    base = plane_sheet(10.0)
    problem = nat.SheetProblem(
        space=base.space,
        initial_poles=base.poles * 1e306,
        energy=nat.ThinPlateWeights.isotropic(0.0, 1.0),
        fixed_poles=nat.boundary_pole_indices(base.space),
    )
    with pytest.raises(nat.SolveFailure, match="non-finite"):
        nat.solve_sheet(problem)


def test_garbage_brep_raises_invalid_input():
    for text in ("", "garbage", "CASCADE Topology V1\nnothing else"):
        with pytest.raises(nat.InvalidInput, match="BREP"):
            nat.surface_from_face_brep(text)
        with pytest.raises(nat.InvalidInput, match="BREP"):
            nat.check_brep(text)
    good = nat.face_brep(plane_sheet())
    with pytest.raises(nat.InvalidInput, match="truncated"):
        nat.surface_from_face_brep(good[: len(good) // 2])
    with pytest.raises(nat.InvalidInput, match="exactly one edge"):
        nat.curve_from_edge_brep(good)


def test_projection_beyond_the_face_raises_invalid_input():
    sheet = plane_sheet(10.0)
    far = line([5.0, 5.0, 50.0], [40.0, 5.0, 50.0])
    with pytest.raises(nat.InvalidInput, match="leaves the face") as info:
        nat.project_curve(sheet, far)
    # Where it leaves (model coordinates) and by how much, in millimetres: the line starts 5 mm
    # inside the 10 mm square, 50 mm above it, and leaves it at x = 10 (its first sample past it).
    text = str(info.value)
    x, y, z = (float(c) for c in re.search(r"leaves the face at \(([^,]+), ([^,]+), ([^)]+)\)", text).groups())
    assert 10.0 < x <= 11.0 and y == pytest.approx(5.0) and z == pytest.approx(50.0), text
    assert "t = " in text and " mm past it there" in text and " mm from the sheet" in text, text


def test_bridge_failures_raise_geometry_error(tmp_path):
    with pytest.raises(nat.GeometryError, match="cannot open"):
        nat.read_step(str(tmp_path / "missing.step"))
    with pytest.raises(nat.GeometryError, match="cannot write"):
        nat.write_step(nat.face_brep(plane_sheet()), str(tmp_path / "no" / "such" / "dir.step"))
    junk = tmp_path / "junk.step"
    junk.write_text("this is not STEP\n")
    with pytest.raises(nat.GeometryError):
        nat.read_step(str(junk))


# --------------------------------------------------------------------------------------------
# API surface


def test_functions_have_docstrings_and_keywords():
    for name in (
        "solve_sheet",
        "boundary_pole_indices",
        "incidence_error",
        "flat_knots",
        "split_knots",
        "surface_from_face_brep",
        "curve_from_edge_brep",
        "project_curve",
        "face_brep",
        "max_deviation",
        "write_step",
        "read_step",
        "check_brep",
    ):
        doc = getattr(nat, name).__doc__
        assert doc and len(doc) > 40, name
    sheet = plane_sheet()
    pre = nat.project_curve(surface=sheet, curve=line([1, 1, 2], [9, 8, 2]), samples=100)
    assert pre.max_distance == pytest.approx(2.0, abs=1e-12)
    assert nat.max_deviation(surface=sheet, curve=line([1, 1, 2], [9, 8, 2]), samples=10) == (
        pytest.approx(2.0, abs=1e-9)
    )
    # Stopped at the first curve beyond 1 mm: the one after it is not measured.
    curves = [line([1, 1, 0.5], [9, 8, 0.5]), line([1, 1, 2], [9, 8, 2]), line([1, 1, 0], [9, 8, 0])]
    assert nat.max_deviations(sheet, curves, 10) == pytest.approx([0.5, 2.0, 0.0], abs=1e-9)
    stopped = nat.max_deviations(surface=sheet, curves=curves, samples=10, accept=0.0, stop_above=1.0)
    assert stopped[0] == pytest.approx(0.5, abs=1e-9) and 1.0 < stopped[1] <= 2.0 + 1e-9
    assert stopped[2] == math.inf


def test_knot_helpers_round_trip():
    flat = nat.flat_knots(knots=[0.0, 0.5, 1.0], mults=[4, 2, 4])
    assert flat == [0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1]
    assert nat.split_knots(flat) == ([0.0, 0.5, 1.0], [4, 2, 4])


def test_value_types():
    space = nat.SplineSpace.uniform(3, 2, 4, 3)
    assert (space.nu(), space.nv(), space.size()) == (7, 5, 35)
    assert space.domain() == (0.0, 1.0, 0.0, 1.0)
    assert len(nat.boundary_pole_indices(space)) == 2 * 7 + 2 * 5 - 4
    w = nat.ThinPlateWeights.isotropic(stretch=0.5, bend=2.0)
    assert np.allclose(w.alpha, 0.5 * np.eye(2)) and np.allclose(w.beta, 2.0)
    options = nat.SolveOptions(rank_tolerance=1e-8)
    assert options.rank_tolerance == 1e-8
    c = line([0, 0, 0], [2, 0, 0], 1.0, 3.0)
    assert (c.first(), c.last(), c.dim(), c.pole_count()) == (1.0, 3.0, 3, 2)
    assert np.allclose(c.evaluate(2.0), [1, 0, 0])


def test_project_and_solve_pipeline():
    """A sheet through an arc above a plane: projection, solve, independent deviation."""
    base = plane_sheet(10.0, spans=6)
    angles = np.linspace(0.0, math.pi, 5)
    arc_pts = np.array([[5 + 3 * math.cos(a), 5 + 3 * math.sin(a), 2.0] for a in angles])
    target = nat.BSplineCurve(degree=4, knots=[0] * 5 + [1] * 5, poles=arc_pts)
    pre = nat.project_curve(base, target)
    assert pre.curve.first() == 0.0 and pre.curve.last() == 1.0
    assert pre.max_distance == pytest.approx(2.0, abs=1e-12)
    assert pre.fit_error < 1e-8
    problem = nat.SheetProblem(
        space=base.space,
        initial_poles=base.poles,
        energy=nat.ThinPlateWeights.isotropic(0.0, 1.0),
        curves=[nat.CurveConstraint(preimage=pre.curve, target=target)],
        fixed_poles=nat.boundary_pole_indices(base.space),
    )
    result = nat.solve_sheet(problem)
    assert result.report.unknowns == 7 * 7  # interior poles of the 9 x 9 sheet
    solved = nat.BSplineSurface(space=base.space, poles=result.poles)
    assert nat.incidence_error(base.space, result.poles, problem.curves[0]) < 1e-6
    assert nat.max_deviation(solved, target) < 1e-6
    check = nat.check_brep(nat.face_brep(solved))
    assert check.valid and check.message == "valid"


# --------------------------------------------------------------------------------------------
# FreeCAD round trips


@pytest.fixture(scope="module")
def Part():
    pytest.importorskip("FreeCAD")
    return pytest.importorskip("Part")


def freecad_bspline_face(Part):
    """A rational 5 x 4 B-spline face with non-uniform knots, built by FreeCAD."""
    rng = np.random.default_rng(4)
    nu, nv = 5, 4
    poles = [
        [
            FreeCADVector(i * 2.0 + rng.uniform(-0.3, 0.3), j * 3.0 + rng.uniform(-0.3, 0.3), rng.uniform(-1, 1))
            for j in range(nv)
        ]
        for i in range(nu)
    ]
    weights = [[float(rng.uniform(0.6, 1.8)) for _ in range(nv)] for _ in range(nu)]
    surf = Part.BSplineSurface()
    # u: degree 3, knots 0, 0.35, 1 (5 poles); v: degree 2, knots -1, 0.4, 2 (4 poles).
    surf.buildFromPolesMultsKnots(
        poles, [4, 1, 4], [3, 1, 3], [0.0, 0.35, 1.0], [-1.0, 0.4, 2.0], False, False, 3, 2, weights
    )
    return surf


def FreeCADVector(x, y, z):
    import FreeCAD

    return FreeCAD.Vector(float(x), float(y), float(z))


def test_freecad_face_round_trip_matches_freecad_evaluation(Part):
    surf = freecad_bspline_face(Part)
    face = surf.toShape()
    sheet = nat.surface_from_face_brep(face.exportBrepToString())
    assert sheet.space.rational()
    assert (sheet.space.nu(), sheet.space.nv()) == (5, 4)
    assert sheet.space.domain() == (0.0, 1.0, -1.0, 2.0)
    rng = np.random.default_rng(1)
    params = [(rng.uniform(0, 1), rng.uniform(-1, 2)) for _ in range(100)]
    for u, v in params:
        assert np.allclose(sheet.evaluate(u, v), tuple(surf.value(u, v)), atol=1e-12, rtol=0)

    shape = Part.Shape()
    shape.importBrepFromString(nat.face_brep(sheet))
    assert shape.isValid() and len(shape.Faces) == 1
    back = shape.Faces[0].Surface
    for u, v in params:
        assert (back.value(u, v) - surf.value(u, v)).Length < 1e-12
    assert shape.Area == pytest.approx(face.Area, rel=1e-9)


def test_freecad_trimmed_cylinder_face(Part):
    cyl = Part.makeCylinder(2.0, 5.0)
    lateral = [f for f in cyl.Faces if f.Surface.TypeId == "Part::GeomCylinder"][0]
    sheet = nat.surface_from_face_brep(lateral.exportBrepToString())
    u0, u1, v0, v1 = sheet.space.domain()
    for i in range(11):
        for j in range(11):
            p = sheet.evaluate(u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10)
            assert math.hypot(p[0], p[1]) == pytest.approx(2.0, abs=1e-12)
            assert -1e-12 <= p[2] <= 5.0 + 1e-12
    shape = Part.Shape()
    shape.importBrepFromString(nat.face_brep(sheet))
    assert shape.isValid()
    # The lateral area 2 pi r h (Part's Area of its own toNurbs conversion was off by 0.3 %).
    area = nat.mass_properties(shape.exportBrepToString(), 1e-10)[0]
    assert area == pytest.approx(2 * math.pi * 2.0 * 5.0, rel=1e-9)


def test_freecad_edges(Part):
    import FreeCAD

    bc = Part.BSplineCurve()
    bc.interpolate([FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1, 2, 0), FreeCAD.Vector(3, 1, 1), FreeCAD.Vector(4, 4, 2)])
    curve = nat.curve_from_edge_brep(bc.toShape().exportBrepToString())
    assert (curve.first(), curve.last()) == pytest.approx((bc.FirstParameter, bc.LastParameter))
    for t in np.linspace(bc.FirstParameter, bc.LastParameter, 25):
        assert np.allclose(curve.evaluate(t), tuple(bc.value(t)), atol=1e-12, rtol=0)

    arc = Part.makeCircle(3.0, FreeCAD.Vector(1, 1, 1), FreeCAD.Vector(0, 0, 1), 0.0, 120.0)
    curve = nat.curve_from_edge_brep(arc.exportBrepToString())
    assert curve.rational()
    for t in np.linspace(curve.first(), curve.last(), 25):
        p = curve.evaluate(t)
        assert math.hypot(p[0] - 1, p[1] - 1) == pytest.approx(3.0, abs=1e-12)
        assert p[2] == pytest.approx(1.0, abs=1e-12)
    assert np.allclose(curve.evaluate(curve.first()), tuple(arc.Vertexes[0].Point), atol=1e-12)
    assert np.allclose(curve.evaluate(curve.last()), tuple(arc.Vertexes[1].Point), atol=1e-12)


def test_step_round_trip_with_freecad(Part, tmp_path):
    sheet = nat.surface_from_face_brep(freecad_bspline_face(Part).toShape().exportBrepToString())
    brep = nat.face_brep(sheet)
    path = str(tmp_path / "sheet.step")
    nat.write_step(brep, path)
    assert "AUTOMOTIVE_DESIGN" in Path(path).read_text()  # AP214
    again = nat.read_step(path)
    assert nat.check_brep(again).valid
    original = Part.Shape()
    original.importBrepFromString(brep)
    imported = Part.read(path)
    assert imported.Area == pytest.approx(original.Area, rel=1e-6)
    imported.check(True)  # OCCT's full check, Boolean operations' included (raises otherwise)


def test_coupled_operators_through_the_binding():
    # A flat unit sheet, boundary held: a normal constraint and a plane attractor switch the
    # solve to the coupled 3n system, and the normal is met.
    space = nat.SplineSpace.uniform(3, 3, 6, 6)
    n = space.size() if callable(space.size) else space.size
    nv = space.nv() if callable(space.nv) else space.nv
    gu = [sum(space.knots_u[i + 1:i + 4]) / 3.0 for i in range(len(space.knots_u) - 4)]
    gv = [sum(space.knots_v[i + 1:i + 4]) / 3.0 for i in range(len(space.knots_v) - 4)]
    poles = np.array([[gu[k // nv], gv[k % nv], 0.0] for k in range(n)])
    normal = np.array([0.2, -0.1, 1.0])
    problem = nat.SheetProblem(space=space, initial_poles=poles,
                               energy=nat.ThinPlateWeights.isotropic(0.1, 1.0),
                               fixed_poles=list(nat.boundary_pole_indices(space)))
    problem.points = [nat.PointConstraint(u=0.5, v=0.5, target=[0.5, 0.5, 0.2])]
    problem.normals = [nat.NormalConstraint(u=0.5, v=0.5, normal=normal)]
    problem.attractors = [nat.Attractor(kind=nat.AttractorKind.plane,
                                        region=nat.Region(u0=0.1, u1=0.3, v0=0.1, v1=0.3),
                                        origin=[0, 0, 0.05], direction=[0, 0, 1], strength=1e3)]
    result = nat.solve_sheet(problem, nat.SolveOptions())
    assert result.report.coupled
    surface = nat.BSplineSurface(space=space, poles=result.poles)
    h = 1e-6
    wu = (surface.evaluate(0.5 + h, 0.5) - surface.evaluate(0.5 - h, 0.5)) / (2 * h)
    wv = (surface.evaluate(0.5, 0.5 + h) - surface.evaluate(0.5, 0.5 - h)) / (2 * h)
    assert abs(np.dot(wu, normal)) < 1e-6 * np.linalg.norm(wu)
    assert abs(np.dot(wv, normal)) < 1e-6 * np.linalg.norm(wv)
    with pytest.raises(nat.InvalidInput, match="normal constraint 0"):
        problem.normals = [nat.NormalConstraint(u=0.5, v=0.5, normal=[0, 0, 0])]
        nat.solve_sheet(problem, nat.SolveOptions())


def test_ribbon_through_the_binding_tilts_the_sheet():
    # Boundary on the plane z = 0.4 x, interior started flat: a ribbon asking for that plane's
    # normal along a diagonal brings the sheet onto the plane.
    space = nat.SplineSpace.uniform(3, 3, 5, 5)
    n = space.size() if callable(space.size) else space.size
    nv = space.nv() if callable(space.nv) else space.nv
    g = [sum(space.knots_u[i + 1:i + 4]) / 3.0 for i in range(len(space.knots_u) - 4)]
    poles = np.array([[g[k // nv], g[k % nv], 0.4 * g[k // nv]] for k in range(n)])
    fixed = list(nat.boundary_pole_indices(space))
    start = poles.copy()
    start[[k for k in range(n) if k not in set(fixed)], 2] = 0.0
    line = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1], poles=np.array([[0.2, 0.3], [0.8, 0.6]]))
    field = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1],
                             poles=np.array([[-0.4, 0.0, 1.0], [-0.4, 0.0, 1.0]]))
    ribbon = nat.RibbonConstraint(preimage=line, normals=field)
    problem = nat.SheetProblem(space=space, initial_poles=start,
                               energy=nat.ThinPlateWeights.isotropic(0.1, 1.0), fixed_poles=fixed)
    problem.ribbons = [ribbon]
    result = nat.solve_sheet(problem, nat.SolveOptions())
    assert result.report.coupled
    assert nat.ribbon_angle_error(space, result.poles, ribbon) < 1e-9
    assert np.abs(result.poles - poles).max() < 1e-9
