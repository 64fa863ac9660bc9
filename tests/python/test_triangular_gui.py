# SPDX-License-Identifier: LGPL-2.1-or-later
"""Runs tests/gui/triangular_gui.py in the real FreeCAD GUI under Xvfb: the TriangularSurface
command on a selected Mesh (its object, view provider and one undo step), its task panel (Update,
OK as one undo step, Cancel restoring), a document written without the GUI opened with its view
providers, and no traceback in the report view."""

from pathlib import Path

import FreeCAD
import pytest

import varsurf
from gui_run import run_gui_script
from test_triangular_surface import add_mesh, torus_mesh

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tests" / "gui" / "triangular_gui.py"
OUT = REPO / "out" / "gui-triangular"  # kept after the run: the screenshots are worth a look


@pytest.fixture(scope="module")
def gui(home, native, tmp_path_factory):
    path = tmp_path_factory.mktemp("triangular") / "headless_triangular.FCStd"
    doc = FreeCAD.newDocument("HeadlessTriangular")
    mesh = add_mesh(doc, *torus_mesh(6, 4))
    varsurf.make_triangular_surface(mesh, degree=4)
    doc.recompute()
    doc.saveAs(str(path))
    FreeCAD.closeDocument(doc.Name)
    mp = pytest.MonkeyPatch()
    mp.setenv("VARSURF_TRI_DOC", str(path))
    try:
        return run_gui_script(SCRIPT, OUT, "triangular.json")
    finally:
        mp.undo()


def test_the_command_makes_a_smooth_solid_in_one_undo_step(gui):
    assert "error" not in gui, gui.get("error")
    valid, status, view, mesh_shown, shown, closed, worst = gui["made"]
    assert valid and status.startswith("OK") and closed and worst < 0.01, status
    assert view == "ViewProviderTriangularSurface" and not mesh_shown and shown
    assert gui["undo_names"] == ["Add VarSurf triangular surface"]
    assert Path(gui["shot"]).is_file()


def test_the_panel_updates_commits_and_cancels(gui):
    assert "error" not in gui, gui.get("error")
    assert gui["clipped"] == [], gui["clipped"]
    degree, patches, worst = gui["updated"]
    assert degree == 4 and patches.startswith("96 (288") and worst.endswith("°"), gui["updated"]
    assert gui["panel_ok"] == [4, ["Edit VarSurf triangular surface"], True], gui["panel_ok"]
    assert gui["panel_cancel"] == [False, True, True], gui["panel_cancel"]
    assert gui["after_undo"] == ["Handle"], gui["after_undo"]
    assert Path(gui["panel_shot"]).is_file()


def test_a_document_built_without_the_gui_gets_its_view_providers(gui):
    assert gui["restored"] == ["ViewProviderTriangularSurface"], gui["restored"]
    assert gui["restored_valid"]


def test_the_report_view_has_no_traceback(gui):
    assert "Traceback" not in gui["report"], gui["report"]
