# SPDX-License-Identifier: LGPL-2.1-or-later
"""Persistence and long sessions: every feature type through save/reopen, files from newer
versions, files opened without VarSurf, restoring without running file code, undo/redo of every
command, hostile calls into the native module, and a soak of drag/recompute cycles."""

import json
import os
import re
import subprocess
import zipfile
from pathlib import Path

import FreeCAD
import Part
import pytest

import varsurf
from varsurf.app import actions, macro, selection, transaction
from varsurf.app.persistence import STATE_VERSION

import scenes
from scenes import Sel

import hinge_pair  # noqa: E402

V = FreeCAD.Vector
REPO = Path(__file__).resolve().parents[2]
FREECAD_LIB = "/usr/lib/freecad-python3/lib"


def geometry(obj):
    """What a recompute produces: the shape's exact geometry and the result properties."""
    shape = getattr(obj, "Shape", None) or Part.Shape()
    return geometry_of_shape(shape) + (getattr(obj, "Status", ""),)


def geometry_of_shape(shape):
    poles = []
    for face in shape.Faces:
        surface = face.Surface
        if hasattr(surface, "getPoles"):
            poles += [(p.x, p.y, p.z) for row in surface.getPoles() for p in row]
    for edge in shape.Edges:
        curve = edge.Curve
        if hasattr(curve, "getPoles"):
            poles += [(p.x, p.y, p.z) for p in curve.getPoles()]
    return poles, len(shape.Faces), len(shape.Edges)


def max_gap(a, b):
    assert len(a[0]) == len(b[0]) and a[1:] == b[1:], (a[1:], b[1:])
    return max((max(abs(x - y) for x, y in zip(p, q)) for p, q in zip(a[0], b[0])), default=0.0)


def varsurf_objects(doc):
    return [o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "TYPE", "").startswith("VarSurf")]


def every_feature_document(doc):
    """A Solid of two sheets with a Hinge, a Sheet with constraints of several kinds, and a
    SpaceCurve: one of each VarSurf feature type."""
    hinge_pair.build(doc, angle=120.0)
    base = scenes.add_face(doc, scenes.curved_face().translated(V(0, 300, 0)), "Base")
    ridge = doc.addObject("Part::Feature", "Ridge")
    ridge.Shape = Part.LineSegment(V(10, 340, 8), V(90, 340, 8)).toShape()
    sheet = varsurf.make_sheet((base, "Face1"), [(ridge, "Edge1")], min_spans=8, max_spans=16, name="Dome")
    varsurf.make_constraint(sheet, "Point", uv=(0.3, 0.3), origin=(30, 324, 6))
    varsurf.make_constraint(sheet, "Normal", uv=(0.7, 0.7), vector=(0.1, 0, 1))
    varsurf.make_constraint(sheet, "PointAttractor", uv=(0.5, 0.2), origin=(50, 316, 9))
    varsurf.make_space_curve((ridge, "Edge1"), handle_parameters=[0.0, 0.5, 1.0],
                             handles=[V(10, 340, 8), V(50, 345, 12), V(90, 340, 8)])
    doc.recompute()
    for obj in varsurf_objects(doc):
        assert obj.isValid(), f"{obj.Label}: {obj.getStatusString()}"
    types = {o.Proxy.TYPE for o in varsurf_objects(doc)}
    assert {"VarSurf::Sheet", "VarSurf::Solid", "VarSurf::Hinge", "VarSurf::Constraint",
            "VarSurf::SpaceCurve"} <= types, types
    return doc


def test_every_feature_type_recomputes_identically_after_save_and_reopen(doc, native, tmp_path):
    every_feature_document(doc)
    before = {o.Name: geometry(o) for o in varsurf_objects(doc)}
    path = str(tmp_path / "every.FCStd")
    doc.saveAs(path)
    again = FreeCAD.openDocument(path)
    try:
        restored = {o.Name: geometry(o) for o in varsurf_objects(again)}
        assert set(restored) == set(before)
        for name in before:  # as saved, before any recompute
            assert max_gap(restored[name], before[name]) < 1e-12, name  # BREP text round trip
        for obj in again.Objects:
            obj.touch()
        again.recompute()
        for obj in varsurf_objects(again):
            assert obj.isValid(), f"{obj.Label}: {obj.getStatusString()}"
            assert getattr(obj.Proxy, "state_version", STATE_VERSION) == STATE_VERSION
            gap = max_gap(geometry(obj), before[obj.Name])
            assert gap < 1e-9, (obj.Label, gap)
            assert geometry(obj)[3].split(",")[0] == before[obj.Name][3].split(",")[0], obj.Label
    finally:
        FreeCAD.closeDocument(again.Name)


def _rewrite_document_xml(path, edit):
    """Rewrite Document.xml inside an FCStd (a zip) with edit(text) -> text."""
    with zipfile.ZipFile(path) as zin:
        items = [(info, zin.read(info.filename)) for info in zin.infolist()]
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zout:
        for info, data in items:
            if info.filename == "Document.xml":
                data = edit(data.decode("utf-8")).encode("utf-8")
            zout.writestr(info, data)


def _edit_proxy_states(text, edit):
    """Document.xml with each VarSurf proxy state (base64 JSON) replaced by edit(state) -> str."""
    import base64

    def one(match):
        state = base64.b64decode(match.group(1)).decode("utf-8")
        new = edit(state) if "VarSurf::" in state else state
        return (f'<Python value="{base64.b64encode(new.encode("utf-8")).decode("ascii")}" '
                f'encoded="yes"{match.group(2)}/>')

    return re.sub(r'<Python value="([^"]*)" encoded="yes"([^>]*)/>', one, text)


def _simple_document(doc, tmp_path, name="simple.FCStd", constraint=True):
    base = scenes.add_face(doc, scenes.flat_face(), "Base")
    ridge = scenes.add_line_sketch(doc, "Ridge", 5.0, (10, 40), (90, 40))
    sheet = varsurf.make_sheet((base, "Face1"), [(ridge, "Edge1")], min_spans=4, max_spans=16, name="Sheet")
    if constraint:
        varsurf.make_constraint(sheet, "Point", uv=(0.3, 0.3), origin=(30, 24, 3))
    doc.recompute()
    assert sheet.isValid()
    path = str(tmp_path / name)
    doc.saveAs(path)
    return path, geometry(sheet)


def test_a_file_from_a_newer_version_keeps_its_data_and_says_so(doc, native, tmp_path, console_errors):
    path, saved = _simple_document(doc, tmp_path, constraint=False)
    FreeCAD.closeDocument(doc.Name)
    _rewrite_document_xml(path, lambda text: _edit_proxy_states(
        text, lambda state: json.dumps(dict(json.loads(state), version=99))))
    again = FreeCAD.openDocument(path)
    try:
        sheet = again.getObject("Sheet")
        assert sheet.Proxy.state_version == 99
        assert max_gap(geometry(sheet), saved) < 1e-12  # data as saved
        stretch = sheet.Stretch
        for obj in again.Objects:
            obj.touch()
        again.recompute()
        assert not sheet.isValid()
        report = console_errors()
        assert "newer VarSurf" in report and "Sheet" in report and "update VarSurf" in report, report
        assert max_gap(geometry(sheet), saved) < 1e-12  # nothing of it was changed
        assert sheet.Stretch == stretch
        # the base and sketch are not VarSurf's and recompute as usual
        assert again.getObject("Ridge").isValid()
        # saved here, the object keeps its newer mark (a later session must not take it as its own)
        again.save()
    finally:
        FreeCAD.closeDocument(again.Name)
    third = FreeCAD.openDocument(path)
    try:
        assert third.getObject("Sheet").Proxy.state_version == 99
        assert max_gap(geometry(third.getObject("Sheet")), saved) < 1e-12
    finally:
        FreeCAD.closeDocument(third.Name)


def _run_without_varsurf(tmp_path, code):
    """Run `code` in a fresh FreeCAD whose Mod folder has no VarSurf (a user without it)."""
    home = tmp_path / "home-without-varsurf"
    (home / ".local" / "share" / "FreeCAD" / "Mod").mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, HOME=str(home))
    env.pop("PYTHONPATH", None)
    script = tmp_path / "without.py"
    script.write_text(f"import sys\nsys.path.append({FREECAD_LIB!r})\nimport FreeCAD\n{code}\n")
    return subprocess.run(["/usr/bin/python3", str(script)], env=env, capture_output=True, text=True,
                          timeout=300, cwd=str(tmp_path))


def test_a_file_opens_without_varsurf_and_keeps_its_data(doc, native, tmp_path):
    path, saved = _simple_document(doc, tmp_path)
    FreeCAD.closeDocument(doc.Name)
    resaved = str(tmp_path / "resaved.FCStd")
    run = _run_without_varsurf(tmp_path, f"""
import importlib.util
assert importlib.util.find_spec("varsurf") is None, "VarSurf must not be importable here"
doc = FreeCAD.openDocument({path!r})
sheet = doc.getObject("Sheet")
print("OBJECTS", len(doc.Objects), "STRETCH", sheet.Stretch, "FACES", len(sheet.Shape.Faces))
for obj in doc.Objects:
    obj.touch()
doc.recompute()  # nothing to run the proxies with: must not crash
doc.saveAs({resaved!r})
print("SAVED")
""")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "SAVED" in run.stdout and "FACES 1" in run.stdout, run.stdout
    # Back with VarSurf: the data came through the foreign session and recomputes the same.
    again = FreeCAD.openDocument(resaved)
    try:
        sheet = again.getObject("Sheet")
        assert max_gap(geometry(sheet), saved) < 1e-12
        for obj in again.Objects:
            obj.touch()
        again.recompute()
        assert sheet.isValid(), sheet.getStatusString()
        assert max_gap(geometry(sheet), saved) < 1e-9
    finally:
        FreeCAD.closeDocument(again.Name)


def test_restoring_runs_no_code_from_the_file(doc, native, tmp_path):
    path, _saved = _simple_document(doc, tmp_path)
    FreeCAD.closeDocument(doc.Name)
    marker = tmp_path / "pwned"
    payload = f"__import__('os').system('touch {marker}')"

    def edit(state):
        # the Sheet's state becomes code in every field; the Constraint's a bare string of code
        if "VarSurf::Sheet" in state:
            return json.dumps({"type": payload, "version": payload, "eval": payload})
        return json.dumps(payload)

    _rewrite_document_xml(path, lambda text: _edit_proxy_states(text, edit))
    again = FreeCAD.openDocument(path)
    try:
        sheet = again.getObject("Sheet")
        for obj in again.Objects:
            obj.touch()
        again.recompute()
        assert not marker.exists()
        assert sheet.Proxy.Type == "VarSurf::Sheet"  # the class's, not the file's
        constraint = again.getObject("Constraint")
        assert not constraint.isValid() and "unreadable" in constraint.getStatusString()
        # the Sheet waits on its broken constraint; alone, it refuses its own unreadable state
        assert not sheet.isValid() or "Touched" in sheet.State
        sheet.Constraints = []
        again.recompute()
        assert not sheet.isValid() and "unreadable" in sheet.getStatusString()
    finally:
        FreeCAD.closeDocument(again.Name)
    assert not marker.exists()


# --- undo / redo -------------------------------------------------------------------------------

def snapshot(doc):
    """Every object's type and every property's value; shapes by their exact geometry (poles of
    every face and edge, counts, placement): FreeCAD's undo restores a shape with an equivalent
    but differently composed TopLoc location, so the BREP text itself may differ."""
    state = {}
    for obj in doc.Objects:
        props = {}
        for name in obj.PropertiesList:
            if name == "Proxy":
                continue
            value = obj.getPropertyByName(name)
            if isinstance(value, Part.Shape):
                value = (geometry_of_shape(value), value.Placement) if not value.isNull() else ""
            props[name] = repr(value)
        state[obj.Name] = (obj.TypeId, props)
    return state


def assert_same(a, b, what):
    assert sorted(a) == sorted(b), (what, sorted(set(a) ^ set(b)))
    for name in a:
        assert a[name][0] == b[name][0], (what, name)
        diff = [p for p in a[name][1] if a[name][1].get(p) != b[name][1].get(p)]
        assert not diff, (what, name, diff)


def _undo_scene(doc):
    from test_constraint_commands import _scene

    doc.UndoMode = 1
    surface = scenes.add_face(doc, scenes.flat_face())
    rail = scenes.add_line_sketch(doc, "Rail", 5.0, (20.0, 15.0), (40.0, 20.0))
    pin = doc.addObject("Part::Vertex", "Pin")
    pin.X, pin.Y, pin.Z = 60.0, 50.0, 9.0
    doc.recompute()
    sheet = varsurf.make_sheet((surface, "Face1"), [(rail, "Edge1")], min_spans=8, max_spans=16)
    doc.recompute()
    return surface, rail, pin, sheet, _scene(doc)


def _constraint_picks(kind, sheet, pin, o):
    from test_constraint_commands import LOOP_EDGES

    from varsurf.solve import constraints

    if kind in selection.VERTEX_KINDS:
        return [Sel(sheet), Sel(pin, "Vertex1")]
    special = {"Ribbon": [Sel(o.seam, "Edge1")], "CurveAttractor": [Sel(o.second, "Edge1")],
               "G0": [Sel(o.second, "Edge1")], "G1": [Sel(o.second, "Edge1"), Sel(o.flat, "Face1")],
               "G2": [Sel(o.second, "Edge1"), Sel(o.flat, "Face1")],
               "SurfaceAttractor": [Sel(o.roof, "Face1")], "FrozenRegion": LOOP_EDGES(o),
               "CurveMap": [Sel(o.seam, "Edge1"), Sel(o.second, "Edge1")], "RegionMap": [Sel(o.roof, "Face1")]}
    if kind in special:
        return [Sel(sheet)] + special[kind]
    assert kind not in constraints.CURVE_KINDS and kind not in constraints.SHAPE_KINDS, kind
    return [Sel(sheet, "Face1")]


def _commands(doc, surface, rail, pin, sheet, o):
    """(name, run) for every document-changing command, as its GUI command runs it."""
    from varsurf.solve import constraints

    run = macro.exec_line
    out = [("Sheet", lambda: actions.run_sheet_command([Sel(surface, "Face1"), Sel(rail, "Edge1")], do_command=run))]
    for kind in constraints.KINDS:
        picks = _constraint_picks(kind, sheet, pin, o)
        out.append((kind, lambda kind=kind, picks=picks: actions.run_constraint_command(kind, picks, do_command=run)))
    for function in ("install_rest_shape", "melt"):
        lines = ["import varsurf", f"varsurf.{function}({macro.ref(sheet)})"]
        out.append((function, lambda lines=lines, f=function: transaction.run_in_transaction(doc, f"VarSurf {f}",
                                                                                             lines, run)))
    out.append(("SpaceCurve", lambda: actions.run_space_curve_command([Sel(o.second, "Edge1")], do_command=run)))
    return out


def test_undo_and_redo_of_every_command_restore_the_exact_states(doc, native):
    surface, rail, pin, sheet, o = _undo_scene(doc)
    for name, command in _commands(doc, surface, rail, pin, sheet, o):
        before = snapshot(doc)
        undo_count = len(doc.UndoNames)
        command()
        assert len(doc.UndoNames) == undo_count + 1, (name, doc.UndoNames[:3])  # one undo step
        after = snapshot(doc)
        assert after != before, name
        doc.undo()
        assert_same(snapshot(doc), before, f"undo {name}")
        doc.redo()
        assert_same(snapshot(doc), after, f"redo {name}")
        doc.undo()  # the next command starts from the plain scene
        assert_same(snapshot(doc), before, f"undo again {name}")


def test_undo_and_redo_of_joining_and_hinging(doc, native):
    doc.UndoMode = 1
    solid = hinge_pair.build(doc, angle=120.0)
    sheets = list(solid.Sheets)
    seam = doc.getObject("Seam")
    for obj in [o for o in doc.Objects if o.TypeId == "App::FeaturePython" and "Hinge" in o.Name] + [solid]:
        doc.removeObject(obj.Name)
    doc.recompute()
    run = macro.exec_line
    before = snapshot(doc)
    made = actions.run_solid_command([Sel(s) for s in sheets], do_command=run)
    assert made is not None and made.isValid(), made and made.getStatusString()
    after_solid = snapshot(doc)
    hinge = actions.run_hinge_command([Sel(sheets[0]), Sel(sheets[1]), Sel(seam, "Edge1")], do_command=run,
                                      angle=120.0)
    assert hinge is not None
    after_hinge = snapshot(doc)
    doc.undo()
    assert_same(snapshot(doc), after_solid, "undo hinge")
    doc.undo()
    assert_same(snapshot(doc), before, "undo solid")
    doc.redo()
    assert_same(snapshot(doc), after_solid, "redo solid")
    doc.redo()
    assert_same(snapshot(doc), after_hinge, "redo hinge")


# --- the native boundary -----------------------------------------------------------------------

HOSTILE = Path(__file__).resolve().parent / "hostile_native_calls.py"


def _hostile_totals(stdout):
    line = [row for row in stdout.splitlines() if row.startswith("CALLS ")][-1].split()
    return {k: int(v) for k, v in zip(line[::2], line[1::2])}


def test_every_native_function_answers_hostile_arguments_with_an_exception(native, tmp_path):
    """Every function, method and constructor of the extension, called with well-typed hostile
    arguments built from its signature (NaN, inf, huge, negative and zero numbers; empty,
    NaN-filled, huge and wrongly sized arrays; spaces, surfaces, curves, problems and options with
    one bad field each), one parameter at a time: each call passes the binding's type conversion
    and reaches the core, which returns or raises a Python exception; the process never dies and
    no call hangs; a solve that returns has finite poles."""
    run = subprocess.run(["/usr/bin/python3", str(HOSTILE), str(REPO / "src"), str(tmp_path)], capture_output=True,
                         text=True, timeout=1200, env=dict(os.environ, VARSURF_HOSTILE_HANG="120"),
                         cwd=str(tmp_path))  # calls writing to relative paths ("garbage") write there
    assert run.returncode == 0, (run.returncode, run.stdout[-3000:], run.stderr[-3000:])
    totals = _hostile_totals(run.stdout)
    print("native boundary:", totals)
    targets = {line.split()[1]: (int(line.split()[2]), int(line.split()[3])) for line in run.stdout.splitlines()
               if line.startswith("TARGET ")}
    assert not [line for line in run.stdout.splitlines() if line.startswith("UNKNOWN")], run.stdout[-3000:]
    assert totals["BAD_RESULTS"] == 0, [line for line in run.stdout.splitlines() if line.startswith("BAD")]
    # well-typed: every call reaches the core (none is a pybind11 conversion TypeError)
    assert totals["REFUSED_BY_BINDING"] == 0 and totals["REACHED"] == totals["CALLS"], totals
    assert totals["CALLS"] >= 3000 and totals["RAISED"] >= totals["CALLS"] // 2, totals
    # every module function and every method of every class with one was called
    functions = {n for n, f in vars(native).items() if not n.startswith("_") and callable(f)
                 and not isinstance(f, type)}
    assert functions <= set(targets), functions - set(targets)
    assert all(reached >= 1 for _calls, reached in targets.values())


@pytest.mark.parametrize("call", [
    "nat.normal_field_between(nat.BSplineCurve(), line, 0.0, 50)",  # crashed: the scale of no poles
    "nat.region_quadrature(nat.SplineSpace(), nat.Region())",  # crashed: the domain of no knots
])
def test_fixed_native_crashes_stay_fixed(native, call):
    """Calls that once killed the process, each in its own process."""
    script = ("import sys; sys.path.insert(0, sys.argv[1]); import numpy as np\n"
              "from varsurf import _native as nat\n"
              "line = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1], poles=np.array([[2.0, 5, 0], [8, 5, 0]]))\n"
              f"try:\n    {call}\nexcept nat.InvalidInput as e:\n    print('InvalidInput', e)\n")
    run = subprocess.run(["/usr/bin/python3", "-c", script, str(REPO / "src")], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0 and "InvalidInput" in run.stdout, (run.returncode, run.stdout, run.stderr[-2000:])


@pytest.mark.parametrize("call", [
    "nat.incidence_error(sp, poles, nat.CurveConstraint(uv, line, 1.0, False), samples=2**31 - 1)",
    "nat.ribbon_angle_error(sp, poles, nat.RibbonConstraint(uv, line, 1.0), samples=2**31 - 1)",
    "nat.BaseTrim(nat.face_brep(flat)).place_curve(uv, 1e-3, samples=2**31 - 1)",
    # knots up to 1e308 (finite) once passed validation; the closest-point search ran for minutes
    "nat.project_point(nat.BSplineSurface(space=nat.SplineSpace(3, 3, [0] * 4 + [1e308] * 4, "
    "[0] * 4 + [1] * 4), poles=np.zeros((16, 3))), np.ones(3))",
    # 2^31 spans: were allocated (about 50 s to a MemoryError)
    "nat.SplineSpace.uniform(3, 3, 2**31 - 1, 2)",
    # poles of 1e308 (finite, overflowing when evaluated): a global search ran for minutes
    "nat.max_deviation(nat.BSplineSurface(space=sp, poles=np.full((25, 3), 1e308)), line, samples=50)",
])
def test_hostile_counts_and_sizes_are_refused_promptly(native, call):
    """Counts and sizes that once ran for minutes are refused at once (within 10 s, in a process of
    their own)."""
    script = ("import sys; sys.path.insert(0, sys.argv[1]); import numpy as np\n"
              "from varsurf import _native as nat\n"
              "sp = nat.SplineSpace.uniform(3, 3, 2, 2)\n"
              "g = [0, 1 / 6, 1 / 2, 5 / 6, 1]\n"
              "poles = np.array([[10 * u, 10 * v, 0.0] for u in g for v in g])\n"
              "flat = nat.BSplineSurface(space=sp, poles=poles)\n"
              "line = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1], poles=np.array([[2.0, 5, 0], [8, 5, 0]]))\n"
              "uv = nat.BSplineCurve(degree=1, knots=[0, 0, 1, 1], poles=np.array([[0.2, 0.5], [0.8, 0.5]]))\n"
              f"try:\n    {call}\nexcept (ValueError, RuntimeError, MemoryError) as e:\n"
              "    print('refused', type(e).__name__, e)\n")
    try:
        run = subprocess.run(["/usr/bin/python3", "-c", script, str(REPO / "src")], capture_output=True, text=True,
                             timeout=10)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{call} ran over 10 s")
    assert run.returncode == 0 and "refused" in run.stdout, (run.returncode, run.stdout, run.stderr[-2000:])


# --- a long session ----------------------------------------------------------------------------

def _rss_bytes():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


SOAK_CYCLES = 1000
SOAK_WARMUP = 100


def test_soak_of_drag_and_recompute_cycles_keeps_memory_flat(doc, native):
    """1000 cycles of a drag move and a full recompute on a sheet with 10 constraints, switching
    the dragged constraint every 10 cycles (each switch finishes a drag: an undo step). Resident
    memory after the warm-up and at the end differ by less than 5 %."""
    import gc

    from varsurf.app import drag

    base = scenes.add_face(doc, scenes.flat_face(), "Base")
    rail = doc.addObject("Part::Feature", "Rail")
    rail.Shape = Part.LineSegment(V(10, 70, 3), V(90, 70, 3)).toShape()
    sheet = varsurf.make_sheet((base, "Face1"), [(rail, "Edge1")], min_spans=8, max_spans=8, name="Soaked")
    spots = [(0.15 + 0.17 * (k % 5), 0.2 + 0.3 * (k // 5)) for k in range(10)]
    pins = [varsurf.make_constraint(sheet, "Point", uv=uv, origin=(100 * uv[0], 80 * uv[1], 2.0))
            for uv in spots]
    doc.recompute()
    assert sheet.isValid() and len(sheet.Constraints) == 10, sheet.getStatusString()

    session, session_target, start = None, None, None
    for cycle in range(SOAK_CYCLES):
        c = pins[(cycle // 10) % 10]
        target = c.Origin + V(0, 0, 0.5 if cycle % 2 else -0.5)
        if cycle % 10 == 0:
            if session is not None:
                session.finish(session_target)
            session = drag.PointDrag(sheet, c)
        session.move(target)
        session_target = target
        sheet.touch()
        doc.recompute()
        assert sheet.isValid(), (cycle, sheet.getStatusString())
        if cycle + 1 == SOAK_WARMUP:
            gc.collect()
            start = _rss_bytes()
    session.finish(session_target)
    gc.collect()
    end = _rss_bytes()
    growth = (end - start) / start
    print(f"soak: {SOAK_CYCLES} drag/recompute cycles, resident memory {start / 1e6:.1f} MB after "
          f"{SOAK_WARMUP}, {end / 1e6:.1f} MB at the end: growth {100 * growth:+.2f} %")
    assert growth < 0.05
