# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Sheet's properties in FreeCAD's property view: it sorts groups (and the properties in each)
by name, so the group names decide what a user sees first. After FreeCAD's own Base (Label,
Placement): what users set most (base, curves, tolerance; the energy), the results and solver
settings, and the anisotropic weights last. Files written with the old groups are regrouped when
opened."""

import FreeCAD

from scenes import railed_sheet

#: The groups in the order the property view shows them, and where the most used properties are.
ORDER = ["Base", "Constraints", "Energy", "Result", "Solver", "Weight tensors"]
PLACES = {"Base": "Constraints", "Curves": "Constraints", "Tolerance": "Constraints", "Trim": "Constraints",
          "Bend": "Energy", "Stretch": "Energy", "Pressure": "Energy", "RestShape": "Energy",
          "MaxDeviations": "Result", "Status": "Result", "SolveMode": "Solver", "Degree": "Solver",
          "StretchTensor": "Weight tensors", "BendTensor": "Weight tensors"}


def _groups(obj):
    return sorted({obj.getGroupOfProperty(name) or "Base" for name in obj.PropertiesList})


def test_groups_put_the_common_properties_first(doc, native):
    sheet = railed_sheet(doc)
    assert _groups(sheet) == ORDER
    assert {name: sheet.getGroupOfProperty(name) for name in PLACES} == PLACES


def test_a_file_with_the_old_groups_is_regrouped_when_opened(doc, native, tmp_path):
    sheet = railed_sheet(doc)
    for name in ("Base", "Tolerance", "Bend"):  # as files written before the groups changed
        sheet.setGroupOfProperty(name, "Sheet")
    sheet.setGroupOfProperty("BendTensor", "Anisotropy")
    path = str(tmp_path / "old_groups.FCStd")
    doc.saveAs(path)
    again = FreeCAD.openDocument(path)
    try:
        reopened = again.getObject(sheet.Name)
        assert _groups(reopened) == ORDER
        assert {name: reopened.getGroupOfProperty(name) for name in PLACES} == PLACES
    finally:
        FreeCAD.closeDocument(again.Name)
