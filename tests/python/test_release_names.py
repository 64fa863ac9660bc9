# SPDX-License-Identifier: LGPL-2.1-or-later
"""Scripts and recorded macros of release 0.1.0 run on the tier layout: the module names they
import (varsurf.model, varsurf.api, varsurf.drag, varsurf.analysis, ...) load as their new homes,
and the macro lines that release recorded replay with the same result as the current ones."""

import importlib

import FreeCAD
import Part

import varsurf
from varsurf.app import macro
from varsurf.app import sheet as sheet_feature
from varsurf.solve import errors

V = FreeCAD.Vector


def _scene(doc):
    plane = doc.addObject("Part::Plane", "Plane")
    plane.Length, plane.Width = 100.0, 60.0
    rail = doc.addObject("Part::Feature", "Rail")
    rail.Shape = Part.LineSegment(V(10, 30, 6), V(90, 30, 6)).toShape()
    doc.recompute()
    return plane, rail


def test_every_old_module_name_loads_what_it_held():
    held = {  # a name each old module had, and where it lives now
        "varsurf.model": ("solve_sheet_on_face", "varsurf.solve.sheet"),
        "varsurf.constraints": ("KINDS", "varsurf.solve.constraints"),
        "varsurf.assembly": ("build_solid", "varsurf.solve.assembly"),
        "varsurf.joint": ("HingeSpec", "varsurf.solve.joint"),
        "varsurf.space_curve": ("VariationalCurve", "varsurf.solve.space_curve"),
        "varsurf.analysis": ("plot_lcurve", "varsurf.app.analysis"),
        "varsurf.persistence": ("VersionedState", "varsurf.app.persistence"),
        "varsurf.api": ("selection_to_sheet_args", "varsurf.app.selection"),
        "varsurf.joints_api": ("make_hinge", "varsurf.app.make_joints"),
        "varsurf.drag": ("PointDrag", "varsurf.app.drag"),
        "varsurf.progress": ("for_solve", "varsurf.app.progress"),
        "varsurf.preferences": ("sheet_defaults", "varsurf.app.preferences"),
    }
    assert set(held) == set(varsurf.MOVED)
    for old, (name, home) in held.items():
        module = importlib.import_module(old)
        assert getattr(module, name) is getattr(importlib.import_module(home), name), old
    # One class, whichever name a script catches it by.
    from varsurf.model import SheetError

    assert SheetError is errors.SheetError is varsurf.SheetError
    # The analysis fields answer through the old name too (their new home is the solve tier).
    assert (importlib.import_module("varsurf.analysis").analyse
            is importlib.import_module("varsurf.solve.analysis").analyse)


def test_a_release_script_solves_as_the_current_api_does(native):
    from varsurf import model  # as 0.1.0's scripts wrote it

    face = Part.makePlane(100.0, 60.0)
    edge = Part.LineSegment(V(10, 30, 6), V(90, 30, 6)).toShape()
    old = model.solve_sheet_on_face(face, [edge], stretch=0.5, tolerance=0.001, min_spans=8)
    new = varsurf.solve_sheet_on_face(face, [edge], varsurf.SheetSettings(stretch=0.5, tolerance=0.001, min_spans=8))
    assert [list(r) for r in old.surface.poles] == [list(r) for r in new.surface.poles]
    assert old.max_deviations == new.max_deviations and max(new.max_deviations) <= 0.001


def test_macro_lines_recorded_by_the_release_replay(doc, native, tmp_path):
    plane, rail = _scene(doc)
    run = macro.exec_line
    # Lines as release 0.1.0's commands recorded them (its Sheet, drag and L-curve commands).
    run("import varsurf")
    run(f"_sheet = varsurf.make_sheet(({macro.ref(plane)}, 'Face1'), [({macro.ref(rail)}, ('Edge1',))])")
    run(f"App.getDocument({doc.Name!r}).recompute()")
    sheet = next(o for o in doc.Objects if getattr(getattr(o, "Proxy", None), "Type", "") == sheet_feature.TYPE)
    assert sheet.isValid(), sheet.getStatusString()
    run(f"_pin = varsurf.make_constraint({macro.ref(sheet)}, 'Point', uv=(0.5, 0.75), origin=(50, 45, 6))")
    pin = sheet.Constraints[-1]
    run("import varsurf.drag")
    run(f"varsurf.drag.set_point_target({macro.ref(pin)}, App.Vector(50.0, 45.0, 9.0))")
    run(f"App.getDocument({doc.Name!r}).recompute()")
    assert sheet.isValid(), sheet.getStatusString()
    assert sheet.Shape.distToShape(Part.Vertex(V(50, 45, 9)))[0] < float(sheet.Tolerance)
    sheet.SolveMode = "TSVD"
    doc.recompute()
    path = str(tmp_path / "lcurve.png")
    run("import varsurf.analysis")
    run(f"varsurf.analysis.plot_lcurve({macro.ref(sheet)}, {path!r})")
    assert (tmp_path / "lcurve.png").stat().st_size > 1000
