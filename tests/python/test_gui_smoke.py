# SPDX-License-Identifier: LGPL-2.1-or-later
"""Runs tests/gui/smoke_gui.py in the real FreeCAD GUI under Xvfb and checks its JSON report."""

from pathlib import Path

import pytest

from gui_run import run_gui_script

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tests" / "gui" / "smoke_gui.py"
OUT = REPO / "out" / "gui-smoke"  # kept after the run: smoke.png is worth a look


@pytest.fixture(scope="module")
def smoke(home, native):
    return run_gui_script(SCRIPT, OUT, "smoke.json")


def test_gui_run_completed(smoke):
    assert smoke["ok"], smoke.get("error")


#: The errors the smoke run provokes on purpose, each the message of one object in error: a Sheet
#: whose Bend is set to 0 (no energy left), the Sheet panel's spans changed under an installed
#: rest shape, a Ribbon command on a rail 5 mm above the face it references, a constraint command
#: whose default asks what the rail forbids, and the Hinge panel's 150 and 90 degrees against side
#: curves opening at 180.
PROVOKED = (
    "Stretch and Bend are both 0",
    "the installed rest shape does not match the sheet's spline space",
    "ribbon: the curve passes 5 mm from its reference face",
    "the curves and constraints cannot all be met",
    "from a join curve (more than the tolerance 0.002 mm) (with hinges Hinge",
)


def _failures(lines):
    """The line before each of FreeCAD's 'Recompute failed!': what failed (an object in error
    reports one line; several in one recompute, one each, the last just before it)."""
    return [lines[k - 1] if k else "" for k, line in enumerate(lines) if "Recompute failed" in line]


def test_report_view_shows_only_the_provoked_errors(smoke):
    """One line per failure, 'VarSurf: <object>: <what is wrong, what to do>': no traceback, no
    exception class, and each is one of the errors the run provokes on purpose."""
    lines = smoke["report_view_at_end"]
    assert not [line for line in lines if "Traceback" in line or line.startswith(("<class ", "File "))], lines
    failures = _failures(lines)
    assert failures and all(" VarSurf: HingePair: " in line or " VarSurf: Sheet: " in line for line in failures), lines
    unexpected = [line for line in failures if not any(p in line for p in PROVOKED)]
    assert not unexpected, unexpected
    assert any(PROVOKED[-1] in line for line in failures), failures


def test_an_error_shows_on_the_sheet_and_in_a_window_picture(smoke):
    """The error case the README shows: the Sheet in error with what is wrong and what to do, a
    full main-window picture of it, and the sheet back to OK once repaired."""
    assert smoke["error_valid"] is False
    assert smoke["error_status"].startswith("Error:") and "give Bend" in smoke["error_status"], smoke["error_status"]
    assert Path(smoke["error_window"]).is_file()
    assert smoke["repaired_status"].startswith("OK"), smoke["repaired_status"]


def test_workbench_and_command(smoke):
    assert smoke["workbench"] == "VarSurfWorkbench"
    assert smoke["command_registered"]


def test_bad_selection_creates_nothing(smoke):
    assert smoke["active_with_edges_only"] is False
    assert smoke["created_on_bad_selection"] == 0


def test_command_creates_a_valid_sheet(smoke):
    assert smoke["active_with_face_and_edges"] is True
    assert smoke["selection"] == [["Surface", ["Face1"]], ["Rail", ["Edge1"]], ["Side", ["Edge1"]]]
    assert smoke["sheets"] == 1
    assert smoke["sheet_valid"], smoke.get("sheet_state")
    assert smoke["curve_names"] == ["Rail:Edge1", "Side:Edge1"]
    # Met within the sheet's tolerance (0.01 mm for this 100 mm scene): the solve fits the curves
    # only that far and leaves the rest to fairness.
    assert 0.0 < smoke["tolerance"] <= 0.01
    assert max(smoke["max_deviations"]) <= smoke["tolerance"]
    assert smoke["base_hidden"]
    assert smoke["children"] == ["Surface", "Rail", "Side"]
    assert smoke["icon"].endswith("VarSurf_Sheet.svg") and Path(smoke["icon"]).is_file()
    assert "Create VarSurf sheet" in smoke["undo_names"]  # one transaction, undoable


def test_task_panel_previews_and_cancel_restores(smoke):
    assert smoke["task_panel_open"]
    assert smoke["task_panel_rows"] == 2
    valid, joins, join_rows = smoke["g0_panel"]  # the G0 command's join, measured, in the Sheet's panel
    assert valid and len(joins) == 1 and len(join_rows) == 1, smoke["g0_panel"]
    assert join_rows[0][0] == f"{joins[0]}: join" and join_rows[0][1].startswith("gap "), join_rows
    assert smoke["bend_during_edit"] == 5.0
    assert smoke["bend_restored"], (smoke["bend_during_edit"], smoke["bend_after_cancel"])
    assert smoke["task_panel_closed"]


def test_screenshot_is_not_blank(smoke):
    stats = smoke["image_stats"]
    assert (stats["width"], stats["height"]) == (800, 600)
    assert stats["variance"] > 50.0, stats
    assert stats["non_white"] > 0.03, stats
    assert smoke["saved"]


def test_constraint_commands_work_in_the_gui(smoke):
    from varsurf.solve import constraints

    assert len(smoke["constraint_commands"]) == len(constraints.KINDS), smoke["constraint_commands"]
    assert smoke["normal_active"]
    assert smoke["constraint_kinds"] == ["Normal"]
    assert smoke["sheet_valid_with_constraint"]
    assert smoke["constraint_residuals"][0] < 1e-6  # degrees
    assert smoke["constraint_in_tree"]
    assert smoke["constraint_icon"].endswith("VarSurf_Normal.svg")  # the kind's own icon
    # The Solid command joins two selected Sheets; the Solid shows them as its children.
    assert smoke["solid_active"]
    assert smoke["solids"] == 1
    assert smoke["solid_closed"]
    assert smoke["solid_icon"].endswith("VarSurf_Solid.svg")
    assert smoke["solid_children"] == ["Top", "Bottom"]
    assert smoke["sheets_hidden"]
    assert smoke["solid_image_stats"]["variance"] > 50.0, smoke["solid_image_stats"]
    assert smoke["hinge_active"] and len(smoke["hinges"]) == 1
    assert smoke["hinge_errors"] and smoke["hinge_errors"][0] <= 0.05, smoke["hinge_errors"]
    assert smoke["hinge_icon"].endswith("VarSurf_Hinge.svg")
    assert smoke["space_curve_active"] and smoke["space_curve_ok"]
    assert smoke["space_curve_icon"].endswith("VarSurf_SpaceCurve.svg")
    assert smoke["pde_active"], smoke
    assert smoke["pde_ok"] == [True, "Hermite", ["Add VarSurf PDE surface"]], smoke["pde_ok"]
    assert smoke["pde_icon"].endswith("VarSurf_PdeSurface.svg")
    assert smoke["hinge_image_stats"]["variance"] > 50.0, smoke["hinge_image_stats"]


def test_dragging_a_pin_solves_live_and_undoes_in_one_step(smoke):
    assert smoke["pin_has_dragger"] and smoke["drag_began"], smoke.get("drag_errors")
    assert smoke["drag_errors"] == []
    # the drawn surface followed the pin (the Sheet's Shape waits for the release) and the view
    # changed; the grid passes within a grid cell of the pin
    assert smoke["preview_top"] > smoke["sheet_top_before"] + 5.0, (smoke["preview_top"], smoke["sheet_top_before"])
    assert smoke["preview_through_pin"] < 5.0
    assert smoke["drag_image_change"] > 0.005, smoke["drag_image_change"]
    assert smoke["drag_image_stats"]["non_white"] > 0.03
    # released: the target written, the sheet recomputed; one undo step puts both back
    # (through the dragger's single-precision field)
    assert all(abs(a - b) < 1e-4 for a, b in zip(smoke["pin_origin_after"], smoke["drag_target"]))
    assert smoke["sheet_valid_after_drag"]
    assert smoke["undo_after_drag"] == ["Drag VarSurf point"]
    assert all(abs(a - b) < 1e-9 for a, b in zip(smoke["pin_origin_after_undo"], smoke["pin_start"]))
    assert abs(smoke["area_after_undo"] - smoke["area_before_drag"]) < 1e-6 * smoke["area_before_drag"]


def test_color_maps_and_the_l_curve(smoke):
    assert smoke["color_map_active"]
    maps = smoke["color_maps"]
    assert [maps[m]["mode"] for m in maps] == ["Deviation", "CurveDeviation", "MeanCurvature",
                                               "GaussianCurvature", "Zebra"]
    assert maps["CurveDeviation"]["curves"] == 2 and maps["CurveDeviation"]["range"].startswith("0 …")
    for mode, shown in maps.items():
        if mode != "CurveDeviation":
            assert shown["cells"] == 2 * 48 * 48, mode
        # the sheet is colored (CurveDeviation: only its two curves are)
        assert shown["change"] > (0.001 if mode == "CurveDeviation" else 0.02), (mode, shown["change"])
        if mode == "Zebra":  # stripes: their count and direction, and no legend
            assert shown["range"] == "12 stripes from (0, 0, 1)" and not shown["legend"], shown
            continue
        assert "…" in shown["range"], (mode, shown["range"])
        # a legend: five values from the range's low end to its high end, then what and which unit
        lo, hi = (float(x) for x in shown["range"].split()[0:3:2])
        labels, title = shown["legend"][:5], shown["legend"][5]
        expected = [lo + (hi - lo) * k / 4 for k in range(5)]
        assert [float(x) for x in labels] == pytest.approx(expected, rel=1e-3, abs=1e-12)
        assert title.endswith("(" + shown["range"].split()[-1] + ")"), (title, shown["range"])
    assert maps["Deviation"]["range"].endswith("mm") and maps["Deviation"]["legend"][2] == "0"
    # Crisp zebra: of the non-white pixels nearly all are black (stripes' and lines' edges aside);
    # the colored maps, for contrast, are mostly mid-tones.
    assert maps["Zebra"]["tones"] < 0.15, maps["Zebra"]["tones"]
    assert maps["Deviation"]["tones"] > 0.5
    stripes, count, change = smoke["zebra_adjusted"]
    assert stripes == "4 stripes from (1, 0, 0)" and count == 4 and change > 0.02, smoke["zebra_adjusted"]
    shown, legend = smoke["scaled_legend"]
    assert shown == "-20 … 20 mm", shown
    assert legend == ["-20", "-10", "0", "10", "20", "Deviation (mm)"], legend
    for name in ("window_deviation.png", "window_zebra.png"):
        assert (OUT / name).is_file(), name
    assert smoke["overlay_cleared"]
    assert smoke["lcurve_active"]
    stats = smoke["lcurve_image_stats"]
    assert (stats["width"], stats["height"]) == (600, 450) and stats["variance"] > 50.0


def test_preferences_page_binds_the_defaults(smoke):
    assert smoke["preference_entries"] == {"degreeSpin": "Degree", "minSpansSpin": "MinSpans", "bendSpin": "Bend",
                                           "toleranceSpin": "Tolerance", "solveModeCombo": "SolveMode",
                                           "timeLimitSpin": "SolveTimeLimit", "memoryLimitSpin": "SolveMemoryLimit"}
    from varsurf.app import preferences

    assert {"SolveTimeLimit", "SolveMemoryLimit"} <= set(preferences._ENTRIES)  # read back by the solve
    from varsurf.solve import settings

    assert smoke["preference_modes"] == list(settings.SOLVE_MODES)  # the stored index means a mode
    # Until a value is typed the page shows (and, on OK, stores) Automatic: a new sheet's
    # tolerance then still follows the model's size.
    assert smoke["preference_tolerance"] == [0.0, "Automatic (model size)"], smoke["preference_tolerance"]


def test_sheet_panel_edits_space_mode_and_rest_shape(smoke):
    rows = smoke["panel_rows_with_constraints"]
    assert rows[:2] == ["Rail:Edge1", "Side:Edge1"] and len(rows) == 4  # two curves, Normal and Pin
    assert smoke["rest_during_edit"] == "Installed"
    assert smoke["rest_after_cancel"] == "Base" and not smoke["installed_after_cancel"]
    assert smoke["panel_ok"] == [4, 4, "Exact", True, ["Edit VarSurf sheet"]]
    refinement, poles_text = smoke["panel_local"]
    assert refinement == "Local" and "local:" in poles_text and "poles solved" in poles_text, poles_text


def test_constraint_and_hinge_panels(smoke):
    # a Point: placed by (u, v) and its Origin; no region, no angle
    assert smoke["pin_panel_fields"] == {"uSpin": True, "originZ": True, "regionU0Spin": False, "angleSpin": False}
    assert smoke["pin_panel_residual"].endswith("mm"), smoke["pin_panel_residual"]
    assert abs(smoke["pin_panel_preview"][0] - 3.0) < 1e-4 and smoke["pin_panel_preview"][1]  # 4 decimals shown
    assert smoke["pin_panel_restored"]
    assert smoke["pin_panel_ok"] == [2.0, True, True, ["Edit VarSurf constraint"]]  # OK: weight only
    assert "…" in smoke["hinge_panel_reached"] and "180" in smoke["hinge_panel_reached"]
    assert smoke["hinge_preview_angle"] == 90.0 and smoke["hinge_after_cancel"] == [180.0, True]
    angle, valid, status, undo = smoke["hinge_panel_ok"]
    assert angle == 150.0 and undo == ["Edit VarSurf hinge"]
    assert not valid and "with hinges" in status, status  # contradicts the pair's side curves
    assert smoke["hinge_after_undo"] == [180.0, True]


def test_dragging_a_space_curve_handle_moves_the_solid(smoke):
    assert smoke["curve_pins"][0] == smoke["curve_pins"][1] >= 3
    assert smoke["curve_drag_began"] and smoke["curve_drag_errors"] == []
    assert smoke["curve_live_solves"] >= 2  # the box follows while the handle moves, not only at the end
    assert smoke["curve_image_change"] > 0.003, smoke["curve_image_change"]
    valid, closed, gained = smoke["curve_solid"]
    assert valid and closed and gained > 1000.0, smoke["curve_solid"]
    assert smoke["curve_undo_name"] == ["Drag VarSurf handle"]
    assert smoke["curve_volume_after_undo"] < 1e-6


def test_progress_indicator_shows_during_a_solve(smoke):
    assert smoke["progress_shown"] > 0 and smoke["sheet_valid_with_progress"]


def test_every_constraint_command_on_a_prepared_selection(smoke):
    from varsurf.solve import constraints

    outcome = smoke["every_constraint_command"]
    assert sorted(outcome) == sorted(constraints.KINDS)
    # each command's constraint was undone again: the Sheet has the constraints it had before
    assert smoke["constraints_after_undos"] == smoke["constraints_before_every_command"], (
        smoke["constraints_before_every_command"], smoke["constraints_after_undos"])
    icons = smoke["constraint_icons"]
    assert len(set(icons.values())) == len(constraints.KINDS), icons  # one icon per kind
    assert all(Path(p).is_file() for p in icons.values()), icons
    for kind, (active, added, undo) in outcome.items():
        assert active, kind
        assert added == [kind], (kind, added)
        assert undo == ["Add VarSurf constraint"] or undo and "constraint" in undo[0].lower(), (kind, undo)


def test_solid_panel_lists_its_joins(smoke):
    assert smoke["solid_panel_seams"] == ["Rim:Edge1"], smoke["solid_panel_seams"]  # the pillow's rim
    assert abs(smoke["solid_panel_preview"] - 2.0) < 1e-6 and smoke["solid_panel_restored"]


def test_dragging_an_attractor_origin(smoke):
    began, z, rise, undo, errors = smoke["origin_drag"]
    assert began and errors == [] and abs(z - 32.0) < 1e-3  # (single-precision dragger field)
    assert rise > 1.0 and undo == ["Drag VarSurf origin"]


def test_rest_shape_commands(smoke):
    rest = smoke["rest_commands"]
    assert rest["VarSurf_InstallRest"] == [True, "Installed", ["VarSurf install rest shape"], True]
    assert rest["VarSurf_Melt"] == [True, "None", ["VarSurf melt"], True]


def test_refined_spans_are_outlined(smoke):
    valid, depth, drawn, spans, change = smoke["refinement_view"]
    assert valid and depth >= 1 and drawn == spans > 0
    assert change > 0.002, change


def test_fill_hole_panel_lists_its_joins(smoke):
    """The crowned lid's FillHole: its own icon with the box as its child, its panel's four rows
    (the top's edges, G0: no angle), a tolerance previewed and cancelled, a picture of it."""
    assert smoke["fill_hole_icon"].endswith("VarSurf_FillHole.svg"), smoke["fill_hole_icon"]
    assert smoke["fill_hole_children"] == ["Box"], smoke["fill_hole_children"]
    rows = smoke["fill_hole_panel_rows"]
    assert [r[0] for r in rows] == [f"hole edge {k}" for k in range(1, 5)], rows
    assert all(float(r[1]) <= 0.001 and r[2] == "—" for r in rows), rows
    assert smoke["fill_hole_panel_continuity"] == "G0"
    assert smoke["fill_hole_panel_preview"] == [2.0, True] and smoke["fill_hole_panel_restored"]
    assert smoke["fill_hole_image_stats"]["variance"] > 50.0, smoke["fill_hole_image_stats"]  # the lid is drawn


def test_tube_command_through_a_sketch_and_a_circle(smoke):
    """The duct's sections picked in the GUI: inactive with one section, active with two; the
    tube is valid on a TubeSkin and drawn."""
    assert not smoke["tube_active_one_section"] and smoke["tube_active"]
    assert len(smoke["tube"]) == 1 and smoke["tube"][0][1], smoke["tube"]
    assert smoke["tube_base"] == "VarSurf::TubeSkin"
    assert smoke["tube_image_stats"]["variance"] > 50.0, smoke["tube_image_stats"]


def test_a_document_built_without_the_gui_opens_with_its_view_providers(smoke):
    """Built by a script without the GUI (as freecadcmd, a macro or a test does) and opened in the
    GUI: every VarSurf object has its view provider (its icon; double click opens the Sheet panel,
    not FreeCAD's Transform), what a sheet or solid replaces is hidden and nothing else is. A
    document saved with the GUI opens with one of each overlay (no second one from the restore)."""
    code, errors = smoke["headless_build"]
    assert code == 0, errors
    providers = smoke["headless_view_providers"]
    assert providers == {"Top": "ViewProviderSheet", "Bottom": "ViewProviderSheet", "Lid": "ViewProviderSheet",
                         "Pillow": "ViewProviderSolid", "Pde": "ViewProviderPdeSurface"}, providers
    assert all(icon.startswith("VarSurf") and icon.endswith(".svg") for icon in smoke["headless_icons"].values())
    visible = smoke["headless_visible"]
    hidden = [name for name in ("TopBase", "BottomBase", "Top", "Bottom") if visible[name]]
    assert not hidden, visible  # flat helper faces the sheets replace, sheets the solid shows
    shown = [name for name in ("Pillow", "Rim", "Lid", "Box", "Arc") if not visible[name]]
    assert not shown, visible  # a sheet on a Part Box's face leaves the box shown, as Surface Filling does
    assert smoke["headless_panel"] == ["bendSpin", "deviationTable"], smoke["headless_panel"]
    assert smoke["reopened_proxies"] == ["ViewProviderSheet"], smoke["reopened_proxies"]
    roots = smoke["reopened_overlay_roots"]
    assert roots and set(roots) == {1}, roots


def test_the_sheet_panel_fits_freecads_default_task_view(smoke):
    """At FreeCAD's default window layout no field of the Sheet panel is cut off at the task
    view's right edge (long rows put the field under its label)."""
    assert smoke["task_panel_clipped"] == [], smoke["task_panel_clipped"]


def test_a_greyed_out_command_says_why(smoke):
    """One Sheet selected: Join sheets into a solid is greyed out, and its tooltip and status tip
    say what is missing."""
    assert not smoke["solid_active_one_sheet"]
    tip, status = smoke["solid_tip_one_sheet"]
    assert "Not available now:" in tip and "two or more Sheets, and only Sheet is selected" in tip, tip
    assert status.startswith("Not available now: A Solid joins two or more Sheets"), status


def test_toolbars_fit_1600_px_with_one_button_per_constraint_family(smoke):
    """No toolbar shows its overflow arrow in a 1600 px window; the constraint kinds are grouped
    into drop-down buttons (each family's members in its menu), every kind in exactly one."""
    assert smoke["toolbar_window_width"] == 1600
    assert smoke["toolbars_overflowing"] == [], smoke["toolbars_overflowing"]
    groups = smoke["constraint_groups"]
    assert smoke["constraint_toolbar_items"] == ["VarSurf_PointConstraints", "VarSurf_CurveJoins", "VarSurf_Operators"]
    assert [len(g) for g in smoke["constraint_toolbar_buttons"]] == [len(g) for g in groups]
    members = [name for group in groups for name in group]
    assert sorted(members) == sorted(smoke["constraint_commands"]) and len(set(members)) == len(members)


def test_the_sheet_panel_shows_its_results_without_scrolling(smoke):
    """At FreeCAD's default layout (1280 x 1024, the combo view's task tab) the results (poles,
    status, the curves' deviations) are in view as the panel opens: they come first."""
    assert smoke["task_panel_results_unseen"] == [], smoke["task_panel_results_unseen"]


def test_the_deviation_table_shows_every_value_whole(smoke):
    """Every deviation in the Sheet panel's table is readable whole, unit included, at FreeCAD's
    default task view width; a name too long for its column gives way and is whole in its tooltip.
    The Solid's seams and the FillHole's joins (four columns) likewise."""
    assert smoke["deviation_cells_cut"] == [], smoke["deviation_cells_cut"]
    assert smoke["solid_cells_cut"] == [], smoke["solid_cells_cut"]
    assert smoke["fill_hole_cells_cut"] == [], smoke["fill_hole_cells_cut"]
    assert smoke["fill_hole_g2_cells_cut"] == [], smoke["fill_hole_g2_cells_cut"]


def test_the_preferences_page_has_its_icon(smoke):
    assert "VarSurf" in smoke["preference_groups"], smoke["preference_groups"]
    log = (OUT / "freecad.log").read_text()
    assert "Cannot find icon" not in log, [line for line in log.splitlines() if "Cannot find icon" in line]


def test_each_constraint_icon_is_recognisable_at_toolbar_size_and_greys_out(smoke):
    """At the toolbars' icon size every kind's icon covers a fair part of its square, no two kinds'
    icons are near alike (G1 and G2 differed by 1.5 % before they carried their order, 2.4 % since), and the
    disabled icon is grey while the enabled one has colour. constraint_icons.png shows them."""
    assert smoke["icon_size"] >= 16, smoke["icon_size"]
    thin = {k: c for k, c in smoke["icon_coverage"].items() if c < 0.2}
    assert not thin, thin
    difference, a, b = smoke["icon_closest_pair"]
    assert difference >= 0.02, (a, b, difference)
    for kind, (normal, disabled) in smoke["icon_saturation"].items():
        assert normal > 0.3 and disabled < 0.05, (kind, normal, disabled)


def test_property_names_are_not_cut_off_at_the_default_panel_width(smoke):
    """With a Sheet selected, the Combo view's property editor (FreeCAD's default width) shows
    every name whole: its name column is widened to them, no further than the values allow."""
    width, name_column, columns = smoke["property_editor"][0]
    assert smoke["property_names_shown"] >= 40, smoke["property_names_shown"]
    assert smoke["property_names_cut"] == [], smoke["property_names_cut"]
    assert name_column <= 0.7 * width, (name_column, width)
    assert columns <= width, (columns, width)  # the values fill the rest: no horizontal scroll bar
