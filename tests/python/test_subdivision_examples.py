# SPDX-License-Identifier: LGPL-2.1-or-later
"""The subdivision-surface examples (examples/subdivision_surfaces.py, after Boier-Martin et al.)
build what they show: Fig. 8's approximate answer is narrower than the refined one for the same
pin; Fig. 9's turned inner boundary and held outer boundary are met, and its B-rep is a valid
shell whose regular seams are tangent."""

import FreeCAD

from subdivision_surfaces import fig8, fig9

V = FreeCAD.Vector


def test_fig8_the_approximate_answer_is_narrower_than_the_refined_one(doc):
    (approximate, direct), _ = fig8(doc)
    assert approximate.isValid() and direct.isValid(), (approximate.getStatusString(), direct.getStatusString())
    assert approximate.PinResidual < 1e-6 and direct.PinResidual < 1e-6

    def raised(subd):
        return sum(p[2] > 1e-3 for p in subd.Proxy.outcome.points)

    # The refined solve spreads the same lift over more of the sheet than the masks alone do.
    assert raised(direct) > 1.5 * raised(approximate), (raised(direct), raised(approximate))


def test_fig9_the_turned_hole_meets_its_boundaries_and_its_brep_is_tangent(doc):
    (subd,), (brep,) = fig9(doc)
    assert subd.isValid(), subd.getStatusString()
    assert subd.PinResidual < 1e-6, subd.PinResidual
    assert len(subd.PinVertices) > 100  # both boundary loops, every finest vertex on them
    assert brep.isValid(), brep.getStatusString()
    assert not brep.Closed and brep.Shape.isValid()
    assert brep.RegularSeamAngle < 1e-6 and brep.EndCapSeamAngle < 1.0
