# SPDX-License-Identifier: LGPL-2.1-or-later
"""FreeCAD in-process for the workbench tests.

The workbench is installed the way a user installs it: a temporary HOME whose
~/.local/share/FreeCAD/Mod/VarSurf is a symlink to this repository. HOME must be set before the
first `import FreeCAD`, which scans the Mod folders and runs our Init.py (that puts src/ on
sys.path). Subprocesses (fresh FreeCAD sessions, the GUI smoke test) inherit the same HOME.
"""

import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
FREECAD_LIB = "/usr/lib/freecad-python3/lib"

_HOME = Path(tempfile.mkdtemp(prefix="varsurf-home-"))
_MOD = _HOME / ".local" / "share" / "FreeCAD" / "Mod"
_MOD.mkdir(parents=True)
(_MOD / "VarSurf").symlink_to(REPO, target_is_directory=True)
os.environ["HOME"] = str(_HOME)
for _var in ("XDG_DATA_HOME", "XDG_CONFIG_HOME", "XDG_CACHE_HOME"):
    os.environ.pop(_var, None)
os.environ["VARSURF_NO_DIALOGS"] = "1"
if FREECAD_LIB not in sys.path:
    sys.path.append(FREECAD_LIB)

import FreeCAD  # noqa: E402  (after HOME)

sys.path.insert(0, str(Path(__file__).resolve().parent))
# The examples are scenes the tests build too.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples"))


def pytest_sessionfinish(session, exitstatus):
    shutil.rmtree(_HOME, ignore_errors=True)


@pytest.fixture(scope="session")
def home():
    return _HOME


@pytest.fixture(scope="session")
def native():
    """The compiled extension; the tests that need it fail loudly without a build."""
    from varsurf.solve.native import native

    return native()


@pytest.fixture
def doc():
    document = FreeCAD.newDocument("VarSurfTest")
    document.UndoMode = 1
    name = document.Name
    yield document
    if name in FreeCAD.listDocuments():
        unadvised = _unadvised_errors(FreeCAD.getDocument(name))  # the test may have reopened it
        FreeCAD.closeDocument(name)
        assert not unadvised, f"objects in error whose message does not say what to do: {unadvised}"


def _unadvised_errors(document):
    """Every VarSurf object a test leaves in error: its message says what to do (a clause that
    starts with a remedy verb), whatever the test provoked."""
    from varsurf.solve import errors

    found = []
    for obj in document.Objects:
        if not type(getattr(obj, "Proxy", None)).__module__.startswith("varsurf.") or obj.isValid():
            continue
        message = obj.getStatusString()  # VarSurf's own: "<Label>: <what is wrong, what to do>"
        if message.startswith(f"{obj.Label}: ") and not errors.says_what_to_do(message):
            found.append(f"{obj.Label}: {message}")
    return found


@pytest.fixture
def console_errors(capfd):
    """Route FreeCAD.Console errors/warnings to stderr (off by default headless) and read them."""
    previous = {kind: FreeCAD.Console.GetStatus("Console", kind) for kind in ("Err", "Wrn")}
    for kind in previous:
        FreeCAD.Console.SetStatus("Console", kind, True)

    def read():
        return capfd.readouterr().err

    capfd.readouterr()
    yield read
    for kind, value in previous.items():
        FreeCAD.Console.SetStatus("Console", kind, bool(value))
