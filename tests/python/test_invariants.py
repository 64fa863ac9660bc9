# SPDX-License-Identifier: LGPL-2.1-or-later
"""Invariants of the sheet over generated faces (generated_scenes.py), not only hand-picked scenes.

1. With the base face as rest shape, curves lying on the base (its own edges, pieces of them, iso
   lines, slanted curves, a curve partly along the boundary, all of them at once) leave the
   sheet where it is: the result is the base face to 1e-9 of its size (its bounding box
   diagonal), measured both ways with OCCT's distToShape from a 9 x 9 grid of points of each face
   (1e-6 of the parameter range inside its sides, where the faces' trims decide, to OCCT's
   1e-7 mm edge tolerance, whether a point is in)
   (generated_scenes.distance: the point of the other face at the same parameters and OCCT's
   point projection are further candidates, since distToShape can miss the foot point on a wavy
   B-spline face; each candidate is a true point of the face, so none can hide a deviation; a
   point within a tenth of the bound by its first candidate is not searched further).
2. Moving the whole scene rigidly (its geometry, its shapes' Locations, or its objects'
   Placements in a document) moves the result with it; reversing or reordering the curves changes
   nothing; the scene at 1 mm, 100 mm and 10 m (tolerance scaled alike) gives the scaled result.
   These compare two solves that fit curves lifted off the base (by 1 % of its size), each to
   within a quarter of the tolerance (the discrepancy principle): the two results may differ by
   the rounding of that fit, so the bound is 1e-9 of the size plus 1e-3 of the tolerance (SAME),
   both solves at the same tolerance (scaled with the scene). No spans are added (MaxSpans =
   MinSpans), so a refinement decision cannot make the difference.

Cases that fail because of a known defect are listed in KNOWN_DEFECTS (case-id patterns) and
marked as expected failures (not strict: a fix shows up as XPASS; then delete its row).
"""

from __future__ import annotations

import fnmatch
import functools

import FreeCAD
import pytest

import generated_scenes as scenes
from varsurf.solve import settings
from varsurf.solve.sheet import solve_sheet_on_face

#: The result is the base face to this fraction of its size.
ON_BASE = 1e-9
#: Two solves of one scene agree to ON_BASE x size + SAME x tolerance. (1e-3 held on an AMD EPYC;
#: on an Intel Xeon with OpenBLAS's AVX-512 kernels the same commit's rigidly moved B-spline
#: scene differed by 1.07e-3 of the tolerance when its test ran after others in the same process,
#: by less alone or with the AVX2 kernels: rounding that depends on the process's state.)
SAME = 2e-3
#: A sampled point whose first distance candidate is within this fraction of the bound needs no
#: further search (generated_scenes.distance); the measured figure stays an upper bound.
SHORT_CUT = 0.1
#: No spans are added: the base face meets every curve already (scenes 1) or at MinSpans (2).
SPANS = dict(min_spans=settings.DEFAULT_MIN_SPANS, max_spans=settings.DEFAULT_MIN_SPANS)


#: Cases failing because of a known defect: (case-id patterns (fnmatch), the defect). The first
#: match marks a case as an expected failure; delete a row when its defect is fixed. None is
#: left. Fixed: trimmed bases (defect 5), the base's own edges, closed curves across a seam and
#: curves through an apex (defect 1), curves on rational faces (defect 7), degree 5 and 7 drift
#: (defect 13), the sphere face read back from STEP (its latitude 4e-13 beyond the pole), scaled
#: cylinders, cones and fillets (the energy weighs the base's two parameters by their relative
#: speed, not as an angle against a length), curves reversed as geometry (one direction for both
#: before projection), rigid motions of B-spline faces (the pre-image fit is 100 times tighter:
#: where it splits no longer flips under rounding). The full sphere and the ring torus were
#: measurement misses (OCCT's projections near a pole and across a periodic seam), not sheet
#: defects: generated_scenes.distance now finds those feet.
KNOWN_DEFECTS = []


def case(case_id, *values):
    reasons = [reason for patterns, reason in KNOWN_DEFECTS
               if any(fnmatch.fnmatchcase(case_id, pattern) for pattern in patterns)]
    marks = [pytest.mark.xfail(strict=False, reason=reasons[0])] if reasons else []
    return pytest.param(*values, id=case_id, marks=marks)


def tolerance_of(shape) -> float:
    """The tolerance a new Sheet gets for a model of this size."""
    return settings.tolerance_for_size(scenes.size_of(shape))


def assert_curves_on(face, edges):
    """The generator's promise: each curve lies on the face (a broken generator is not a defect)."""
    size = scenes.size_of(face)
    for edge in edges:
        off = scenes.max_distance(edge.discretize(24), face)
        assert off <= ON_BASE * size, f"generated curve lies {off:.3g} mm off the face"


def solve(face, edges, tolerance=None, **options):
    """The sheet over ``face`` through ``edges``, the base as rest shape (the Sheet's default), at
    the tolerance a new Sheet gets unless one is given."""
    tolerance = tolerance_of(face) if tolerance is None else tolerance
    return solve_sheet_on_face(face, edges, rest="base", tolerance=tolerance, **SPANS, **options)


# --------------------------------------------------------------------------------------------
# 1. curves on the base return the base

IDENTITY = [case(f"on-base/{name}/{kind}", name, kind, settings.SHEET_MIN_DEGREE)
            for name in scenes.FACES for kind in scenes.CURVE_SETS]
# Higher sheet degrees on a few bases: the elevation is exact, so must the sheet be.
IDENTITY += [case(f"on-base-degree{degree}/{name}/{kind}", name, kind, degree)
             for degree, names in ((4, ("bspline-3x3",)), (5, ("plane-a", "cylinder-partial-a", "bspline-3x3")),
                                   (7, ("plane-a",)))
             for name in names for kind in ("none", "iso-grid")]


@pytest.mark.parametrize("name, kind, degree", IDENTITY)
def test_curves_on_the_base_return_the_base(name, kind, degree):
    face = scenes.face(name)
    edges = scenes.curves_on(name, kind)
    assert_curves_on(face, edges)
    size = scenes.size_of(face)
    outcome = solve(face, edges, degree=degree)
    off = scenes.hausdorff(outcome.shape, face, enough=SHORT_CUT * ON_BASE * size)
    assert off <= ON_BASE * size, f"the sheet leaves the base by {off:.3g} mm ({off / size:.2g} of its size)"


# --------------------------------------------------------------------------------------------
# 2. rigid motions, reversal, reordering, scale

#: Faces whose sheet through lifted curves is compared under motions.
MOVED_FACES = ("plane-b", "box-face6", "cylinder-partial-a", "cone-partial", "sphere-patch", "torus-patch",
               "fillet-edge", "bspline-3x3", "bspline-4x3", "step-bspline")


@functools.lru_cache(maxsize=None)
def lifted_outcome(name):
    """The face ``name``, curves lifted off it, and the sheet through them (shared by the tests
    of one face: they must not change it)."""
    face, curves = scenes.face(name), scenes.lifted_curves(name)
    return face, curves, solve(face, curves)


def assert_same(result, expected, size, tolerance, what):
    bound = ON_BASE * size + SAME * tolerance
    off = scenes.hausdorff(result, expected, enough=SHORT_CUT * bound)
    assert off <= bound, f"{what}: the results differ by {off:.3g} mm (allowed {bound:.3g} mm)"


@pytest.mark.parametrize("name, how", [case(f"rigid/{name}/{how}", name, how)
                                       for name in MOVED_FACES for how in ("geometry", "location")])
def test_rigid_motion_moves_the_result_rigidly(name, how):
    face, curves, outcome = lifted_outcome(name)
    size = scenes.size_of(face)
    motion = scenes.random_motion(name, size)
    if how == "geometry":
        move = lambda shape: scenes.moved(shape, motion.toMatrix())  # noqa: E731
    else:
        move = lambda shape: scenes.located(shape, motion)  # noqa: E731
    # The same tolerance: a new Sheet's default follows the axis-aligned bounding box, which a turn
    # changes (and its rounding to 1, 2 or 5 x 10^k can double it).
    moved = solve(move(face), [move(c) for c in curves], tolerance_of(face))
    assert_same(moved.shape, scenes.moved(outcome.shape, motion.toMatrix()), size, tolerance_of(face),
                f"moved by {motion}")


@pytest.mark.parametrize("name, how", [case(f"order/{name}/{how}", name, how) for name in MOVED_FACES
                                       for how in ("reversed-edges", "reversed-curves", "reordered")])
def test_reversing_or_reordering_curves_changes_nothing(name, how):
    face, curves, outcome = lifted_outcome(name)
    if how == "reversed-edges":  # the edges' orientation flag
        changed = [c.reversed() for c in curves]
    elif how == "reversed-curves":  # the curves' own parametrization
        changed = []
        for c in curves:
            geometry = c.Curve.toBSpline(*c.ParameterRange)
            geometry.reverse()
            changed.append(geometry.toShape())
    else:
        changed = curves[1:] + curves[:1]
    again = solve(face, changed)
    assert_same(again.shape, outcome.shape, scenes.size_of(face), tolerance_of(face), how)


#: Scenes at 1 mm, 100 mm and 10 m: the 100 mm scene is the reference. The tolerance is scaled
#: with the scene (a new Sheet's tolerance is rounded to 1, 2 or 5 x 10^k, so at a size just
#: under 100 mm it would not scale exactly).
SCALES = {"1mm": 0.01, "10m": 100.0}


def scaled_scene(name, factor):
    """The face and lifted curves of ``name`` scaled to ``factor`` x 100 mm across."""
    face = scenes.face(name)
    matrix = FreeCAD.Matrix()
    matrix.scale(100.0 * factor / scenes.size_of(face))
    return scenes.moved(face, matrix), [scenes.moved(c, matrix) for c in scenes.lifted_curves(name)]


@pytest.mark.parametrize("name, scale", [case(f"scale/{name}/{scale}", name, scale)
                                         for name in MOVED_FACES for scale in SCALES])
def test_the_scene_at_another_scale_gives_the_scaled_result(name, scale):
    factor = SCALES[scale]
    face, curves = scaled_scene(name, 1.0)
    tolerance = tolerance_of(face)
    reference = solve(face, curves, tolerance)
    big_face, big_curves = scaled_scene(name, factor)
    result = solve(big_face, big_curves, factor * tolerance)
    matrix = FreeCAD.Matrix()
    matrix.scale(factor)
    assert_same(result.shape, scenes.moved(reference.shape, matrix), scenes.size_of(big_face), factor * tolerance,
                f"at {scale}")


@pytest.mark.parametrize("name, kind, scale", [case(f"on-base-scaled/{name}/{kind}/{scale}", name, kind, scale)
                                               for name in ("plane-a", "cylinder-partial-a", "bspline-3x3",
                                                            "step-bspline")
                                               for kind in ("iso-grid", "free") for scale in SCALES])
def test_curves_on_the_base_return_the_base_at_any_scale(name, kind, scale):
    factor = SCALES[scale]
    matrix = FreeCAD.Matrix()
    matrix.scale(100.0 * factor / scenes.size_of(scenes.face(name)))
    face = scenes.moved(scenes.face(name), matrix)
    edges = [scenes.moved(e, matrix) for e in scenes.curves_on(name, kind)]
    size = scenes.size_of(face)
    off = scenes.hausdorff(solve(face, edges, 1e-4 * size).shape, face, enough=SHORT_CUT * ON_BASE * size)
    assert off <= ON_BASE * size, f"the sheet leaves the base by {off:.3g} mm ({off / size:.2g} of its size)"


# --------------------------------------------------------------------------------------------
# the same through a document: Sheet features on Part::Feature objects and their Placements


def sheet_scene(doc, name, curves):
    """A Part::Feature for the face and one per curve, and a Sheet on them (RestShape Base, the
    default; the tolerance a new Sheet gets; no added spans)."""
    import varsurf

    base = doc.addObject("Part::Feature", "Base")
    base.Shape = scenes.face(name)
    links = []
    for k, edge in enumerate(curves):
        obj = doc.addObject("Part::Feature", f"Curve{k + 1}")
        obj.Shape = edge
        links.append((obj, "Edge1"))
    sheet = varsurf.make_sheet((base, "Face1"), links, min_spans=SPANS["min_spans"], max_spans=SPANS["max_spans"])
    doc.recompute()
    assert sheet.RestShape == "Base"
    return [base] + [obj for obj, _ in links], sheet


@pytest.mark.parametrize("name", [case(f"document-on-base/{name}", name)
                                  for name in ("box-face6", "box-face1", "plane-a", "cylinder-partial-b",
                                               "bspline-4x3", "step-fillet")])
def test_a_sheet_through_its_base_faces_own_edges_is_the_base(doc, name):
    face = scenes.face(name)
    _, sheet = sheet_scene(doc, name, scenes.boundary_edges(face))
    assert sheet.isValid(), sheet.Status
    off = scenes.hausdorff(sheet.Shape.Faces[0], face, enough=SHORT_CUT * ON_BASE * scenes.size_of(face))
    assert off <= ON_BASE * scenes.size_of(face), f"{sheet.Status}; the sheet leaves the base by {off:.3g} mm"


@pytest.mark.parametrize("name", [case(f"document-placement/{name}", name)
                                  for name in ("plane-b", "cylinder-partial-a", "bspline-3x3", "fillet-edge")])
def test_moving_the_objects_moves_the_sheet_rigidly(doc, name):
    objects, sheet = sheet_scene(doc, name, scenes.lifted_curves(name))
    assert sheet.isValid(), sheet.Status
    before = sheet.Shape.Faces[0].copy()
    size = scenes.size_of(before)
    motion = scenes.random_motion(name, size)
    for obj in objects:
        obj.Placement = motion.multiply(obj.Placement)
    doc.recompute()
    assert sheet.isValid(), sheet.Status
    assert_same(sheet.Shape.Faces[0], scenes.moved(before, motion.toMatrix()), size, float(sheet.Tolerance),
                f"objects moved by {motion}")
