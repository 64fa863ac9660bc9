# SPDX-License-Identifier: LGPL-2.1-or-later
"""Catmull-Clark limit surfaces of control meshes, without a document: the core's subdivision
(OpenSubdiv) of points and faces, its finest level's quads drawn through the limit points."""

from __future__ import annotations

from typing import List, Sequence, Tuple

from varsurf.solve.errors import SheetError
from varsurf.solve.native import native

Point = Tuple[float, float, float]


Crease = Tuple[Tuple[int, int], float]


def limit_triangles(points: Sequence[Point], faces: Sequence[Sequence[int]], levels: int,
                    creases: Sequence[Crease] = ()) -> Tuple[List[Point], List[Tuple[int, int, int]]]:
    """The limit surface after `levels` refinements as triangles: the finest level's faces (quads
    after one refinement) split along a diagonal, their corners moved to the limit surface.
    SheetError names what is wrong with a bad mesh."""
    nat = native()
    try:
        result = nat.subdivide(nat.SubdivisionMesh([list(map(float, p)) for p in points],
                                                   [list(map(int, f)) for f in faces], list(creases)), int(levels))
    except nat.InvalidInput as error:
        raise SheetError(f"the control mesh cannot be subdivided: {error}") from error
    limit = [tuple(float(c) for c in row) for row in result.limit_points]
    triangles = []
    for face in result.levels[-1].faces:
        triangles += [(face[0], face[k], face[k + 1]) for k in range(1, len(face) - 1)]
    return limit, triangles
