# SPDX-License-Identifier: LGPL-2.1-or-later
"""Solves report progress and can be cancelled: a cancelled recompute marks the object in error
with a clear message and changes nothing else; the next recompute solves again."""

import pytest

from varsurf.app import progress
from scenes import railed_sheet


class Canceller(progress.SolveProgress):
    """Says stop at the `after`-th question (as a user pressing Esc would)."""

    after = 2
    made = []

    def __init__(self, label):
        super().__init__(label)
        Canceller.made.append(self)

    def __call__(self):
        self.asked += 1
        return self.asked < self.after


@pytest.fixture
def cancelling():
    Canceller.made = []
    progress.factory = Canceller
    yield Canceller
    progress.factory = progress.SolveProgress


def test_a_solve_asks_and_headless_never_stops(doc, native):
    watched = []

    class Counting(progress.SolveProgress):
        def __init__(self, label):
            super().__init__(label)
            watched.append(self)

    progress.factory = Counting
    try:
        sheet = railed_sheet(doc)
        sheet.SolveMode = "Penalty"
        doc.recompute()
    finally:
        progress.factory = progress.SolveProgress
    assert sheet.isValid(), sheet.getStatusString()
    assert watched and watched[-1].asked > 1 and not watched[-1].cancelled
    assert watched[-1].indicator is None  # no GUI: nothing shown


def test_a_cancelled_sheet_is_in_error_and_solves_again(doc, native, cancelling):
    progress.factory = progress.SolveProgress
    sheet = railed_sheet(doc)
    base = sheet.Base[0]
    progress.factory = Canceller  # the refinement level asks first, then the penalty steps (C++)
    sheet.SolveMode = "Penalty"
    doc.recompute()
    assert not sheet.isValid() and "cancelled" in sheet.Status, sheet.Status
    assert Canceller.made[-1].asked == Canceller.after
    assert base.isValid() and not base.Shape.isNull()  # the rest of the document is untouched
    progress.factory = progress.SolveProgress
    sheet.touch()
    doc.recompute()
    assert sheet.isValid(), sheet.getStatusString()


def test_a_cancelled_joint_solve_leaves_the_solid_in_error(doc, native, cancelling):

    import hinge_pair

    progress.factory = progress.SolveProgress
    solid = hinge_pair.build(doc, 120.0)
    assert solid.isValid()
    area = solid.Shape.Area
    Canceller.after = 1  # the first question: before the joint solve's first hinge iteration
    progress.factory = Canceller
    solid.touch()
    doc.recompute()
    Canceller.after = 2
    assert not solid.isValid() and "cancelled" in solid.getStatusString(), solid.getStatusString()
    progress.factory = progress.SolveProgress
    solid.touch()
    doc.recompute()
    assert solid.isValid() and abs(solid.Shape.Area - area) < 1e-9 * area
