# SPDX-License-Identifier: LGPL-2.1-or-later
"""The check every STEP file written in the tests passes: FreeCAD reads it back as a shape that
passes OpenCASCADE's full check (BRepCheck and the Boolean operations' checks, ``check(True)``)
with the faces, area and solids' volume it was written with (relative 1e-6).

Area and volume are integrated adaptively on both sides (``mass_properties``, relative precision
1e-9): FreeCAD's Shape.Area / Volume use a fixed rule good to only a few 1e-6 on trimmed B-spline
faces (the pillow: 7279.115 by the rule, 7279.145 integrated), and its error changes with how a
boundary is split into edges, which the export may do.
"""

from pathlib import Path

import Part
import pytest

RELATIVE = 1e-6


def assert_reads_back(shape, path, native):
    """Read the STEP file at `path`, written from `shape`; return the re-read shape."""
    shape.check(True)  # the written shape itself is sound (raises with the faults otherwise)
    back = Part.read(str(path))
    try:
        back.check(True)
    except Exception as fault:  # FreeCAD raises with the list of BOPAlgo faults
        pytest.fail(f"{Path(path).name} read back fails OpenCASCADE's check: {fault}")
    assert len(back.Faces) == len(shape.Faces)
    area, _ = native.mass_properties(shape.exportBrepToString())
    back_area, _ = native.mass_properties(back.exportBrepToString())
    assert back_area == pytest.approx(area, rel=RELATIVE)
    assert len(back.Solids) == len(shape.Solids)
    if shape.Solids:  # volume: of the solids only (an open sheet encloses none)
        _, volume = native.mass_properties(Part.makeCompound(shape.Solids).exportBrepToString())
        _, back_volume = native.mass_properties(Part.makeCompound(back.Solids).exportBrepToString())
        assert volume > 0 and back_volume == pytest.approx(volume, rel=RELATIVE)
    return back
