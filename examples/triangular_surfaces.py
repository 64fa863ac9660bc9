#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""VarSurf example: triangular Bezier surfaces over triangle meshes, after Veltkamp & Wesselink.

    /usr/bin/python3 examples/triangular_surfaces.py [OUT_DIR [FIGURE...]]   (default: out/triangular)

- fig1: point and normal constraints (their Fig. 1): a flat hexagonal fan of six triangles pulled up
  at a point of one triangle and given a tilted normal at another; both met exactly, G1 kept.
- fig8: external energy operators (their Fig. 8): a flat square of 32 triangles shaped only by
  operators: a point attractor raises a hump, a line attractor a ridge along one side, a repeller
  pushes a dent, a director tilts a corner's normals.
- handle: a closed genus-1 model from a coarse mesh of 48 triangles (a handle drawn as a triangle
  mesh) to a smooth closed G1 solid through its vertices.
- hole5, hole6: a five- and a six-sided hole in a wavy B-spline face filled by a triangular surface:
  the hole's border sampled and triangulated (two rings and a fan), the surface through the border
  at five points a side and tangent to the face around it there (point and normal constraints),
  the gap and the angle to the face measured along the whole border.

Each figure writes figN.FCStd, figN.step and figN.png (the FreeCAD GUI under Xvfb, when present)
into OUT_DIR and prints what it measured.
"""

import math
import sys

import freecad_env  # noqa: E402,F401  (FreeCAD and VarSurf on the path)

import FreeCAD  # noqa: E402
import Mesh  # noqa: E402
import Part  # noqa: E402

import varsurf  # noqa: E402
from varsurf.solve import triangular  # noqa: E402
from figures import run_figures  # noqa: E402

V = FreeCAD.Vector


def add_mesh(doc, name, points, triangles):
    obj = doc.addObject("Mesh::Feature", name)
    obj.Mesh = Mesh.Mesh([[V(*points[i]) for i in t] for t in triangles])
    return obj


def fig1(doc):
    ring = [(20 * math.cos(k * math.pi / 3), 20 * math.sin(k * math.pi / 3), 0.0) for k in range(6)]
    points = [(0.0, 0.0, 0.0)] + ring
    mesh = add_mesh(doc, "Hexagon", points, [(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)])
    pulled = [0.5 * points[0][i] + 0.25 * points[1][i] + 0.25 * points[2][i] for i in range(3)]
    pulled[2] += 6.0
    surface = varsurf.make_triangular_surface(mesh, degree=4, constraints=[
        ("Point", 0, (0.5, 0.25, 0.25), tuple(pulled)),
        ("Normal", 3, (1 / 3, 1 / 3, 1 / 3), (0, 0, 0), (0.4, 0.0, 1.0))])
    doc.recompute()
    return [surface], [surface], [f"fig1: constraint residual {surface.ConstraintResidual:.1e}"]


def fig8(doc):
    n = 4
    points = [(15.0 * i, 15.0 * j, 0.0) for j in range(n + 1) for i in range(n + 1)]
    triangles = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            triangles += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    mesh = add_mesh(doc, "Square", points, triangles)
    # Triangles by cell (i, j): 2 (j n + i) and 2 (j n + i) + 1.
    cells = lambda pairs: [2 * (j * n + i) + k for i, j in pairs for k in (0, 1)]  # noqa: E731
    # Sculpting: the energy is of the displacement from the flat square, whose vertices are free
    # control points here; its four corners are held by point constraints, the operators move
    # the rest.
    corners = [(0, (1, 0, 0), points[0]), (2 * (n - 1) + 0, (0, 1, 0), points[n]),
               (2 * (n * n - 1) + 0, (0, 0, 1), points[-1]), (2 * (n * (n - 1)) + 1, (0, 0, 1), points[n * (n + 1)])]
    surface = varsurf.make_triangular_surface(
        mesh, degree=4, constraints=[("Point", t, at, p) for t, at, p in corners], operators=[
            ("PointAttractor", cells([(1, 1), (1, 2), (2, 1), (2, 2)]), (30, 30, 25), (0, 0, 1), 0.05),
            ("LineAttractor", cells([(i, 3) for i in range(4)]), (0, 60, 10), (1, 0, 0), 0.05),
            ("Repeller", cells([(3, 0)]), (52, 8, -4), (0, 0, 1), 0.2),
            ("Director", cells([(0, 0)]), (0, 0, 0), (-0.6, -0.6, 1.0), 0.2)])
    surface.InterpolateVertices = False
    surface.RestShape = True
    surface.Stretch = 1.0
    doc.recompute()
    report = surface.Proxy.outcome.report
    return [surface], [surface], [f"fig8: {report.operator_iterations} Gauss-Newton steps for the repeller; "
                                  f"patches meet within {report.worst_angle:.1e}°"]


def torus_mesh(nu=8, nv=6, big=20.0, small=7.0):
    points, triangles = [], []
    for i in range(nu):
        for j in range(nv):
            u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            points.append(((big + small * math.cos(v)) * math.cos(u), (big + small * math.cos(v)) * math.sin(u),
                           small * math.sin(v)))
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = i * nv + (j + 1) % nv, ((i + 1) % nu) * nv + (j + 1) % nv
            triangles += [(a, b, d), (a, d, c)]
    return points, triangles


def handle(doc):
    mesh = add_mesh(doc, "HandleMesh", *torus_mesh())
    surface = varsurf.make_triangular_surface(mesh, degree=4)
    doc.recompute()
    return [surface], [surface], [f"handle: mesh volume {mesh.Mesh.Volume:.0f}, solid {surface.Shape.Volume:.0f} mm^3"]


def wavy_face(half=60.0):
    """A bicubic B-spline face over [-half, half]^2 with a few millimetres of waves."""
    n = 8
    xs = [-half + 2 * half * k / (n - 1) for k in range(n)]
    height = lambda x, y: 5.0 * math.sin(x / 22.0) * math.cos(y / 27.0) + 0.002 * x * y  # noqa: E731
    surface = Part.BSplineSurface()
    surface.interpolate([[V(x, y, height(x, y)) for y in xs] for x in xs])
    return surface.toShape()


def border_samples(face, per_side):
    """The hole's border (the face's inner wire) as points in order: each edge's end and
    `per_side - 1` points between, and for every pair of neighbours the edge and the two
    parameters they sit at (to place points between them on the border itself)."""
    wire = [w for w in face.Wires if not w.isSame(face.OuterWire)][0]
    points, pieces = [], []
    for edge in wire.OrderedEdges:
        first, last = edge.ParameterRange
        params = [first + (last - first) * k / per_side for k in range(per_side + 1)]
        if edge.Orientation == "Reversed":
            params.reverse()
        for a, b in zip(params[:-1], params[1:]):
            points.append(tuple(edge.valueAt(a)))
            pieces.append((edge, a, b))
    return points, pieces


def hole(doc, sides):
    host = wavy_face()
    turns = [2 * math.pi * k / sides + 0.3 for k in range(sides + 1)]
    prism = Part.makePolygon([V(25 * math.cos(a), 25 * math.sin(a), -20) for a in turns])
    cut = host.cut(Part.Face(prism).extrude(V(0, 0, 40))).Faces[0]
    around = doc.addObject("Part::Feature", "FaceAround")
    around.Shape = cut
    loop, pieces = border_samples(cut, 2)
    points, triangles = triangular.loop_triangulation(loop, rings=2)
    mesh = add_mesh(doc, "HoleMesh", points, triangles)
    mesh.Visibility = False
    constraints = []
    count = len(loop)
    for k, (edge, a, b) in enumerate(pieces):
        # Triangle 2k is (k, k + 1, inner k + 1): its corners 0 and 1 run along the border piece.
        for t in (0.25, 0.5, 0.75):
            p = edge.valueAt(a + t * (b - a))
            u, v = cut.Surface.parameter(p)
            constraints.append(("Point", 2 * k, (1 - t, t, 0.0), tuple(p)))
            constraints.append(("Normal", 2 * k, (1 - t, t, 0.0), (0, 0, 0), tuple(cut.normalAt(u, v))))
    assert len(pieces) == count
    surface = varsurf.make_triangular_surface(mesh, degree=5, constraints=constraints, name=f"Fill{sides}")
    doc.recompute()
    gap, angle = border_fit(surface, cut, pieces)
    return [surface], [surface, around], [f"hole{sides}: {len(triangles)} patches; along the border: gap "
                                          f"{gap:.1e} mm, angle to the face around {angle:.3f}°"]


def border_fit(surface, around, pieces, samples=20):
    """The largest distance from the border to the fill and angle between their normals there."""
    gap = angle = 0.0
    fill = surface.Shape
    for edge, a, b in pieces:
        for s in range(samples + 1):
            p = edge.valueAt(a + (b - a) * s / samples)
            dist, pairs, info = fill.distToShape(Part.Vertex(p))
            gap = max(gap, dist)
            kind, index = info[0][0], info[0][1]
            # The nearest point may lie on an edge or a vertex of the fill: take a face there.
            face = fill.Faces[index] if kind == "Face" else fill.ancestorsOfType(
                fill.Edges[index] if kind == "Edge" else fill.Vertexes[index], Part.Face)[0]
            u, v = face.Surface.parameter(pairs[0][0])
            hu, hv = around.Surface.parameter(p)
            turn = face.normalAt(u, v).getAngle(around.normalAt(hu, hv))
            angle = max(angle, math.degrees(min(turn, math.pi - turn)))
    return gap, angle


FIGURES = {"fig1": fig1, "fig8": fig8, "handle": handle, "hole5": lambda doc: hole(doc, 5),
           "hole6": lambda doc: hole(doc, 6)}


def _build_report(stem, doc):
    surfaces, to_step, extra = FIGURES[stem](doc)
    lines = [f"{stem} {s.Label}: {s.Status if s.isValid() else s.getStatusString()}" for s in surfaces] + extra
    return surfaces, to_step, lines


def main(out_dir="out/triangular", *only):
    """Every figure, or those named after OUT_DIR (e.g. fig1 handle)."""
    return run_figures(FIGURES, out_dir, only, _build_report)


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
