# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run from a Python that cannot run VarSurf (no numpy, or another version than the extension was
built for), importing it says exactly that, the same way each time it is tried."""

import subprocess
import sys
from pathlib import Path

from varsurf.solve import environment

SRC = Path(__file__).resolve().parents[2] / "src"

#: numpy made unimportable before VarSurf is imported twice: both attempts print their message.
WITHOUT_NUMPY = f"""
import sys
class NoNumpy:
    def find_spec(self, name, path=None, target=None):
        if name == "numpy" or name.startswith("numpy."):
            raise ImportError("No module named 'numpy'")
sys.meta_path.insert(0, NoNumpy())
sys.path.insert(0, {str(SRC)!r})
for attempt in (1, 2):
    try:
        import varsurf
    except ImportError as error:
        print(attempt, error)
"""


def test_a_python_without_numpy_is_told_so_every_time():
    run = subprocess.run([sys.executable, "-c", WITHOUT_NUMPY], capture_output=True, text=True, timeout=120)
    lines = run.stdout.splitlines()
    assert [line[:2] for line in lines] == ["1 ", "2 "], run.stdout + run.stderr
    for line in lines:
        assert "VarSurf needs numpy" in line and sys.executable in line and "/usr/bin/python3" in line, line
    assert "already registered" not in run.stdout + run.stderr


def test_an_extension_built_for_another_python_is_named(monkeypatch):
    monkeypatch.setattr(environment.importlib.machinery, "EXTENSION_SUFFIXES", [".cpython-399-x86_64-linux-gnu.so"])
    text = environment.native_import_problem(ImportError("No module named 'varsurf._native'"))
    assert "built for another Python" in text and "_native.cpython-" in text and sys.executable in text, text
    assert "tools/build.sh" in text


def test_a_missing_build_says_how_to_build(monkeypatch):
    monkeypatch.setattr(environment.glob, "glob", lambda pattern: [])
    text = environment.native_import_problem(ImportError("No module named 'varsurf._native'"))
    assert text.startswith("the VarSurf native extension (varsurf._native) is not built: run tools/build.sh")


def test_an_extension_that_does_not_load_keeps_the_reason():
    text = environment.native_import_problem(ImportError("initialization failed"))
    assert "does not load in this Python" in text and "initialization failed" in text and sys.executable in text
