# SPDX-License-Identifier: LGPL-2.1-or-later
"""Catmull-Clark control meshes and capture targets from FreeCAD inputs: a Mesh (its triangles), a
Part shape (its faces' vertex loops as a cage: a box, a cage of planar faces), or a VarSurf sheet
(its pole net). App side only."""

from __future__ import annotations

import FreeCAD
import Mesh
import Part

from varsurf.solve import subdivision
from varsurf.solve.errors import SheetError


def _label(source):
    return getattr(source, "Label", type(source).__name__)


def _is_varsurf_sheet(source) -> bool:
    kind = getattr(getattr(source, "Proxy", None), "Type", "") or ""
    shape = getattr(source, "Shape", None)
    return (str(kind).startswith("VarSurf::") and isinstance(shape, Part.Shape) and len(shape.Faces) == 1
            and isinstance(shape.Faces[0].Surface, Part.BSplineSurface))


def _pole_net(face):
    """(points, quads) of a B-spline face's poles, turned with the face; a periodic direction
    wraps around."""
    surface = face.Surface
    poles = surface.getPoles()
    nu, nv = len(poles), len(poles[0])
    wrap_u, wrap_v = surface.isUPeriodic(), surface.isVPeriodic()
    points = [(p.x, p.y, p.z) for row in poles for p in row]
    faces = []
    for i in range(nu if wrap_u else nu - 1):
        for j in range(nv if wrap_v else nv - 1):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            quad = [a, b, ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv]
            faces.append(quad[::-1] if face.Orientation == "Reversed" else quad)
    return points, faces


def control_mesh(source):
    """(points, faces) of a Mesh.Mesh, a Part.Shape, a VarSurf sheet (its pole net), or a document
    object holding a mesh or shape."""
    mesh = getattr(source, "Mesh", None)
    if isinstance(source, Mesh.Mesh) or isinstance(mesh, Mesh.Mesh):
        m = source if isinstance(source, Mesh.Mesh) else mesh
        points, facets = m.Topology
        return [(p.x, p.y, p.z) for p in points], [list(f) for f in facets]
    if _is_varsurf_sheet(source):
        return _pole_net(source.Shape.Faces[0])
    shape = source if isinstance(source, Part.Shape) else getattr(source, "Shape", None)
    if not isinstance(shape, Part.Shape) or not shape.Faces:
        raise SheetError(f"{_label(source)} has no mesh and no faces: give a Mesh or a shape with faces")
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


def target_triangles(source, tolerance: float = 0.0):
    """(points, triangles) of a capture target: a Mesh's facets, or a shape's faces tessellated
    within `tolerance` (0: 5e-4 of its size; a ten-thousandth took 4.3 s on a sphere, this 0.06 s)."""
    mesh = getattr(source, "Mesh", None)
    if isinstance(source, Mesh.Mesh) or isinstance(mesh, Mesh.Mesh):
        m = source if isinstance(source, Mesh.Mesh) else mesh
        points, facets = m.Topology
        return [(p.x, p.y, p.z) for p in points], [tuple(f) for f in facets]
    shape = source if isinstance(source, Part.Shape) else getattr(source, "Shape", None)
    if not isinstance(shape, Part.Shape) or not shape.Faces:
        raise SheetError(f"{_label(source)} has no mesh and no faces to capture detail from: give a Mesh or a "
                         "shape with faces as Target")
    box = shape.BoundBox
    tolerance = float(tolerance) or 5e-4 * box.DiagonalLength
    # Tessellated at a size of 100: OCC's mesher did not return in minutes on a 1.3 mm sphere at
    # 1.1e-3 mm (measured), and at one size the triangles, and so the capture, scale with the model.
    factor = _MESH_SIZE / max(box.DiagonalLength, 1e-300)
    centre = box.Center
    copy = shape.copy()
    copy.scale(factor, centre)
    points, triangles = copy.tessellate(tolerance * factor)
    back = [centre + (p - centre) * (1.0 / factor) for p in points]
    return [(p.x, p.y, p.z) for p in back], [tuple(t) for t in triangles]


_MESH_SIZE = 100.0


def mesh_of(points, triangles) -> Mesh.Mesh:
    """A Mesh of points (rows of three floats) and triangles (index triples)."""
    m = Mesh.Mesh()
    m.addFacets(([FreeCAD.Vector(*map(float, p)) for p in points], [tuple(map(int, t)) for t in triangles]))
    return m


def limit_mesh(source, levels: int = 3) -> Mesh.Mesh:
    """The Catmull-Clark limit surface of `source` (see control_mesh) after `levels` refinements,
    as a Mesh."""
    points, faces = control_mesh(source)
    limit, triangles = subdivision.limit_triangles(points, faces, levels)
    return mesh_of(limit, triangles)
