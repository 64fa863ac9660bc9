# SPDX-License-Identifier: LGPL-2.1-or-later
"""Solve modes on a Sheet: every mode recomputes, the energy modes agree, TSVD/MTSVD publish
their L-curve, and a PreparedSheet drag through the API equals a fresh solve."""

import math

import pytest

import varsurf
from varsurf.solve import errors
from varsurf.solve.sheet import solve_sheet_on_face
from scenes import add_arc_sketch, poles_of, railed_sheet


@pytest.fixture
def sheet(doc, native):
    s = railed_sheet(doc)
    arc = add_arc_sketch(doc, "Arc", 3.0, (60.0, 40.0), 18.0, 200.0, 340.0)
    doc.recompute()
    s.Curves = list(s.Curves) + [(arc, ("Edge1",))]
    doc.recompute()
    assert s.isValid(), s.getStatusString()
    return s


def test_energy_modes_agree_and_say_what_they_did(sheet):
    doc = sheet.Document
    assert sheet.SolveMode == "Automatic" and sheet.SolveModeUsed.startswith("exact:")
    reference = poles_of(sheet)
    for mode in ("Exact", "Penalty", "PenaltyQR", "CG", "MTSVD"):
        sheet.SolveMode = mode
        doc.recompute()
        assert sheet.isValid(), (mode, sheet.getStatusString())
        assert sheet.SolveModeUsed.startswith(mode.lower().replace("qr", "")), sheet.SolveModeUsed
        assert max(sheet.MaxDeviations) <= varsurf.DEFAULT_TOLERANCE, (mode, list(sheet.MaxDeviations))
        # Exact and CG solve the same reduced system; the penalty mode stops refining once every
        # curve is within the tolerance, and MTSVD truncates where the L-curve says: both meet
        # the curves (above) with their own poles.
        if mode in ("Exact", "CG"):
            assert max(math.dist(p, q) for p, q in zip(reference, poles_of(sheet))) < 1e-6, mode


def test_tsvd_and_mtsvd_publish_the_l_curve(sheet):
    doc = sheet.Document
    for mode in ("TSVD", "MTSVD"):
        sheet.SolveMode = mode
        doc.recompute()
        assert sheet.isValid(), sheet.getStatusString()
        k = len(sheet.LCurveResiduals)
        assert k == len(sheet.LCurveNorms) > 10
        assert 1 <= sheet.LCurveCorner <= k
        assert all(a >= b * (1 - 1e-9) for a, b in zip(sheet.LCurveResiduals, sheet.LCurveResiduals[1:]))
    sheet.SolveMode = "Exact"
    doc.recompute()
    assert sheet.LCurveResiduals == [] and sheet.LCurveCorner == 0


def test_prepared_sheet_drag_equals_a_fresh_solve(native):
    nat = native
    unit = nat.BSplineSurface(space=nat.SplineSpace.uniform(1, 1, 1, 1),
                              poles=[[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]])
    flat = nat.refine_surface(unit, 12, 12, 3)  # the unit square as a bicubic 15 x 15 sheet
    problem = nat.SheetProblem()
    problem.space = flat.space
    problem.initial_poles = flat.poles
    problem.energy = nat.ThinPlateWeights.isotropic(0.1, 1.0)
    problem.fixed_poles = list(nat.boundary_pole_indices(flat.space))
    problem.points = [nat.PointConstraint(u=0.4, v=0.6, target=[0.4, 0.6, 0.2])]
    prepared = nat.PreparedSheet(problem)
    problem.points = [nat.PointConstraint(u=0.4, v=0.6, target=[0.45, 0.6, 0.3])]  # dragged
    dragged = prepared.update(problem)
    fresh = nat.solve_sheet(problem)
    assert abs(dragged.poles - fresh.poles).max() < 1e-10
    assert abs(dragged.poles - prepared.result.poles).max() > 1e-3
    problem.points = [nat.PointConstraint(u=0.5, v=0.6, target=[0.45, 0.6, 0.3])]  # re-placed
    with pytest.raises(nat.InvalidInput, match="use change"):
        prepared.update(problem)
    changed = prepared.change(problem)  # the constraint side rebuilt, the energy kept
    assert abs(changed.poles - nat.solve_sheet(problem).poles).max() < 1e-10
    problem.energy = nat.ThinPlateWeights.isotropic(1.0, 1.0)
    with pytest.raises(nat.InvalidInput, match="prepare the sheet again"):
        prepared.change(problem)


def test_prepared_sheet_change_keeps_the_penalty_factor(native):
    """A pin added in the penalty mode is solved through the earlier factorization (the report
    says so), with the fresh solve's poles; a pin taken away factors anew."""
    nat = native
    unit = nat.BSplineSurface(space=nat.SplineSpace.uniform(1, 1, 1, 1),
                              poles=[[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]])
    flat = nat.refine_surface(unit, 12, 12, 3)
    problem = nat.SheetProblem()
    problem.space = flat.space
    problem.initial_poles = flat.poles
    problem.fixed_poles = list(nat.boundary_pole_indices(flat.space))
    spots = [(0.2 + 0.12 * k, 0.3 + 0.07 * k, 0.02 * k) for k in range(6)]
    problem.points = [nat.PointConstraint(u=u, v=v, target=[u, v, z]) for u, v, z in spots]
    options = nat.SolveOptions()
    options.mode = nat.SolveMode.penalty
    options.fit_tolerance = 1e-4
    prepared = nat.PreparedSheet(problem, options)
    assert not prepared.result.report.factor_kept
    problem.points = list(problem.points) + [nat.PointConstraint(u=0.7, v=0.25, target=[0.7, 0.25, 0.1])]
    changed = prepared.change(problem)
    assert changed.report.factor_kept
    assert abs(changed.poles - nat.solve_sheet(problem, options).poles).max() < 1e-9
    assert abs(changed.poles - flat.poles).max() > 1e-2
    problem.points = list(problem.points)[1:]
    changed = prepared.change(problem)
    assert not changed.report.factor_kept
    assert abs(changed.poles - nat.solve_sheet(problem, options).poles).max() < 1e-9


def test_unknown_mode_is_refused(sheet):
    face = sheet.Base[0].Shape.Faces[0]
    with pytest.raises(errors.SheetError, match="SolveMode must be one of"):
        solve_sheet_on_face(face, [], solve_mode="Magic")
