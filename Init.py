# SPDX-License-Identifier: LGPL-2.1-or-later
# VarSurf workbench: application (headless) initialization.
#
# FreeCAD runs this file with exec() while it scans its Mod folders, so __file__ is not set (0.20).
# FreeCAD has put this Mod folder on sys.path; find it there and make the `varsurf` package, which
# lives in <mod folder>/src, importable.

import os
import sys


def _varsurf_mod_folder():
    for entry in list(sys.path):
        if not isinstance(entry, str) or not entry:
            continue
        if os.path.isfile(os.path.join(entry, "package.xml")) and os.path.isfile(
            os.path.join(entry, "src", "varsurf", "__init__.py")
        ):
            return os.path.normpath(entry)
    return None


_folder = _varsurf_mod_folder()
if _folder is not None:
    _src = os.path.join(_folder, "src")
    if _src not in sys.path:
        sys.path.append(_src)
del _folder
