# SPDX-License-Identifier: LGPL-2.1-or-later
"""Makes FreeCAD and VarSurf importable from Debian's python3 for the examples: FreeCAD's
Python modules live outside the interpreter's path, VarSurf in this repository's src/.
Import it before FreeCAD."""

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
FREECAD_LIB = "/usr/lib/freecad-python3/lib"
if FREECAD_LIB not in sys.path:
    sys.path.append(FREECAD_LIB)
if str(REPO / "src") not in sys.path:
    sys.path.insert(0, str(REPO / "src"))


def write_outputs(doc, obj, out_dir, stem):
    """Save the document and export ``obj`` to STEP into out_dir; returns the two paths."""
    import varsurf

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    fcstd, step = out / f"{stem}.FCStd", out / f"{stem}.step"
    doc.saveAs(str(fcstd))
    varsurf.export_step([obj], str(step))
    return fcstd, step
