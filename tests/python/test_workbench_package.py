# SPDX-License-Identifier: LGPL-2.1-or-later
"""The workbench as a FreeCAD Mod: package metadata, Init files, resources, App/Gui separation."""

import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import FreeCAD

REPO = Path(__file__).resolve().parents[2]
NS = {"p": "https://wiki.freecad.org/Package_Metadata"}


def test_varsurf_is_found_through_the_mod_folder(home):
    import varsurf

    mod = home / ".local" / "share" / "FreeCAD" / "Mod" / "VarSurf"
    # Init.py (run by FreeCAD while scanning Mod folders) put <mod>/src on sys.path
    assert str(mod / "src") in sys.path
    assert Path(varsurf.__file__).resolve() == (REPO / "src" / "varsurf" / "__init__.py").resolve()
    assert varsurf.__version__ == "0.1.0"


def test_app_side_imports_no_gui():
    code = (
        "import sys; sys.path.append('/usr/lib/freecad-python3/lib'); import FreeCAD\n"
        "import importlib, pkgutil, varsurf, varsurf.app, varsurf.solve\n"
        "for tier in (varsurf.solve, varsurf.app):\n"
        "    for info in pkgutil.iter_modules(tier.__path__, tier.__name__ + '.'):\n"
        "        importlib.import_module(info.name)\n"
        "import varsurf.api, varsurf.model, varsurf.analysis  # the names of earlier releases\n"
        "bad = [m for m in sys.modules if m.startswith(('FreeCADGui', 'PySide', 'varsurf.gui'))]\n"
        "print('GUI-MODULES', bad)\n"
        "assert not bad, bad\n"
    )
    run = subprocess.run(
        ["/usr/bin/python3", "-c", code], capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stdout + run.stderr
    assert "GUI-MODULES []" in run.stdout


def test_package_xml():
    root = ET.parse(REPO / "package.xml").getroot()
    assert root.find("p:name", NS).text == "VarSurf"
    assert root.find("p:version", NS).text == "0.1.0"
    assert root.find("p:license", NS).text == "LGPL-2.1-or-later"
    assert root.find("p:description", NS).text.strip()
    wb = root.find("p:content/p:workbench", NS)
    assert wb.find("p:classname", NS).text == "VarSurfWorkbench"
    assert wb.find("p:subdirectory", NS).text == "./"
    assert (REPO / wb.find("p:icon", NS).text).is_file()
    assert root.find("p:freecadmin", NS).text == "0.20"
    assert [d.text for d in root.findall("p:depend", NS)] == ["Part"]


def test_init_files_compile():
    for name in ("Init.py", "InitGui.py"):
        compile((REPO / name).read_text(), name, "exec")
    text = (REPO / "InitGui.py").read_text()
    assert "Gui::PythonWorkbench" in text and "FreeCADGui.addWorkbench(VarSurfWorkbench())" in text


def test_icons_are_64px_svg():
    for name in ("VarSurf.svg", "VarSurf_Sheet.svg"):
        root = ET.parse(REPO / "Resources" / "icons" / name).getroot()
        assert root.tag.endswith("svg")
        assert root.get("width") == "64" and root.get("height") == "64"
        assert root.get("viewBox") == "0 0 64 64"


def test_task_panel_ui_has_the_widgets_the_panel_uses():
    root = ET.parse(REPO / "Resources" / "ui" / "sheet.ui").getroot()
    names = {w.get("name"): w.get("class") for w in root.iter("widget")}
    expected = {
        "stretchSpin": "QDoubleSpinBox",
        "bendSpin": "QDoubleSpinBox",
        "fixBoundaryCheck": "QCheckBox",
        "toleranceEdit": "QLineEdit",
        "updateButton": "QPushButton",
        "deviationTable": "QTableWidget",
        "polesValue": "QLabel",
        "solveTimeValue": "QLabel",
        "rankValue": "QLabel",
        "statusValue": "QLabel",
    }
    for name, kind in expected.items():
        assert names.get(name) == kind, name


def test_gui_sources_compile():
    for path in (REPO / "src" / "varsurf" / "gui").glob("*.py"):
        compile(path.read_text(), str(path), "exec")
    commands = (REPO / "src" / "varsurf" / "gui" / "commands.py").read_text()
    assert "QT_TRANSLATE_NOOP" in commands and "doCommand" in commands


def test_sheet_proxy_state_is_a_small_versioned_dict(doc):
    from varsurf.app.sheet import SheetFeature

    obj = doc.addObject("Part::FeaturePython", "Sheet")
    proxy = SheetFeature(obj)
    assert proxy.dumps() == {"type": "VarSurf::Sheet", "version": 1}
    assert proxy.__getstate__() == proxy.dumps()
    restored = SheetFeature.__new__(SheetFeature)
    restored.__setstate__(proxy.__getstate__())
    assert restored.Type == "VarSurf::Sheet"
    # defaults: a thin plate that keeps the base boundary
    assert obj.Stretch == 0.0 and obj.Bend == 1.0 and obj.FixBoundary is True
    assert abs(float(obj.Tolerance) - 0.01) < 1e-15
    assert obj.MinSpans == 16 and obj.MaxSpans == 64
    for name in ("MaxDeviations", "CurveNames", "PoleCountU", "PoleCountV", "DegreeU",
                 "DegreeV", "SolveTime", "ConstraintRank", "Status"):
        assert obj.getGroupOfProperty(name) == "Result"
        assert "ReadOnly" in obj.getEditorMode(name)
    assert FreeCAD.ActiveDocument is not None
