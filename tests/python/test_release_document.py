# SPDX-License-Identifier: LGPL-2.1-or-later
"""A document saved by release 0.1.0, before the package had one folder per tier: it opens with
every object's proxy restored, recomputes to the geometry it was saved with, and saves and opens
again.

"The same geometry": the same status, faces and edges, and poles within 1e-12 mm, or within 1 % of
the object's Tolerance where it has one. The penalty solve of the two sheets made from curves
alone is conditioned so that the processor's rounding (OpenBLAS picks its kernels by processor)
moves their poles by 4.2e-6 mm of a 1e-3 mm tolerance between machines; a base face's sheet
agrees to 3e-18 mm."""

from pathlib import Path

import FreeCAD

from test_persistence_and_sessions import geometry, max_gap, varsurf_objects

RELEASE_DOCUMENT = Path(__file__).resolve().parents[1] / "data" / "release-0.1.0.FCStd"
#: What the file holds (its proxies' module paths are the old release's own).
TYPES = {"VarSurf::Sheet": 3, "VarSurf::Solid": 1, "VarSurf::Hinge": 1, "VarSurf::Constraint": 3,
         "VarSurf::SpaceCurve": 1}


def _open(path):
    doc = FreeCAD.openDocument(str(path))
    found = {}
    for obj in varsurf_objects(doc):
        found[obj.Proxy.TYPE] = found.get(obj.Proxy.TYPE, 0) + 1
    assert found == TYPES, found
    return doc


def _allowed(obj):
    tolerance = float(obj.getPropertyByName("Tolerance")) if "Tolerance" in obj.PropertiesList else 0.0
    return max(1e-12, 1e-2 * tolerance)


def test_a_release_document_recomputes_identically_and_saves_again(native, tmp_path):
    doc = _open(RELEASE_DOCUMENT)
    try:
        saved = {o.Name: geometry(o) for o in varsurf_objects(doc)}
        shaped = [o for o in varsurf_objects(doc) if o.Proxy.TYPE in ("VarSurf::Sheet", "VarSurf::Solid",
                                                                      "VarSurf::SpaceCurve")]
        assert all(saved[o.Name][0] for o in shaped), "the file holds the shapes as saved"
        for obj in doc.Objects:
            obj.touch()
        doc.recompute()
        for obj in varsurf_objects(doc):
            assert obj.isValid(), f"{obj.Label}: {obj.getStatusString()}"
            gap = max_gap(geometry(obj), saved[obj.Name])
            assert gap <= _allowed(obj), (obj.Label, gap)
        again_path = tmp_path / "resaved.FCStd"
        doc.saveAs(str(again_path))
    finally:
        FreeCAD.closeDocument(doc.Name)
    again = _open(again_path)
    try:
        for obj in varsurf_objects(again):
            assert max_gap(geometry(obj), saved[obj.Name]) <= _allowed(obj), obj.Label
    finally:
        FreeCAD.closeDocument(again.Name)
