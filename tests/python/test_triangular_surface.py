# SPDX-License-Identifier: LGPL-2.1-or-later
"""The TriangularSurface feature (Veltkamp & Wesselink's triangular Bezier surfaces) on FreeCAD
inputs: a coarse Mesh of a handle (genus 1) and a Part Box's faces become smooth closed G1 solids
through their vertices, written exactly as Bezier faces, sewn, checked by OCCT's full check and
through STEP; an open mesh read from an STL file; rigid motion; saving, reopening, undo and the
recorded command; bad meshes named with the object in error and the document intact."""

import math

import FreeCAD
import Mesh
import Part
import pytest

import varsurf
from scenes import reopened
from triangle_grids import grid_points, grid_triangles
from triangular_surfaces import torus_mesh  # noqa: F401  (examples/: a coarse handle mesh)
from varsurf.solve import triangular

V = FreeCAD.Vector


def add_mesh(doc, points, triangles, name="Handle"):
    obj = doc.addObject("Mesh::Feature", name)
    # Facet by facet: Mesh.addFacets((points, indices)) drops a non-manifold mesh's facets.
    obj.Mesh = Mesh.Mesh([[V(*points[i]) for i in t] for t in triangles])
    doc.recompute()
    return obj


def vertices_on(shape, points, tolerance):
    return max(shape.distToShape(Part.Vertex(V(*p)))[0] for p in points) <= tolerance


def test_a_coarse_handle_becomes_a_smooth_closed_g1_solid_that_survives_step(doc, native, tmp_path):
    from step_check import assert_reads_back

    points, triangles = torus_mesh()
    mesh = add_mesh(doc, points, triangles)
    surface = varsurf.make_triangular_surface(mesh, degree=4)
    doc.recompute()
    assert surface.isValid(), surface.getStatusString()
    assert surface.Closed and surface.Shape.ShapeType == "Solid"
    assert surface.PatchCount == 96 and surface.FaceCount == 3 * 96 == len(surface.Shape.Faces)
    assert surface.WorstAngle < 0.01 and surface.OverruledEdges == 0 and not surface.SingularVertices
    # Every seam of the B-rep (between patches and inside each) is tangent to rounding.
    assert surface.SeamAngle < 1e-6
    assert vertices_on(surface.Shape, points, 1e-6)
    surface.Shape.check(True)
    # A smooth handle: its volume lies between the inscribed mesh's and the exact torus's.
    torus = Part.makeTorus(20.0, 7.0)
    assert mesh.Mesh.Volume < surface.Shape.Volume < 1.1 * torus.Volume
    path = tmp_path / "handle.step"
    varsurf.export_step(surface, str(path))
    assert_reads_back(surface.Shape, path, native)
    name = surface.Name
    volume = surface.Shape.Volume
    with reopened(doc, tmp_path / "handle.FCStd") as again:
        copy = again.getObject(name)
        assert copy.Closed and len(copy.Shape.Faces) == 288
        copy.touch()
        again.recompute()
        assert copy.isValid(), copy.getStatusString()
        assert copy.Shape.Volume == pytest.approx(volume, rel=1e-9)


def test_a_part_box_says_where_g1_fails_and_a_higher_degree_meets_it(doc):
    """A Part Box's faces (12 triangles, corners of valence 3 to 6) as the mesh: cubic and quartic
    patches cannot meet the linear G1 conditions there (the status names the edges); sextic
    patches meet them and make a valid rounded solid through the corners."""
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 30.0, 20.0, 10.0
    doc.recompute()
    surface = varsurf.make_triangular_surface(box, degree=3)
    doc.recompute()
    assert surface.isValid(), surface.getStatusString()
    assert surface.Closed and surface.PatchCount == 12
    assert surface.OverruledEdges > 0 and surface.WorstAngle > 1.0
    assert "is not G1" in surface.Status
    surface.Degree = 6
    doc.recompute()
    assert surface.WorstAngle < 0.01 and surface.OverruledEdges == 0 and not surface.SingularVertices
    assert "is not G1" not in surface.Status
    corners = [(v.Point.x, v.Point.y, v.Point.z) for v in box.Shape.Vertexes]
    assert vertices_on(surface.Shape, corners, 1e-6)
    surface.Shape.check(True)
    # Rounded through the corners: it holds the box's centre and is no box.
    assert surface.Shape.isInside(V(15, 10, 5), 1e-6, True)
    assert not math.isclose(surface.Shape.Volume, 6000.0, rel_tol=1e-2)


def test_an_open_mesh_read_from_stl_gives_an_open_g1_shell(doc, tmp_path):
    """A height field over a grid, written to STL and read back as the user imports one."""
    n = 4
    points = [(10.0 * i, 10.0 * j, 3.0 * math.sin(i) * math.cos(j)) for j in range(n + 1) for i in range(n + 1)]
    triangles = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            triangles += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    mesh = Mesh.Mesh()
    mesh.addFacets(([V(*p) for p in points], triangles))
    path = tmp_path / "terrain.stl"
    mesh.write(str(path))
    imported = doc.addObject("Mesh::Feature", "Terrain")
    imported.Mesh = Mesh.Mesh(str(path))
    doc.recompute()
    surface = varsurf.make_triangular_surface(imported)
    doc.recompute()
    assert surface.isValid(), surface.getStatusString()
    assert not surface.Closed and surface.Shape.ShapeType == "Shell"
    # The border vertices' weights come from the mesh's angles there; every edge meets G1.
    assert surface.WorstAngle < 0.01 and surface.SeamAngle < 0.01 and surface.OverruledEdges == 0
    assert vertices_on(surface.Shape, points, 1e-5)
    surface.Shape.check(True)


def test_rigid_motion_moves_the_surface_rigidly():
    points, triangles = torus_mesh(6, 5)
    base = triangular.solve(points, triangles, triangular.Settings(degree=3), export=False)
    turn = FreeCAD.Placement(V(100.0, -40.0, 7.0), FreeCAD.Rotation(V(0.3, -0.5, 0.8), 71.0))
    moved_points = [tuple(turn.multVec(V(*p))) for p in points]
    moved = triangular.solve(moved_points, triangles, triangular.Settings(degree=3), export=False)
    for a, b in zip(base.patches, moved.patches):
        for p, q in zip(a.points, b.points):
            assert (turn.multVec(V(*p)) - V(*q)).Length < 1e-7


def test_the_command_is_one_undoable_step_and_its_macro_replays(doc):
    points, triangles = torus_mesh(6, 4)
    mesh = add_mesh(doc, points, triangles)
    lines, namespace = [], {"App": FreeCAD}

    def run(line):
        lines.append(line)
        exec(line, namespace)

    surface = varsurf.run_triangular_command([type("Sel", (), {"Object": mesh})()], do_command=run)
    assert surface is not None and surface.isValid(), surface.getStatusString()
    assert any("make_triangular_surface" in line for line in lines)
    count = len(doc.Objects)
    doc.undo()
    assert len(doc.Objects) == count - 1
    doc.redo()
    assert len(doc.Objects) == count
    # The recorded lines, replayed in a fresh document with the same mesh, make the same surface.
    other = FreeCAD.newDocument("Replay")
    try:
        add_mesh(other, points, triangles)
        replay = {"App": FreeCAD}
        for line in lines:
            exec(line.replace(repr(doc.Name), repr(other.Name)), replay)
        again = [o for o in other.Objects if varsurf.is_triangular_surface(o)][0]
        assert again.Shape.Volume == pytest.approx(surface.Shape.Volume, rel=1e-9)
    finally:
        FreeCAD.closeDocument(other.Name)


def test_a_non_manifold_mesh_is_named_and_the_document_stays_intact(doc, console_errors):
    points = [(0, 0, 0), (10, 0, 0), (0, 10, 0), (0, -10, 0), (0, 0, 10)]
    mesh = add_mesh(doc, points, [(0, 1, 2), (1, 0, 3), (0, 1, 4)], "Fin")
    box = doc.addObject("Part::Box", "Box")
    surface = varsurf.make_triangular_surface(mesh)
    doc.recompute()
    assert not surface.isValid()
    status = surface.getStatusString()
    assert "edge (0, 1) is shared by more than two triangles" in status and status.count("\n") == 0
    assert "split the mesh" in status
    assert box.isValid() and math.isclose(box.Shape.Volume, 1000.0)
    assert mesh.Mesh.CountFacets == 3


def test_a_pinched_vertex_and_an_unknown_solver_are_refused(doc):
    points = [(0, 0, 0), (10, 0, 0), (10, 10, 0), (-10, 0, 0), (-10, -10, 0)]
    mesh = add_mesh(doc, points, [(0, 1, 2), (0, 3, 4)], "Bowtie")
    surface = varsurf.make_triangular_surface(mesh)
    doc.recompute()
    assert not surface.isValid()
    assert "vertex 0 joins separate fans" in surface.getStatusString()
    with pytest.raises(triangular.SheetError, match="Solver must be one of"):
        triangular.solve(points, [(0, 1, 2)], triangular.Settings(solver="LU"))


def test_a_loop_triangulation_fills_an_n_sided_region():
    for sides in (3, 5, 6, 9):
        loop = [(10 * math.cos(2 * math.pi * k / sides), 10 * math.sin(2 * math.pi * k / sides),
                 2 * math.sin(3 * math.pi * k / sides)) for k in range(sides)]
        points, triangles = triangular.loop_triangulation(loop, rings=2)
        assert points[:sides] == [tuple(p) for p in loop]
        assert len(triangles) == 3 * sides
        outcome = triangular.solve(points, triangles, triangular.Settings(degree=4))
        assert not outcome.closed and outcome.report.worst_angle < 0.01, sides
    with pytest.raises(triangular.SheetError, match="at least 3 points"):
        triangular.loop_triangulation([(0, 0, 0), (1, 0, 0)])


def test_point_and_normal_constraints_shape_the_surface_exactly(doc):
    """The paper's Fig. 1 on a FreeCAD Mesh: a hexagonal fan pulled up at a point of one triangle
    and given a tilted normal at another; both met exactly (to rounding), G1 kept, undoable."""
    ring = [(20 * math.cos(k * math.pi / 3), 20 * math.sin(k * math.pi / 3), 0.0) for k in range(6)]
    points = [(0.0, 0.0, 0.0)] + ring
    triangles = [(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)]
    mesh = add_mesh(doc, points, triangles, "Hexagon")
    at = (0.5, 0.25, 0.25)
    pulled = V(*[0.5 * points[0][i] + 0.25 * points[1][i] + 0.25 * points[2][i] for i in range(3)]) + V(0, 0, 6)
    tilt = V(0.4, 0.0, 1.0)
    surface = varsurf.make_triangular_surface(mesh, degree=4, constraints=[
        ("Point", 0, at, tuple(pulled)), ("Normal", 3, (1 / 3, 1 / 3, 1 / 3), (0, 0, 0), tuple(tilt))])
    doc.recompute()
    assert surface.isValid(), surface.getStatusString()
    assert surface.ConstraintResidual < 1e-9
    assert surface.Shape.distToShape(Part.Vertex(pulled))[0] < 1e-6
    patch = surface.Proxy.outcome.patches[3]
    centre = V(*patch.evaluate([1 / 3, 1 / 3, 1 / 3]))
    face = min(surface.Shape.Faces, key=lambda f: f.distToShape(Part.Vertex(centre))[0])
    u, v = face.Surface.parameter(centre)
    assert face.normalAt(u, v).getAngle(tilt) < 1e-6 or face.normalAt(u, v).getAngle(-tilt) < 1e-6
    assert surface.WorstAngle < 0.01
    surface.ConstraintTriangles = [0]  # one entry for two constraints
    doc.recompute()
    assert not surface.isValid()
    assert "ConstraintTriangles has 1 entries for 2 ConstraintKinds" in surface.getStatusString()


def test_operators_pull_the_surface_and_a_shape_attractor_reaches_a_part(doc):
    """Veltkamp & Wesselink's operators on a FreeCAD Mesh: a point attractor above a flat hexagon
    lifts its middle; a ShapeAttractor onto a Part Plane above pulls the surface toward it as the
    plane attractor through the same plane does (a plane is its own closest-point model); bad
    operator lists are named."""
    ring = [(20 * math.cos(k * math.pi / 3), 20 * math.sin(k * math.pi / 3), 0.0) for k in range(6)]
    mesh = add_mesh(doc, [(0.0, 0.0, 0.0)] + ring, [(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)], "Flat")
    plane = doc.addObject("Part::Plane", "Lid")
    plane.Length = plane.Width = 100.0
    plane.Placement.Base = V(-50, -50, 4)
    doc.recompute()
    pulled = varsurf.make_triangular_surface(mesh, degree=4, operators=[
        ("PointAttractor", [], (0, 0, 10), (0, 0, 1), 2.0)])
    onto = varsurf.make_triangular_surface(mesh, degree=4, operators=[
        ("ShapeAttractor", [0, 1, 2], (0, 0, 0), (0, 0, 1), 3.0, plane)])
    planar = varsurf.make_triangular_surface(mesh, degree=4, operators=[
        ("PlaneAttractor", [0, 1, 2], (0, 0, 4), (0, 0, 1), 3.0)])
    doc.recompute()
    for surface in (pulled, onto, planar):
        assert surface.isValid(), surface.getStatusString()
    middle = V(*pulled.Proxy.outcome.patches[0].evaluate([0.4, 0.3, 0.3]))
    assert middle.z > 0.5
    a = onto.Proxy.outcome.patches[1].evaluate([1 / 3, 1 / 3, 1 / 3])
    b = planar.Proxy.outcome.patches[1].evaluate([1 / 3, 1 / 3, 1 / 3])
    assert a[2] > 0.5 and max(abs(x - y) for x, y in zip(a, b)) < 1e-6
    assert onto.Proxy.outcome.report.operator_iterations >= 1
    onto.OperatorTargets = []
    doc.recompute()
    assert not onto.isValid()
    assert "OperatorTargets has 0 shapes for 1 ShapeAttractors" in onto.getStatusString()


def test_a_curve_through_mesh_vertices_is_carried_by_the_patch_edges(doc):
    """Their Fig. 2 with the mesh drawn along the curve: an arc (a Part edge) through the middle
    row of a grid mesh's vertices; the mesh edges between them carry it, so the surface contains
    it (to the interpolation of each piece by a quartic). With the vertices at even steps of the
    arc's parameter the pieces meet with equal tangents and the surface is G1 across it; at
    uneven steps the tangents' lengths jump at the vertices, the linear G1 conditions cannot hold
    there, and the report names those edges."""
    arc = doc.addObject("Part::Feature", "Arc")
    arc.Shape = Part.Arc(V(0, 20, 0), V(20, 20, 8), V(40, 20, 0)).toShape()
    doc.recompute()
    edge = arc.Shape.Edges[0]
    first, last = edge.FirstParameter, edge.LastParameter
    n = 4

    def grid(steps):
        points = grid_points(n, 10.0)
        for i, t in enumerate(steps):  # the middle row on the arc
            points[2 * (n + 1) + i] = tuple(edge.valueAt(first + t * (last - first)))
        return points, grid_triangles(n)

    surfaces = []
    for name, steps in (("Even", [0, 0.25, 0.5, 0.75, 1]), ("Uneven", [0, 0.15, 0.5, 0.8, 1])):
        surface = varsurf.make_triangular_surface(add_mesh(doc, *grid(steps), name), degree=4)
        surface.Curves = [(arc, ["Edge1"])]
        surfaces.append(surface)
    doc.recompute()
    for surface in surfaces:
        assert surface.isValid(), surface.getStatusString()
        worst = max(surface.Shape.distToShape(Part.Vertex(edge.valueAt(first + (last - first) * s / 50.0)))[0]
                    for s in range(51))
        assert worst < 1e-4, worst
    even, uneven = surfaces
    assert even.WorstAngle < 0.01 and even.OverruledEdges == 0
    assert uneven.WorstAngle > 0.01 and uneven.OverruledEdges > 0 and "is not G1" in uneven.Status
    # The mesh drawn through the curve is not split.
    assert even.SplitTriangles == 0 and even.PatchCount == 32
    # A curve that starts off the mesh is named.
    stray = doc.addObject("Part::Feature", "Stray")
    stray.Shape = Part.LineSegment(V(-30, 5, 0), V(20, 5, 0)).toShape()
    even.Curves = [(stray, ["Edge1"])]
    doc.recompute()
    assert not even.isValid()
    assert "curve Stray.Edge1 starts outside the mesh" in even.getStatusString()
    even.Curves = [(stray, ["Edge7"])]
    doc.recompute()
    assert not even.isValid()
    assert "curve Stray.Edge7 does not exist" in even.getStatusString()
    # Repaired, whole again; the mesh and the curve untouched.
    even.Curves = [(arc, ["Edge1"])]
    doc.recompute()
    assert even.isValid() and even.WorstAngle < 0.01
    assert stray.Shape.isValid() and len(even.Source.Mesh.Facets) == 32


def jittered_grid(n=6, cell=10.0, jitter=0.2):
    """A grid_points/grid_triangles grid, its inner points moved by up to `jitter` of a cell."""
    return grid_points(n, cell, lambda i, j: (jitter * cell * math.sin(7.1 * i + 3.3 * j),
                                              jitter * cell * math.cos(5.7 * i - 2.9 * j))), grid_triangles(n)


def profile_sketch(doc, joined=True):
    """A sketch lifted 3 mm over the grid: a line, an arc and a B-spline, end to end (the arc
    tangent to the line, the spline leaving the arc at 6.5 degrees) or apart."""
    import Sketcher  # noqa: F401  (registers the sketch type)

    sketch = doc.addObject("Sketcher::SketchObject", "Profile" if joined else "Apart")
    sketch.Placement = FreeCAD.Placement(V(0, 0, 3), FreeCAD.Rotation())
    spline = Part.BSplineCurve()
    if joined:
        sketch.addGeometry(Part.LineSegment(V(8, 13, 0), V(25, 13, 0)))
        sketch.addGeometry(Part.ArcOfCircle(Part.Circle(V(25, 21, 0), V(0, 0, 1), 8), -math.pi / 2, 0.0))
        spline.interpolate([V(33, 21, 0), V(36, 33, 0), V(44, 41, 0), V(52, 47, 0)])
    else:
        sketch.addGeometry(Part.LineSegment(V(8, 8, 0), V(50, 12, 0)))
        sketch.addGeometry(Part.ArcOfCircle(Part.Circle(V(22, 32, 0), V(0, 0, 1), 8), 0.3, 2.5))
        spline.interpolate([V(36, 22, 0), V(40, 33, 0), V(46, 41, 0), V(52, 52, 0)])
    sketch.addGeometry(spline)
    doc.recompute()
    return sketch


def contains(surface, edge, within):
    first, last = edge.FirstParameter, edge.LastParameter
    return max(surface.Shape.distToShape(Part.Vertex(edge.valueAt(first + (last - first) * s / 40.0)))[0]
               for s in range(41)) <= within


def test_a_sketch_arc_across_the_mesh_is_carried_and_survives_step(doc, native, tmp_path):
    """Their Fig. 3 with a FreeCAD sketch's arc lifted over a flat mesh, crossing triangles
    anywhere: the triangles it crosses are split, the surface contains it (within CurveFit, a
    millionth of the mesh), is G1 to 1e-4 degrees, passes OCCT's full check and survives STEP."""
    from step_check import assert_reads_back

    mesh = add_mesh(doc, *jittered_grid(), "Grid")
    sketch = profile_sketch(doc, joined=False)
    surface = varsurf.make_triangular_surface(mesh, degree=5)
    surface.Curves = [(sketch, ["Edge2"])]
    doc.recompute()
    assert surface.isValid(), surface.getStatusString()
    assert surface.SplitTriangles > 0 and surface.PatchCount > 72 and not surface.FoldedPatches
    assert surface.SelfIntersections == 0
    size = mesh.Mesh.BoundBox.DiagonalLength
    assert surface.CurveFit <= 1e-6 * size
    assert contains(surface, sketch.Shape.Edges[1], surface.CurveFit + 1e-6 * size)
    assert surface.WorstAngle < 1e-4
    path = tmp_path / "arc.step"
    varsurf.export_step(surface, str(path))
    assert_reads_back(surface.Shape, path, native)
    # The mesh's own border vertices are still interpolated.
    assert vertices_on(surface.Shape, [p for p in jittered_grid()[0] if p[0] in (0.0, 60.0)], 1e-6)


def test_a_sketch_of_lines_arcs_and_splines_is_carried_and_its_folds_named(doc):
    """A whole sketch as Curves (a line, an arc and a B-spline): every edge is contained within
    CurveFit. Where the split leaves crowded, high-valence vertices (here, where the curves meet)
    the fair surface can fold inside a patch or overlap itself: OCCT's full check runs after the
    split and Status says what it finds (a known limit); the patches turned over inside are named
    in FoldedPatches."""
    mesh = add_mesh(doc, *jittered_grid(), "Grid")
    size = mesh.Mesh.BoundBox.DiagonalLength
    for joined in (True, False):
        sketch = profile_sketch(doc, joined)
        surface = varsurf.make_triangular_surface(mesh, degree=5)
        surface.Curves = [sketch]  # the whole sketch: every edge
        doc.recompute()
        assert surface.isValid(), surface.getStatusString()
        assert surface.SplitTriangles > 0 and surface.CurveFit <= 1e-5 * size
        for edge in sketch.Shape.Edges:
            assert contains(surface, edge, surface.CurveFit + 1e-6 * size)
        try:
            surface.Shape.check(True)
            faults = 0
        except ValueError as fault:
            faults = str(fault).count("SelfIntersect")
        assert surface.SelfIntersections == faults
        assert (f"OCCT's check finds {faults} self-intersections" in surface.Status) == (faults > 0)
        if surface.FoldedPatches:
            assert "fold (the surface turns over inside them)" in surface.Status


def test_a_constraint_on_a_split_triangle_follows_it(doc):
    """A point constraint on a source triangle that a curve splits stays where it was put."""
    points, triangles = jittered_grid()
    mesh = add_mesh(doc, points, triangles, "Grid")
    arc = doc.addObject("Part::Feature", "Arc")
    arc.Shape = Part.Arc(V(12, 14, 0), V(30, 26, 5), V(48, 44, 0)).toShape()
    doc.recompute()
    # The triangle under the arc's middle, and a point on it raised 4 mm.
    middle = V(30, 26, 0)
    index = min(range(len(triangles)), key=lambda k: (sum((V(*points[c]) for c in triangles[k]), V())
                                                      * (1.0 / 3.0) - middle).Length)
    corner = [V(*points[c]) for c in triangles[index]]
    target = (corner[0] * 0.6 + corner[1] * 0.2 + corner[2] * 0.2) + V(0, 0, 4)
    surface = varsurf.make_triangular_surface(mesh, degree=5, constraints=[
        ("Point", index, (0.6, 0.2, 0.2), tuple(target))])
    surface.Curves = [(arc, ["Edge1"])]
    doc.recompute()
    assert surface.isValid(), surface.getStatusString()
    assert surface.SplitTriangles > 0 and surface.ConstraintResidual < 1e-6
    assert surface.Shape.distToShape(Part.Vertex(target))[0] < 1e-6
