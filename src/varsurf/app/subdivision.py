# SPDX-License-Identifier: LGPL-2.1-or-later
"""Catmull-Clark limit meshes of FreeCAD inputs: a Mesh (its triangles as the control mesh) or a
Part shape (its faces' vertex loops: a box, a cage of planar faces). App side only."""

from __future__ import annotations

import Mesh
import Part

from varsurf.solve import subdivision
from varsurf.solve.errors import SheetError


def control_mesh(source):
    """(points, faces) of a Mesh.Mesh, a Part.Shape, or a document object holding either."""
    shape = getattr(source, "Shape", None)
    mesh = getattr(source, "Mesh", None)
    if isinstance(source, Mesh.Mesh) or isinstance(mesh, Mesh.Mesh):
        m = source if isinstance(source, Mesh.Mesh) else mesh
        points, facets = m.Topology
        return [(p.x, p.y, p.z) for p in points], [list(f) for f in facets]
    shape = source if isinstance(source, Part.Shape) else shape
    if not isinstance(shape, Part.Shape) or not shape.Faces:
        raise SheetError(f"{getattr(source, 'Label', source)} has no mesh and no faces: give a Mesh or a shape "
                         "with faces")
    vertices = shape.Vertexes
    index = {v.hashCode(): k for k, v in enumerate(vertices)}
    faces = []
    for f in shape.Faces:
        loop = f.OuterWire.OrderedVertexes
        ids = [index[v.hashCode()] for v in loop]
        # Counterclockwise seen from outside: the loop turns with the face's normal.
        if len(ids) >= 3:
            a, b, c = (vertices[i].Point for i in ids[:3])
            if (b - a).cross(c - b).dot(f.normalAt(*f.Surface.parameter(a))) < 0.0:
                ids.reverse()
        faces.append(ids)
    return [(v.Point.x, v.Point.y, v.Point.z) for v in vertices], faces


def limit_mesh(source, levels: int = 3) -> Mesh.Mesh:
    """The Catmull-Clark limit surface of `source` (see control_mesh) after `levels` refinements,
    as a Mesh."""
    points, faces = control_mesh(source)
    limit, triangles = subdivision.limit_triangles(points, faces, levels)
    return Mesh.Mesh([[limit[i] for i in t] for t in triangles])
