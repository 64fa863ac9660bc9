# SPDX-License-Identifier: LGPL-2.1-or-later
"""The PdeSurface task panel in the real FreeCAD GUI (tests/gui/pde_panel_gui.py under Xvfb)."""

from pathlib import Path

import pytest

from gui_run import run_gui_script

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tests" / "gui" / "pde_panel_gui.py"
OUT = REPO / "out" / "gui-pde-panel"  # kept after the run: pde_panel.png is worth a look


@pytest.fixture(scope="module")
def panel(home, native):
    return run_gui_script(SCRIPT, OUT, "pde_panel.json")


def test_the_panel_edits_a_and_the_regions_in_one_undoable_step(panel):
    assert "error" not in panel, panel.get("error")
    assert panel["shown"] == ["Hermite", 1.0, 0]
    assert panel["previewed"] == [2.5, [5.0, 0.25, 0.75, 0.25, 0.75], True]
    assert panel["ok"] == [2.5, 5, True, ["Edit VarSurf PDE surface"], True]
    assert panel["reloaded"] == [2.5, 1]
    assert panel["cancelled"] == [2.5, 5, True]  # the cancelled change is undone
    assert panel["clipped"] == [], panel["clipped"]
    assert Path(panel["shot"]).stat().st_size > 10000
