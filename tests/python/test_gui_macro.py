# SPDX-License-Identifier: LGPL-2.1-or-later
"""A session recorded with FreeCAD's macro recorder replays: tests/gui/macro_gui.py records it in
the real GUI under Xvfb (commands on selections, property edits, a color map) and replays it in a
fresh GUI document; here the same macro is replayed in freecadcmd. Both replays must give the
recorded surfaces (poles to 1e-12 mm) and the same solid."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from gui_run import run_gui_script

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tests" / "gui" / "macro_gui.py"
OUT = REPO / "out" / "gui-macro"

#: Runs after the macro in the same freecadcmd session (freecadcmd runs its file arguments in
#: order, each as FreeCAD runs a macro) and writes what the comparison needs.
DUMP = """
import json, os
import FreeCAD
import varsurf
doc = FreeCAD.getDocument("Recorded")
out = {"sheets": {}, "invalid": sorted(o.Name for o in doc.Objects if not o.isValid())}
for obj in doc.Objects:
    if varsurf.is_sheet(obj) and not obj.Shape.isNull():
        out["sheets"][obj.Name] = [[tuple(p) for p in row] for row in obj.Shape.Faces[0].Surface.getPoles()]
    if getattr(getattr(obj, "Proxy", None), "Type", "") == "VarSurf::Solid":
        out["solid"] = [obj.Name, obj.isValid(), obj.Shape.Volume if not obj.Shape.isNull() else 0.0]
with open(os.environ["VARSURF_REPLAY_OUT"], "w") as handle:
    json.dump(out, handle)
"""


@pytest.fixture(scope="module")
def session(home, native):
    assert shutil.which("freecadcmd"), "freecadcmd is needed for the macro test (tools/setup.sh)"
    result = run_gui_script(SCRIPT, OUT, "macro.json")
    assert result["ok"], result.get("error")
    return result


@pytest.fixture(scope="module")
def headless_replay(session):
    macro = OUT / "varsurf_session.FCMacro"
    dump = OUT / "dump.py"
    dump.write_text(DUMP)
    env = dict(os.environ, VARSURF_REPLAY_OUT=str(OUT / "headless.json"))
    run = subprocess.run(["freecadcmd", str(macro), str(dump)], cwd=OUT, env=env, capture_output=True,
                         text=True, timeout=300)
    (OUT / "freecadcmd.log").write_text(run.stdout + "\n--- stderr ---\n" + run.stderr)
    assert (OUT / "headless.json").is_file(), \
        f"freecadcmd (exit {run.returncode}):\n{run.stdout[-3000:]}\n{run.stderr[-3000:]}"
    return json.loads((OUT / "headless.json").read_text())


def _pole_gap(a, b):
    assert sorted(a) == sorted(b)
    gap = 0.0
    for name in a:
        rows_a, rows_b = a[name], b[name]
        assert [len(r) for r in rows_a] == [len(r) for r in rows_b], name
        for ra, rb in zip(rows_a, rows_b):
            for p, q in zip(ra, rb):
                gap = max(gap, max(abs(x - y) for x, y in zip(p, q)))
    return gap


def test_macro_has_the_session_as_lines_that_run_without_the_gui(session):
    """Imports by full module path (the module the commands are registered from imports
    headless), document lines for every command, view lines only as comments."""
    lines = session["macro"].splitlines()
    imports = [line for line in lines if line.startswith("import ")]
    assert "import commands" not in imports and "import VarSurfGui" in imports, imports
    body = "\n".join(lines)
    assert body.count("varsurf.make_sheet(") == 2
    assert "varsurf.make_constraint(" in body and "varsurf.make_solid(" in body
    view_lines = [line for line in lines if "ViewObject" in line]
    assert view_lines and all(line.startswith("#") for line in view_lines), view_lines
    assert session["analysis_recorded"] == "Deviation"
    # each command was one undoable step
    assert session["undo_names"][:2] == ["Add VarSurf solid", "Add VarSurf constraint"], session["undo_names"]


def test_gui_replay_gives_the_recorded_surfaces(session):
    recorded, replayed = session["recorded"], session["replayed"]
    assert len(recorded["sheets"]) == 2 and not recorded["invalid"], recorded["invalid"]
    assert not replayed["invalid"], replayed["invalid"]
    assert _pole_gap(recorded["sheets"], replayed["sheets"]) <= 1e-12
    name, valid, volume = replayed["solid"]
    assert valid and volume > 1000.0
    assert abs(volume - recorded["solid"][2]) <= 1e-9 * recorded["solid"][2]
    assert session["replayed_view_provider"] == "ViewProviderSheet"


def test_freecadcmd_replay_gives_the_recorded_surfaces(session, headless_replay):
    recorded = session["recorded"]
    assert not headless_replay["invalid"], headless_replay["invalid"]
    assert _pole_gap(recorded["sheets"], headless_replay["sheets"]) <= 1e-12
    assert headless_replay["solid"][1]
    assert abs(headless_replay["solid"][2] - recorded["solid"][2]) <= 1e-9 * recorded["solid"][2]
