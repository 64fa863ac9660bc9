"""Curves that cross: a sheet through them meets them without throwing its poles.

Two arcs crossing at one point and height over a flat face (the boundary held) once put poles
260 mm below a 6 mm dome in the Exact, CG and Automatic modes while the curves were met to
0.007 mm: the rows of the two arcs near the crossing and at the arcs' steep ends (53 degrees
where the short arc meets the face) ask for slightly different things, and fitting their
difference was only possible by throwing poles. Heights are measured on the B-rep surface and
curve distances with OCCT's ``distToShape``, not by the solver.

How far below the base a fair sheet may go: a thin plate without tension continues an arc's
steep end below the face before the held boundary brings it back. The same scene solved on a
128-span space (twice the finest the solve picks) undershoots 0.68 arc heights without tension
and 0.11 with Stretch 1; the coarser spaces the solve stops at undershoot more (down to 1.56 and
0.44 arc heights). The bounds below (1.75 and 0.5 arc heights) leave that room; the defect went
20 to 40 arc heights below.
"""

import FreeCAD
import Part
import pytest

from varsurf import model

V = FreeCAD.Vector
MODES = ("Automatic", "Exact", "Penalty", "CG", "TSVD", "MTSVD")
HEIGHT = 6.0  # the arcs' height over the face (mm)
TOLERANCE = model.DEFAULT_TOLERANCE
UNDERSHOOT = {0.0: 1.75 * HEIGHT, 1.0: 0.5 * HEIGHT}  # see the module's docstring


def base_face():
    return Part.makePlane(120, 90, V(-60, -45, 0))


def arc(start, top, end):
    return Part.Arc(V(*start), V(*top), V(*end)).toShape()


def crossing_arcs(second_top=HEIGHT):
    """A long arc along x and a short one along y, crossing over the face's centre."""
    return [arc((-20, 0, 0), (0, 0, HEIGHT), (20, 0, 0)), arc((0, -12, 0), (0, 0, second_top), (0, 12, 0))]


def height_range(outcome):
    """Lowest and highest point of the sheet's surface on a 121 x 91 grid of its parameters."""
    surface = outcome.shape.Surface
    u0, u1, v0, v1 = outcome.shape.ParameterRange
    zs = [surface.value(u0 + (u1 - u0) * i / 120, v0 + (v1 - v0) * j / 90).z for i in range(121) for j in range(91)]
    return min(zs), max(zs)


def farthest(outcome, edge, count=30):
    """Largest distance from points along `edge` to the sheet, by OCCT."""
    return max(
        outcome.shape.distToShape(Part.Vertex(edge.valueAt(edge.FirstParameter + (edge.LastParameter - edge.FirstParameter) * k / count)))[0]
        for k in range(count + 1)
    )


def check_fair(outcome, edges, stretch, top=HEIGHT):
    low, high = height_range(outcome)
    assert low >= -UNDERSHOOT[stretch], (outcome.solve_mode, low)
    assert high <= top + TOLERANCE, (outcome.solve_mode, high)
    for name, edge in zip(outcome.curve_names, edges):
        assert farthest(outcome, edge) <= TOLERANCE, (outcome.solve_mode, name)


@pytest.mark.parametrize("stretch", (0.0, 1.0))
def test_reference_on_a_finer_space_is_within_the_bound(stretch):
    """The premise of the bounds: the scene on a 128-span space stays well within them."""
    edges = crossing_arcs()
    fine = model.solve_sheet_on_face(base_face(), edges, stretch=stretch, rest="base", solve_mode="Exact",
                                     min_spans=128, max_spans=128)
    low, high = height_range(fine)
    assert -0.75 * UNDERSHOOT[stretch] <= low <= 0.0
    assert abs(high - HEIGHT) <= TOLERANCE


@pytest.mark.parametrize("stretch", (0.0, 1.0))
@pytest.mark.parametrize("mode", MODES)
def test_crossing_arcs_are_met_without_throwing_poles(mode, stretch):
    edges = crossing_arcs()
    outcome = model.solve_sheet_on_face(base_face(), edges, stretch=stretch, rest="base", solve_mode=mode)
    check_fair(outcome, edges, stretch)
    # The poles too: the B-rep's bounding box is the control net's.
    assert outcome.shape.BoundBox.ZMin >= -2.0 * UNDERSHOOT[stretch]


@pytest.mark.parametrize("mode", ("Automatic", "Exact", "Penalty"))
def test_crossing_lines_at_one_height(mode):
    edges = [Part.makeLine(V(-20, 0, 5), V(20, 0, 5)), Part.makeLine(V(0, -12, 5), V(0, 12, 5))]
    outcome = model.solve_sheet_on_face(base_face(), edges, stretch=1.0, rest="base", solve_mode=mode)
    low, high = height_range(outcome)
    # Level lines over a flat face: the sheet rises to them and nowhere beyond or below.
    assert low >= -TOLERANCE and high <= 5.0 + TOLERANCE
    for name, edge in zip(outcome.curve_names, edges):
        assert farthest(outcome, edge) <= TOLERANCE, name


@pytest.mark.parametrize("mode", ("Automatic", "Exact", "Penalty"))
def test_three_curves_through_one_point(mode):
    edges = crossing_arcs() + [arc((-10, -10, 0), (0, 0, HEIGHT), (10, 10, 0))]
    outcome = model.solve_sheet_on_face(base_face(), edges, stretch=1.0, rest="base", solve_mode=mode)
    check_fair(outcome, edges, 1.0)


@pytest.mark.parametrize("mode", ("Automatic", "Exact", "Penalty"))
def test_heights_differing_by_less_than_the_tolerance_are_both_met(mode):
    edges = crossing_arcs(second_top=HEIGHT + 0.4 * TOLERANCE)
    outcome = model.solve_sheet_on_face(base_face(), edges, stretch=1.0, rest="base", solve_mode=mode)
    check_fair(outcome, edges, 1.0, top=HEIGHT + 0.4 * TOLERANCE)


@pytest.mark.parametrize("mode", ("Automatic", "Exact", "Penalty"))
def test_heights_differing_by_more_contradict(mode):
    edges = crossing_arcs(second_top=HEIGHT + 0.5)
    with pytest.raises(model.SheetError, match="contradict") as error:
        model.solve_sheet_on_face(base_face(), edges, stretch=1.0, rest="base", solve_mode=mode,
                                  names=["LongArc", "ShortArc"])
    assert "LongArc" in str(error.value) and "ShortArc" in str(error.value)
