# SPDX-License-Identifier: LGPL-2.1-or-later
"""Catmull-Clark limit meshes of FreeCAD inputs (OpenSubdiv through the core): a Part Box's faces as
the cage give a closed, consistently oriented limit surface inside the box whose points at the
box's corners are Catmull-Clark's closed-form limits; a coarse Mesh of a sphere gives a surface
near the sphere; bad meshes name what is wrong."""

import FreeCAD
import Part
import pytest

from varsurf.app import subdivision
from varsurf.solve import subdivision as solve_subdivision
from varsurf.solve.errors import SheetError

V = FreeCAD.Vector


def test_a_box_cage_gives_a_closed_limit_surface_with_catmull_clarks_corners(doc):
    box = doc.addObject("Part::Box", "Cage")
    box.Length, box.Width, box.Height = 10.0, 20.0, 30.0
    box.Placement = FreeCAD.Placement(V(5, -3, 2), FreeCAD.Rotation(V(1, 2, 3), 40))
    doc.recompute()
    mesh = subdivision.limit_mesh(box, 3)
    limit, _triangles = solve_subdivision.limit_triangles(*subdivision.control_mesh(box), 3)
    assert mesh.CountFacets == 6 * 4 ** 3 * 2
    assert mesh.isSolid() and not mesh.hasNonManifolds() and not mesh.hasSelfIntersections()
    assert 0.0 < mesh.Volume < box.Shape.Volume  # consistently outward, and inside the cage
    bound = box.Shape.BoundBox
    assert all(bound.isInside(p.Vector) for p in mesh.Points)
    # Valence 3 at a box corner: (9 v + 4 sum(edge neighbours) + sum(face diagonals)) / 24.
    for v in box.Shape.Vertexes:
        edge = [e.Vertexes[1].Point if e.Vertexes[0].isSame(v) else e.Vertexes[0].Point
                for e in box.Shape.Edges if any(w.isSame(v) for w in e.Vertexes)]
        across = [w.Point for f in box.Shape.Faces if any(x.isSame(v) for x in f.Vertexes)
                  for w in f.Vertexes if not w.isSame(v) and all((w.Point - p).Length > 1e-9 for p in edge)]
        assert len(edge) == 3 and len(across) == 3
        want = (v.Point * 9 + sum(edge, V()) * 4 + sum(across, V())) * (1 / 24)
        assert min((V(*p) - want).Length for p in limit) < 1e-12
        assert min((p.Vector - want).Length for p in mesh.Points) < 1e-5  # a Mesh keeps floats


def test_a_mesh_sphere_gives_a_surface_near_it(doc):
    """A coarse triangle mesh of a sphere (MeshPart, as a user meshes a shape) as the control mesh."""
    import MeshPart

    feature = doc.addObject("Mesh::Feature", "Coarse")
    feature.Mesh = MeshPart.meshFromShape(Part.makeSphere(10.0), LinearDeflection=2.0)
    coarse = min(p.Vector.Length for p in feature.Mesh.Points)
    limit = subdivision.limit_mesh(feature, 2)
    radii = [p.Vector.Length for p in limit.Points]
    assert limit.isSolid() and limit.Volume > 0.0
    assert 0.85 * coarse < min(radii) and max(radii) < 10.0 + 1e-9  # inside the control net, near it


@pytest.mark.parametrize("faces, words", [
    ([[0, 1]], "fewer than 3 vertices"),
    ([[0, 1, 7]], "names vertex 7"),
])
def test_bad_meshes_name_the_problem(faces, words):
    with pytest.raises(SheetError, match=words):
        solve_subdivision.limit_triangles([(0, 0, 0), (1, 0, 0), (0, 1, 0)], faces, 1)


def test_a_shape_without_faces_is_refused():
    with pytest.raises(SheetError, match="no mesh and no faces"):
        subdivision.control_mesh(Part.makeLine(V(0, 0, 0), V(1, 0, 0)))
