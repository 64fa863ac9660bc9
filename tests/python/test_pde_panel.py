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
    # (The OK above runs after clipped_widgets, which leaves the form deleted for OK's store: see
    # gui_helpers.clipped_widgets; Update stored the values, as `ok` shows.)


def test_a_rectangle_dragged_over_the_surface_paints_a(panel):
    """Paint in view: a left-button drag over the surface from (u, v) = (0.3, 0.3) to (0.6, 0.7)
    adds that rectangle with the Paint a value (6) and previews it, the view does not turn, and OK
    keeps it in one undoable step; a drag that starts off the surface paints nothing, and the next
    one on the surface paints again."""
    painted = panel["painted"]
    assert painted["view_moved"] < 1e-9
    a, u0, u1, v0, v1 = painted["regions"][5:]
    assert a == 6.0
    assert max(abs(u0 - 0.3), abs(u1 - 0.6), abs(v0 - 0.3), abs(v1 - 0.7)) < 0.01, painted["regions"]
    assert panel["painted_rows"] == 2
    assert panel["painted_off"] == painted["regions"]  # a drag from off the surface paints nothing
    after = panel["painted_after_off"]  # and the next drag on it paints
    assert len(after) == 15 and max(abs(a - b) for a, b in zip(after[11:], (0.1, 0.2, 0.1, 0.2))) < 0.01, after
    regions, loop_numbers, valid, undo, report = panel["paint_ok"]
    assert len(regions) == 15 and loop_numbers > 40 and valid and undo == ["Edit VarSurf PDE surface"]
    assert "Traceback" not in report, report
    assert Path(painted["shot"]).stat().st_size > 10000


def test_a_loop_drawn_over_the_surface_paints_a_inside_it(panel):
    """The Loop shape: a circular drag of radius 0.15 in (u, v) paints a inside the path it drew
    (PdeLoops: a 6, then its points, every one within 0.01 of the circle), previewed at once."""
    (a, count), off, valid = panel["loop"]
    assert a == 6.0 and count >= 20, panel["loop"]
    assert off < 0.01 and valid
    assert panel["loops_label"] == "1 loops"


def test_a_pin_on_the_surface_drags_by_back_substitution(panel):
    """The pin's drag updates the prepared solve (PointDrag, not a recompute a move), the preview
    passes through the pin, and the release is one undoable step through the target."""
    assert panel["drag_began"] and panel["drag_session"] == "PointDrag", panel
    assert panel["drag_errors"] == []
    assert panel["preview_through_pin"] is not None and panel["preview_through_pin"] < 0.5
    added = panel["report_at_end"][len(panel["report_after_cancel"]):]
    assert "Traceback" not in added, added
    valid, one_step, distance = panel["after_drag"]
    assert valid and one_step and distance < 1e-6
    assert Path(panel["drag_shot"]).stat().st_size > 10000
    print(f"PdeSurface pin drag in the GUI: {panel['drag_moves_per_second']:.0f} moves per second, view redrawn")


def test_a_dynamic_drag_follows_with_inertia_and_settles(panel):
    """DragMode Dynamic and a heavier region around the pin, set in the panel: the pin pulls the
    surface by a spring; it follows the pointer with inertia (still above it when the pointer
    stops going down), at 30 frames a second or more with the view redrawn, settles after the
    release, and the release is one undoable step through the target."""
    assert panel["dynamics_shown"] == ["Static", 1.0, 0.5, 10.0]
    assert panel["material_rows"] == 1
    assert panel["dynamics_stored"] == ["Dynamic", 0.3, [4.0, 0.3, 0.25, 0.75, 0.25, 0.75]]
    assert Path(panel["dynamics_shot"]).stat().st_size > 10000
    assert panel["dynamic_began"] and panel["dynamic_session"] == "DynamicDrag", panel
    assert panel["dynamic_errors"] == []
    assert panel["dynamic_frames_per_second"] >= 30.0, panel["dynamic_frames_per_second"]
    assert panel["dynamic_lag"] is not None and panel["dynamic_lag"] > 0.1
    finished, valid, one_step, distance = panel["after_dynamic"]
    assert finished and valid and one_step and distance < 1e-6
    assert panel["dynamic_settle_seconds"] < 3.5
    added = panel["report_at_end"][len(panel["report_after_cancel"]):]
    assert "Traceback" not in added, added
    print(f"PdeSurface dynamic drag in the GUI: {panel['dynamic_frames_per_second']:.0f} frames per second, "
          f"settled in {panel['dynamic_settle_seconds']:.2f} s")
