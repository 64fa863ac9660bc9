# SPDX-License-Identifier: LGPL-2.1-or-later
"""The VarSurf_Sheet command's selection rules (the code its Activated runs, headless)."""

import pytest

import varsurf
from varsurf.app import actions, macro, make, references
from varsurf.app import selection as selecting
from scenes import Sel, add_face, add_line_sketch, curved_face


@pytest.fixture
def scene(doc):
    surface = add_face(doc, curved_face())
    sketch = add_line_sketch(doc, "Sketch", 12.0, (20, 20), (80, 60))
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    return doc, surface, sketch, box


def test_face_and_edges_give_make_sheet_arguments(scene):
    doc, surface, sketch, box = scene
    base, curves = selecting.selection_to_sheet_args([Sel(surface, "Face1"), Sel(sketch, "Edge1")])
    assert base == (surface, "Face1")
    assert curves == [(sketch, ("Edge1",))]


def test_whole_objects_count_as_their_face_or_their_edges(scene):
    doc, surface, sketch, box = scene
    base, curves = selecting.selection_to_sheet_args([Sel(surface), Sel(sketch)])
    assert base == (surface, "Face1")
    assert curves == [(sketch, ("Edge1",))]


def test_face_alone_is_enough(scene):
    doc, surface, sketch, box = scene
    base, curves = selecting.selection_to_sheet_args([Sel(surface, "Face1")])
    assert base == (surface, "Face1") and curves == []


def test_edges_of_one_object_are_merged(scene):
    doc, surface, sketch, box = scene
    base, curves = selecting.selection_to_sheet_args(
        [Sel(box, "Face6"), Sel(box, "Edge1", "Edge2"), Sel(box, "Edge1", "Edge3")]
    )
    assert base == (box, "Face6")
    assert curves == [(box, ("Edge1", "Edge2", "Edge3"))]


BAD = {
    "nothing": (lambda s: [], "Nothing is selected"),
    "no face": (lambda s: [Sel(s[2], "Edge1")], "No face is selected"),
    "two faces": (
        lambda s: [Sel(s[1], "Face1"), Sel(s[3], "Face2"), Sel(s[2], "Edge1")],
        "2 faces are selected (Surface:Face1, Box:Face2)",
    ),
    "a vertex": (
        lambda s: [Sel(s[1], "Face1"), Sel(s[2], "Vertex1")],
        "Sketch:Vertex1 is a vertex",
    ),
    "a solid as a whole": (lambda s: [Sel(s[3])], "Box has 6 faces"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_selection_is_explained_and_creates_nothing(scene, case, console_errors):
    doc, surface, sketch, box = scene
    make_selection, expected = BAD[case]
    selection = make_selection(scene)
    with pytest.raises(ValueError) as info:
        selecting.selection_to_sheet_args(selection)
    assert expected in str(info.value)
    assert "Select exactly one face" in str(info.value)  # says what to do
    assert selecting.selection_problem(selection) == str(info.value)  # IsActive is False

    names_before = [o.Name for o in doc.Objects]
    shown = []
    result = actions.run_sheet_command(selection, on_error=shown.append)
    assert result is None
    assert [o.Name for o in doc.Objects] == names_before
    assert shown == [str(info.value)]
    assert expected in console_errors()  # the report view got it
    assert not doc.UndoNames or actions.TRANSACTION_CREATE not in doc.UndoNames


def test_command_lines_are_a_replayable_macro(scene):
    doc, surface, sketch, box = scene
    lines = macro.sheet_command_lines((surface, "Face1"), [(sketch, ("Edge1",))])
    assert lines[0] == "import varsurf"
    assert lines[1] == (
        "_sheet = varsurf.make_sheet((App.getDocument('VarSurfTest').getObject('Surface'), "
        "'Face1'), [(App.getDocument('VarSurfTest').getObject('Sketch'), ('Edge1',))])"
    )
    assert lines[2] == "App.getDocument('VarSurfTest').recompute()"
    assert varsurf.sheet_command_lines is macro.sheet_command_lines


def test_make_sheet_rejects_malformed_references(scene):
    doc, surface, sketch, box = scene
    with pytest.raises(ValueError, match="exactly one face"):
        make.make_sheet((surface, "Edge1"), [])
    with pytest.raises(ValueError, match="is not an edge"):
        make.make_sheet((surface, "Face1"), [(sketch, "Vertex1")])
    assert not [o for o in doc.Objects if references.is_sheet(o)]
