# SPDX-License-Identifier: LGPL-2.1-or-later
"""The subdivision-surface examples (examples/subdivision_surfaces.py, after Boier-Martin et al.)
build what they show: Fig. 8's approximate answer is narrower than the refined one for the same
pin; Fig. 9's turned inner boundary and held outer boundary are met, and its B-rep is a valid
shell whose regular seams are tangent; Fig. 7d's curve drawn on a scanned relief, lifted and
turned, lies on the result and the relief's bumps ride along. Both B-reps (merged C2 faces) read
back from STEP through check(True)."""

import FreeCAD

import Part

import varsurf
from subdivision_surfaces import fig7d, fig8, fig9

V = FreeCAD.Vector


def test_fig8_the_approximate_answer_is_narrower_than_the_refined_one(doc):
    (approximate, direct), _ = fig8(doc)
    assert approximate.isValid() and direct.isValid(), (approximate.getStatusString(), direct.getStatusString())
    assert approximate.PinResidual < 1e-6 and direct.PinResidual < 1e-6

    def raised(subd):
        return sum(p[2] > 1e-3 for p in subd.Proxy.outcome.points)

    # The refined solve spreads the same lift over more of the sheet than the masks alone do.
    assert raised(direct) > 1.5 * raised(approximate), (raised(direct), raised(approximate))


def test_fig9_the_turned_hole_meets_its_boundaries_and_its_brep_is_tangent(doc, native, tmp_path):
    from step_check import assert_reads_back

    (subd,), (brep,) = fig9(doc)
    assert subd.isValid(), subd.getStatusString()
    assert subd.PinResidual < 1e-6, subd.PinResidual
    # Both boundary loops (CurveLoops and HeldLoops), every finest vertex on them.
    assert subd.BoundaryLoops == 2 and subd.CurvePins == 512
    assert brep.isValid(), brep.getStatusString()
    assert not brep.Closed and brep.Shape.isValid()
    assert brep.RegularSeamAngle < 1e-6 and brep.EndCapSeamAngle < 1.0
    # Merged faces: each end cap alone, the regular patches in few C2 faces.
    assert brep.EndCapCount < brep.FaceCount < brep.PatchCount / 50, (brep.FaceCount, brep.PatchCount)
    path = tmp_path / "fig9.step"
    varsurf.export_step(brep, str(path))
    assert_reads_back(brep.Shape, path, native)


def test_fig7d_a_curve_drawn_on_a_relief_carries_it(doc, native, tmp_path):
    from step_check import assert_reads_back

    (subd,), (brep,) = fig7d(doc)
    assert subd.isValid() and brep.isValid(), (subd.getStatusString(), brep.getStatusString())
    assert subd.CurvePins > 50 and subd.PinResidual < 1e-6
    drawn = doc.getObject("DrawnCurve").Shape.Edges[0]
    moved = [subd.CurveMotion.multVec(p) for p in drawn.discretize(40)]
    # The moved curve lies on the B-rep within the chain's distance from the curve (each point
    # measured against the faces whose boxes come within 5 mm of it).
    faces = brep.Shape.Faces

    def distance(p):
        near = []
        for f in faces:
            box = f.BoundBox
            box.enlarge(5.0)
            if box.isInside(p):
                near.append(f)
        return Part.Compound(near).distToShape(Part.Vertex(p))[0]

    # The curve, a B-spline through 48 points of the scan, lies on the bumpy surface only so far
    # (CurveDistance before the motion); the motion adds nothing to that, and the exact B-rep
    # agrees with the limit's triangles within a tenth of a finest face.
    gap = max(distance(p) for p in moved)
    assert gap <= subd.CurveDistance + 0.1 * 100.0 / 10 / 16, (gap, subd.CurveDistance)
    start = subd.Proxy.outcome.curve_start
    assert 0.0 < start and subd.CurveDistance <= start + 0.01, (subd.CurveDistance, start)
    path = tmp_path / "fig7d.step"
    varsurf.export_step(brep, str(path))
    assert_reads_back(brep.Shape, path, native)
    # The bumps ride along: the finest level's detail vectors (in their local frames) keep their
    # size and their pattern through the edit, exactly beyond four finest edges of the curve (2.5
    # mm); nearer, the surface is drawn through the curve's points, which lie up to 0.4 mm off its
    # bumps, and the details there change (all of them: 1.016 x, correlation 0.989).
    import numpy as np

    outcome = subd.Proxy.outcome
    before, after = (np.asarray(m.details[-1]) for m in (outcome.rest, outcome.edited))
    ratio = np.linalg.norm(after) / np.linalg.norm(before)
    correlation = np.corrcoef(before.ravel(), after.ravel())[0, 1]
    assert abs(ratio - 1.0) < 0.1 and correlation > 0.9, (ratio, correlation)
    vertices = np.asarray(outcome.editor.points(outcome.rest)[-1])
    curve = np.array([tuple(p) for p in drawn.discretize(2000)])
    far = np.array([np.sqrt(((curve - p) ** 2).sum(axis=1)).min() > 2.5 for p in vertices])
    assert far.sum() > 0.9 * len(far)
    ratio = np.linalg.norm(after[far]) / np.linalg.norm(before[far])
    correlation = np.corrcoef(before[far].ravel(), after[far].ravel())[0, 1]
    assert abs(ratio - 1.0) < 1e-3 and correlation > 0.999, (ratio, correlation)
