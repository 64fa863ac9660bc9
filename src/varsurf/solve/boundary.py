# SPDX-License-Identifier: LGPL-2.1-or-later
"""A sheet made from curves alone, trimmed to the closed loop among its curves (as Surface Filling
bounds its face by its boundary edges), so that it ends on the curves and sews to the faces
around a hole.

The loop is found among the curves by their ends (within the sheet's tolerance, in any order and
orientation); with several closed loops, the one with the largest extent bounds the sheet (the
others are interior curves). The face is built by the same joining as a Solid's (one sheet, its
loop): its edges are the given 3D curves with their pre-images on the sheet as pcurves and
tolerances from the measured deviation, not re-approximations.
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence

from varsurf.solve import assembly
from varsurf.solve.errors import SheetError


#: An open chain whose two free ends are closer than this fraction of its extent was meant as a
#: loop: its gap is reported instead of leaving the sheet untrimmed without a word.
NEAR_LOOP = 0.1


def _chains(edges, tolerance):
    """The edges grouped by ends that meet (within ``tolerance``): [(indices, free ends, branches)]
    where free ends are (point, index) of ends that meet no other end and branches counts ends
    met by more than one other."""
    ends = [(i, v.Point) for i, e in enumerate(edges) for v in (e.Vertexes[0], e.Vertexes[-1])]
    parent = list(range(len(edges)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    partners = []
    for k, (i, p) in enumerate(ends):
        met = [j for m, (j, q) in enumerate(ends) if m != k and (p - q).Length <= tolerance]
        partners.append(met)
        for j in met:
            parent[root(i)] = root(j)
    groups = {}
    for i in range(len(edges)):
        groups.setdefault(root(i), []).append(i)
    chains = []
    for members in groups.values():
        free = [(p, i) for k, (i, p) in enumerate(ends) if i in members and not partners[k]]
        branches = sum(1 for k, (i, _p) in enumerate(ends) if i in members and len(partners[k]) > 1)
        chains.append((sorted(members), free, branches))
    return chains


def _extent(edges, members):
    box = edges[members[0]].BoundBox
    for i in members[1:]:
        box.add(edges[i].BoundBox)
    return box.DiagonalLength


def _point(p):
    return f"({p.x:.4g}, {p.y:.4g}, {p.z:.4g})"


def closed_loop(edges: Sequence, names: Sequence[str], tolerance: float) -> Optional[List[int]]:
    """Indices (into ``edges``) of the curves forming the largest closed loop (ends meeting within
    ``tolerance``, any order and orientation), or None. SheetError, naming the curves and the
    place, for a chain that nearly closes (a gap beyond the tolerance) or a loop that crosses
    itself."""
    best, extent = None, 0.0
    for members, free, branches in _chains(edges, tolerance):
        size = _extent(edges, members)
        listed = ", ".join(names[i] for i in members)
        if len(free) == 2 and len(members) > 1:
            gap = (free[0][0] - free[1][0]).Length
            if gap <= NEAR_LOOP * size:
                raise SheetError(
                    f"the curves {listed} nearly close a loop but leave a gap of {gap:.3g} mm between "
                    f"{_point(free[0][0])} and {_point(free[1][0])} (more than the Tolerance {tolerance:.3g} mm): "
                    "close the loop, or set the Sheet's Trim to None")
        if free or branches or size <= extent:
            continue
        _refuse_crossing(edges, names, members, tolerance)
        best, extent = members, size
    return best


def _refuse_crossing(edges, names, members, tolerance):
    """SheetError where two curves of a loop that do not follow each other meet."""
    def touching(i, j):
        return any((v.Point - w.Point).Length <= tolerance for v in edges[i].Vertexes for w in edges[j].Vertexes)

    for k, i in enumerate(members):
        for j in members[k + 1:]:
            if touching(i, j):
                continue
            distance, pairs, _info = edges[i].distToShape(edges[j])
            if distance <= tolerance:
                raise SheetError(f"the loop of {', '.join(names[m] for m in members)} crosses itself at "
                                 f"{_point(pairs[0][0])}, where {names[i]} meets {names[j]}: a sheet cannot be "
                                 "bounded by it; untangle the loop, or set the Sheet's Trim to None")


def loop_for(edges, names, settings, has_base: bool):
    """The loop (indices into ``edges``) that bounds the sheet under ``settings.trim``, or None."""
    if settings.trim == "None" or (settings.trim == "Automatic" and has_base):
        return None
    loop = closed_loop(edges, names, settings.tolerance)
    if loop is None and settings.trim == "Loop":
        raise SheetError("Trim is Loop, but no closed loop is among the curves: give the sheet curves that "
                         "close one (a closed sketch), or set Trim to Automatic")
    return loop


#: Points per loop curve of the kept region's polygon: its area differs from the curved loop's by
#: O(1/n^2) of the loop's curvature, far below what the energy's shape responds to.
KEPT_SAMPLES = 48


def kept_polygon(preimages: Sequence, samples: int = KEPT_SAMPLES) -> List[List[float]]:
    """The (u, v) polygon the loop's pre-images (native 2D curves, in any order and orientation)
    enclose: the region of the sheet its trim keeps, where its energy acts. Each curve is sampled
    and chained to the polygon's end it starts or ends nearest."""
    runs = []
    for pre in preimages:
        t0, t1 = pre.first(), pre.last()
        runs.append([[float(x) for x in pre.evaluate(t0 + (t1 - t0) * k / samples)] for k in range(samples + 1)])
    polygon = runs.pop(0)
    while runs:
        end = polygon[-1]
        gaps = [(min(math.dist(end, r[0]), math.dist(end, r[-1])), k) for k, r in enumerate(runs)]
        _gap, k = min(gaps)
        run = runs.pop(k)
        if math.dist(end, run[-1]) < math.dist(end, run[0]):
            run.reverse()
        polygon.extend(run[1:])
    return polygon[:-1]  # the last point closes on the first


def trimmed_to_loop(label: str, face, edges: Sequence, loop: Sequence[int], tolerance: float):
    """``face`` (the solved sheet) bounded by the curves ``loop`` of ``edges``: one trimmed face,
    its edges the curves themselves. SheetError when the sheet misses a loop curve by more than
    ``tolerance`` or the loop's pre-images do not close."""
    outcome = assembly.build_solid([(label, face, [edges[i] for i in loop])], tolerance)
    faces = outcome.shape.Faces
    if len(faces) != 1:
        raise SheetError(f"{label}: trimming to the loop of its curves gave {len(faces)} faces")
    return faces[0]
