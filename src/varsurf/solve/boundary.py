# SPDX-License-Identifier: LGPL-2.1-or-later
"""A sheet made from curves alone, trimmed to the closed loop among its curves (as Surface Filling
bounds its face by its boundary edges), so that it ends on the curves and sews to the faces
around a hole.

The loop is found among the curves as Part chains them (Part.sortEdges, in any order and
orientation); with several closed loops, the one with the largest extent bounds the sheet (the
others are interior curves). The face is built by the same joining as a Solid's (one sheet, its
loop): its edges are the given 3D curves with their pre-images on the sheet as pcurves and
tolerances from the measured deviation, not re-approximations.
"""

from __future__ import annotations

from typing import List, Optional, Sequence

from varsurf.solve import assembly, shapes
from varsurf.solve.errors import SheetError


def closed_loop(edges: Sequence) -> Optional[List[int]]:
    """Indices (into ``edges``) of the curves forming the largest closed loop, or None."""
    if not edges:
        return None
    Part = shapes.part()
    position = {e.hashCode(): i for i, e in enumerate(edges)}
    best, extent = None, 0.0
    try:
        groups = Part.sortEdges(list(edges))
    except Exception:  # OCC refuses edges it cannot chain: no loop among them
        return None
    for group in groups:
        try:
            wire = Part.Wire(group)
        except Exception:
            continue
        if not wire.isClosed():
            continue
        size = wire.BoundBox.DiagonalLength
        ids = [position.get(e.hashCode()) for e in group]  # the same edges, maybe reversed
        if None not in ids and size > extent:
            best, extent = sorted(ids), size
    return best


def trimmed_to_loop(label: str, face, edges: Sequence, loop: Sequence[int], tolerance: float):
    """``face`` (the solved sheet) bounded by the curves ``loop`` of ``edges``: one trimmed face,
    its edges the curves themselves. SheetError when the sheet misses a loop curve by more than
    ``tolerance`` or the loop's pre-images do not close."""
    outcome = assembly.build_solid([(label, face, [edges[i] for i in loop])], tolerance)
    faces = outcome.shape.Faces
    if len(faces) != 1:
        raise SheetError(f"{label}: trimming to the loop of its curves gave {len(faces)} faces")
    return faces[0]
