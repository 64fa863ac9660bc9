# SPDX-License-Identifier: LGPL-2.1-or-later
"""Runs a script of tests/gui in the real FreeCAD GUI under Xvfb (at FreeCAD's default 1280 x 1024)
and reads the JSON it writes."""

import json
import os
import shutil
import subprocess


def run_gui_script(script, out, result_name):
    """Run ``script`` in a fresh FreeCAD GUI with ``out`` as its output folder (emptied first);
    FreeCAD's output goes to out/freecad.log. Returns the parsed out/result_name."""
    for tool in ("xvfb-run", "freecad"):
        assert shutil.which(tool), f"{tool} is needed for the GUI tests (tools/setup.sh)"
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    env = dict(os.environ)  # HOME is the temporary one with the Mod symlink (conftest)
    env.update(VARSURF_GUI_OUT=str(out), VARSURF_NO_DIALOGS="1", QTWEBENGINE_CHROMIUM_FLAGS="--no-sandbox")
    env.pop("QT_QPA_PLATFORM", None)  # offscreen aborts FreeCAD; Xvfb is the display
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad", str(script)]
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300, cwd=out)
    (out / "freecad.log").write_text(run.stdout + "\n--- stderr ---\n" + run.stderr)
    result_file = out / result_name
    assert result_file.is_file(), \
        f"no {result_name} (exit {run.returncode}):\n{run.stdout[-3000:]}\n{run.stderr[-3000:]}"
    return json.loads(result_file.read_text())
