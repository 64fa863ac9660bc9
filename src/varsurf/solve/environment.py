# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the Python running VarSurf must have, said exactly when it lacks it: numpy, and a build of
the native extension for this Python's version (FreeCAD's own Python, /usr/bin/python3 on
Debian, is the one tools/build.sh builds for)."""

from __future__ import annotations

import glob
import importlib.machinery
import os
import sys

_THIS_PYTHON = f"this Python ({sys.executable or 'embedded'}, {sys.version.split()[0]})"
_USE = ("Run VarSurf in FreeCAD or with the Python FreeCAD uses (Debian: /usr/bin/python3, which "
        "tools/setup.sh gives python3-numpy)")


def require_numpy():
    """ImportError naming this Python when it has no numpy."""
    try:
        import numpy  # noqa: F401
    except ImportError as error:
        raise ImportError(f"VarSurf needs numpy, which {_THIS_PYTHON} does not have ({error}). {_USE}, or "
                          "install numpy for this Python.") from None


def native_import_problem(error: BaseException) -> str:
    """Why ``varsurf._native`` did not import, in words a user can act on."""
    folder = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    built = sorted(os.path.basename(p) for p in glob.glob(os.path.join(folder, "_native*.so")))
    if not built:
        return "the VarSurf native extension (varsurf._native) is not built: run tools/build.sh in the VarSurf folder"
    suffixes = importlib.machinery.EXTENSION_SUFFIXES
    if not any(name.endswith(tuple(suffixes)) for name in built):
        return (f"the VarSurf native extension is built for another Python ({', '.join(built)}), not for "
                f"{_THIS_PYTHON}. {_USE}, or rebuild with tools/build.sh for this Python")
    return f"the VarSurf native extension ({', '.join(built)}) does not load in {_THIS_PYTHON}: {error}"
